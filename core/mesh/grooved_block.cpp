#include "mesh/grooved_block.hpp"

#include <fmt/format.h>
#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "mesh/gmsh_session.hpp"

namespace stiction::mesh {

namespace {

void check_spec(const GroovedBlockSpec& s) {
  const auto& L = s.size;
  if (!(L[0] > 0 && L[1] > 0 && L[2] > 0))
    throw Error(fmt::format("grooved-block generator: every side length must be positive (size = [{}, {}, {}])", L[0],
                            L[1], L[2]));
  if (s.grooves < 1) throw Error(fmt::format("grooved-block generator: grooves = {}: give at least one groove", s.grooves));
  if (!(s.groove_width > 0)) throw Error("grooved-block generator: groove_width must be positive");
  if (!(s.grooves * s.groove_width < L[0]))
    throw Error(fmt::format("grooved-block generator: {} grooves {} wide do not fit in lx = {} (they need "
                            "grooves x groove_width < lx, to leave strips between them)",
                            s.grooves, s.groove_width, L[0]));
  if (!(s.groove_depth > 0 && s.groove_depth < L[2]))
    throw Error(fmt::format("grooved-block generator: groove_depth = {} must lie in (0, lz = {})", s.groove_depth, L[2]));
  if (!(s.h > 0)) throw Error("grooved-block generator: the element size h must be positive");
  if (!(s.contact_size > 0 && s.contact_size <= s.h))
    throw Error(fmt::format("grooved-block generator: contact_size = {} must be positive and at most h = {}",
                            s.contact_size, s.h));
}

// Which named face a plane face of the cut box is, from its bounding box (OCC pads boxes by
// about 1e-7: compare with a looser tolerance). Gmsh's entity numbering plays no part.
std::string face_name(const GroovedBlockSpec& s, const double b[6]) {
  const auto& L = s.size;
  const double tol = 1e-6 * std::max({1.0, L[0], L[1], L[2]});
  auto flat = [&](int axis, double at) { return std::abs(b[axis] - at) < tol && std::abs(b[axis + 3] - at) < tol; };
  if (flat(2, 0)) return "strip-bottom";
  if (flat(2, s.groove_depth)) return "groove-floor";
  if (flat(2, L[2])) return "top";
  if (flat(0, 0)) return "xmin";
  if (flat(0, L[0])) return "xmax";
  if (flat(1, 0)) return "ymin";
  if (flat(1, L[1])) return "ymax";
  for (int i = 0; i < s.grooves; ++i) {
    const auto x = groove_span(s, i);
    if (flat(0, x[0])) return "groove-wall-left";
    if (flat(0, x[1])) return "groove-wall-right";
  }
  throw Error(fmt::format("grooved-block generator: a face with bounding box [{}, {}] x [{}, {}] x [{}, {}] is none of "
                          "the block's",
                          b[0], b[3], b[1], b[4], b[2], b[5]),
              ErrorKind::Internal);
}

void build_grooved_block_model(const GroovedBlockSpec& s) {
  namespace occ = gmsh::model::occ;
  const auto& L = s.size;
  const int n = s.grooves;
  // The groove boxes overhang the block in y and below z = 0: no coincident faces for the
  // boolean to resolve.
  const double margin = 0.1 * std::max({L[0], L[1], L[2]});
  gmsh::vectorpair tools;
  for (int i = 0; i < n; ++i) {
    const auto x = groove_span(s, i);
    tools.push_back({3, occ::addBox(x[0], -margin, -margin, x[1] - x[0], L[1] + 2 * margin, s.groove_depth + margin)});
  }
  gmsh::vectorpair out;
  std::vector<gmsh::vectorpair> map;
  occ::cut({{3, occ::addBox(0, 0, 0, L[0], L[1], L[2])}}, tools, out, map);
  occ::synchronize();

  gmsh::vectorpair volumes, faces, points;
  gmsh::model::getEntities(volumes, 3);
  if (volumes.size() != 1)
    throw Error(fmt::format("grooved-block generator: the cut left {} volumes (1 expected)", volumes.size()),
                ErrorKind::Internal);
  gmsh::model::addPhysicalGroup(3, {volumes[0].second}, 1);
  gmsh::model::setPhysicalName(3, 1, "body");

  // Faces by position. Expected: n + 1 strip bottoms, n of each wall and floor, one each
  // of the others (the comb-shaped faces ymin, ymax included).
  const std::vector<std::string> order{"strip-bottom", "groove-wall-left", "groove-wall-right", "groove-floor",
                                       "top", "xmin", "xmax", "ymin", "ymax"};
  std::map<std::string, std::vector<int>> groups;
  gmsh::model::getEntities(faces, 2);
  for (auto [d, t] : faces) {
    double b[6];
    gmsh::model::getBoundingBox(d, t, b[0], b[1], b[2], b[3], b[4], b[5]);
    groups[face_name(s, b)].push_back(t);
  }
  for (size_t k = 0; k < order.size(); ++k) {
    const auto& entities = groups[order[k]];
    const size_t expected = order[k] == "strip-bottom" ? n + 1 : k < 4 ? n : 1;
    if (entities.size() != expected)
      throw Error(fmt::format("grooved-block generator: {} faces named '{}' ({} expected)", entities.size(), order[k],
                              expected),
                  ErrorKind::Internal);
    const int tag = static_cast<int>(k) + 1;
    gmsh::model::addPhysicalGroup(2, entities, tag);
    gmsh::model::setPhysicalName(2, tag, order[k]);
  }

  // Size at each corner of the geometry, linear in z: contact_size on the strip bottoms
  // (the contact surface with the ground), growing up the groove walls (the self-contact
  // surfaces) to h at the top (clamped, away from any contact). Gmsh interpolates the
  // corner sizes along the edges, then over the faces and the volume.
  gmsh::model::getEntities(points, 0);
  for (auto [d, t] : points) {
    double b[6];
    gmsh::model::getBoundingBox(d, t, b[0], b[1], b[2], b[3], b[4], b[5]);
    const double z = std::clamp(0.5 * (b[2] + b[5]), 0.0, L[2]);
    gmsh::model::mesh::setSize({{d, t}}, s.contact_size + (s.h - s.contact_size) * z / L[2]);
  }
  detail::set_size_and_generate(3, s.h, s.contact_size);
}

}  // namespace

std::array<double, 2> groove_span(const GroovedBlockSpec& spec, int i) {
  const double w = spec.groove_width, strip = (spec.size[0] - spec.grooves * w) / (spec.grooves + 1);
  const double x0 = (i + 1) * strip + i * w;
  return {x0, x0 + w};
}

Mesh generate_grooved_block(const GroovedBlockSpec& spec) {
  check_spec(spec);
  return detail::with_gmsh("grooved-block generator", [&] {
    detail::gmsh_begin();
    build_grooved_block_model(spec);
    return detail::extract_current_model("generated grooved block");
  });
}

}  // namespace stiction::mesh
