#include "mesh/gmsh_io.hpp"

#include <fmt/format.h>
#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "common/error.hpp"
#include "mesh/gmsh_session.hpp"

namespace stiction::mesh {

namespace {

using detail::extract_current_model;
using detail::gmsh_begin;
using detail::set_size_and_generate;
using detail::with_gmsh;

// Makes each field's size the background mesh size (the minimum of them where several
// apply), on the entities of the boundary group it names in the current model.
void add_boundary_size_fields(int dim, const std::vector<BoundarySizeField>& fields, double h, double scale) {
  if (fields.empty()) return;
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, dim - 1);
  std::vector<double> thresholds;
  for (const BoundarySizeField& f : fields) {
    std::vector<double> entities;
    std::string names;
    for (auto [gd, gtag] : groups) {
      std::string name;
      gmsh::model::getPhysicalName(gd, gtag, name);
      names += (names.empty() ? "" : ", ") + name;
      if (name != f.boundary) continue;
      std::vector<int> tags;
      gmsh::model::getEntitiesForPhysicalGroup(gd, gtag, tags);
      entities.assign(tags.begin(), tags.end());
    }
    if (entities.empty())
      throw Error(fmt::format("size field: no boundary named '{}' (boundaries: {})", f.boundary, names));
    // Gmsh 4.8 names: FacesList (later SurfacesList), NumPointsPerCurve (later Sampling).
    const int distance = gmsh::model::mesh::field::add("Distance");
    gmsh::model::mesh::field::setNumbers(distance, dim == 2 ? "CurvesList" : "FacesList", entities);
    gmsh::model::mesh::field::setNumber(distance, "NumPointsPerCurve", 200);
    const int threshold = gmsh::model::mesh::field::add("Threshold");
    gmsh::model::mesh::field::setNumber(threshold, "InField", distance);
    gmsh::model::mesh::field::setNumber(threshold, "SizeMin", f.size * scale);
    gmsh::model::mesh::field::setNumber(threshold, "SizeMax", h);
    gmsh::model::mesh::field::setNumber(threshold, "DistMin", 0);
    gmsh::model::mesh::field::setNumber(threshold, "DistMax", f.distance);
    thresholds.push_back(threshold);
  }
  const int smallest = gmsh::model::mesh::field::add("Min");
  gmsh::model::mesh::field::setNumbers(smallest, "FieldsList", thresholds);
  gmsh::model::mesh::field::setAsBackgroundMesh(smallest);
  // The field decides inside the domain; sizes propagated from the boundary would not grade.
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
}

// Adds the OCC box/rectangle with named physical groups, tagged by bounding box position.
void build_box_model(int dim, const std::array<double, 3>& L, double h) {
  if (dim == 3)
    gmsh::model::occ::addBox(0, 0, 0, L[0], L[1], L[2]);
  else
    gmsh::model::occ::addRectangle(0, 0, 0, L[0], L[1]);
  gmsh::model::occ::synchronize();
  gmsh::vectorpair bodies, faces;
  gmsh::model::getEntities(bodies, dim);
  gmsh::model::getEntities(faces, dim - 1);
  std::vector<int> body_tags;
  for (auto [d, t] : bodies) body_tags.push_back(t);
  gmsh::model::addPhysicalGroup(dim, body_tags, 1);
  gmsh::model::setPhysicalName(dim, 1, "body");
  const char* names[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  // OCC pads bounding boxes by about 1e-7: compare with a looser tolerance.
  const double tol = 1e-6 * std::max({1.0, L[0], L[1], L[2]});
  for (int axis = 0; axis < dim; ++axis)
    for (int side = 0; side < 2; ++side) {
      std::vector<int> on_plane;
      for (auto [d, t] : faces) {
        double b[6];
        gmsh::model::getBoundingBox(d, t, b[0], b[1], b[2], b[3], b[4], b[5]);
        const double target = side ? L[axis] : 0.0;
        if (std::abs(b[axis] - target) < tol && std::abs(b[axis + 3] - target) < tol) on_plane.push_back(t);
      }
      const int tag = 2 * axis + side + 1;
      gmsh::model::addPhysicalGroup(dim - 1, on_plane, tag);
      gmsh::model::setPhysicalName(dim - 1, tag, names[tag - 1]);
    }
  set_size_and_generate(dim, h);
}

void build_polygon_model(const PolygonSpec& spec) {
  const auto& xy = spec.xy;
  const auto& names = spec.names;
  const double h = spec.h * spec.scale, thickness = spec.thickness;
  const int n = static_cast<int>(xy.size() / 2);
  std::vector<int> points, lines;
  // Point sizes grade the mesh (Gmsh interpolates them along the sides and inside).
  for (int i = 0; i < n; ++i)
    points.push_back(gmsh::model::occ::addPoint(xy[2 * i], xy[2 * i + 1], 0,
                                                spec.point_sizes.empty() ? 0.0 : spec.point_sizes[i] * spec.scale));
  for (int i = 0; i < n; ++i) {
    auto arc = spec.arc_centers.find(i);
    if (arc == spec.arc_centers.end()) {
      lines.push_back(gmsh::model::occ::addLine(points[i], points[(i + 1) % n]));
      continue;
    }
    const int centre = gmsh::model::occ::addPoint(arc->second[0], arc->second[1], 0);
    lines.push_back(gmsh::model::occ::addCircleArc(points[i], centre, points[(i + 1) % n]));
  }
  const int surface = gmsh::model::occ::addPlaneSurface({gmsh::model::occ::addCurveLoop(lines)});
  const int dim = thickness > 0 ? 3 : 2;
  std::vector<std::vector<int>> side_entities(n);
  std::vector<int> front, back, body;
  if (dim == 2) {
    gmsh::model::occ::synchronize();
    for (int i = 0; i < n; ++i) side_entities[i] = {lines[i]};
    body = {surface};
  } else {
    gmsh::vectorpair out;
    gmsh::model::occ::extrude({{2, surface}}, 0, 0, thickness, out);
    gmsh::model::occ::synchronize();
    front = {surface};
    // Lateral faces: match each to the side whose midpoint is nearest its centre of mass
    // (the order Gmsh returns them in is not part of its API).
    for (auto [d, tag] : out) {
      if (d == 3) body.push_back(tag);
      if (d != 2) continue;
      double cx, cy, cz;
      gmsh::model::occ::getCenterOfMass(d, tag, cx, cy, cz);
      if (std::abs(cz - thickness) < 1e-9 * std::max(1.0, thickness)) {
        back.push_back(tag);
        continue;
      }
      int best = 0;
      double best_d = INFINITY;
      for (int i = 0; i < n; ++i) {
        const double mx = 0.5 * (xy[2 * i] + xy[2 * ((i + 1) % n)]), my = 0.5 * (xy[2 * i + 1] + xy[2 * ((i + 1) % n) + 1]);
        const double dist = std::hypot(cx - mx, cy - my);
        if (dist < best_d) best_d = dist, best = i;
      }
      side_entities[best].push_back(tag);
    }
  }
  gmsh::model::addPhysicalGroup(dim, body, 1);
  gmsh::model::setPhysicalName(dim, 1, "body");
  int tag = 0;
  auto add_group = [&](const std::vector<int>& entities, const std::string& name) {
    if (entities.empty()) return;
    gmsh::model::addPhysicalGroup(dim - 1, entities, ++tag);
    gmsh::model::setPhysicalName(dim - 1, tag, name);
  };
  // Sides with the same name form one boundary.
  std::map<std::string, std::vector<int>> by_name;
  for (int i = 0; i < n; ++i) by_name[names[i]].insert(by_name[names[i]].end(), side_entities[i].begin(), side_entities[i].end());
  for (const auto& [name, entities] : by_name) add_group(entities, name);
  add_group(front, "front");
  add_group(back, "back");
  add_boundary_size_fields(dim, spec.size_fields, h, spec.scale);
  double h_min = h;
  for (double s : spec.point_sizes) h_min = std::min(h_min, s * spec.scale);
  for (const BoundarySizeField& f : spec.size_fields) h_min = std::min(h_min, f.size * spec.scale);
  set_size_and_generate(dim, h, h_min);
}

void build_sphere_octant_model(const SphereOctantSpec& spec) {
  namespace occ = gmsh::model::occ;
  const double R = spec.radius, h = spec.h * spec.scale, hc = spec.contact_size * spec.scale;
  gmsh::vectorpair out;
  std::vector<gmsh::vectorpair> map;
  const double side = spec.below ? -1 : 1;  // y of the ball's centre, in units of R
  occ::intersect({{3, occ::addSphere(0, side * R, 0, R)}}, {{3, occ::addBox(0, spec.below ? -R : 0, 0, R, R, R)}}, out,
                 map);
  occ::synchronize();
  std::vector<int> body;
  for (auto [d, t] : out)
    if (d == 3) body.push_back(t);
  gmsh::model::addPhysicalGroup(3, body, 1);
  gmsh::model::setPhysicalName(3, 1, "body");
  // Faces by their bounding boxes: the three planes, and the spherical rest.
  gmsh::vectorpair faces;
  gmsh::model::getEntities(faces, 2);
  std::map<std::string, std::vector<int>> groups;
  const double tol = 1e-6 * R;
  for (auto [d, t] : faces) {
    double b[6];
    gmsh::model::getBoundingBox(d, t, b[0], b[1], b[2], b[3], b[4], b[5]);
    const bool x0 = std::abs(b[0]) < tol && std::abs(b[3]) < tol, z0 = std::abs(b[2]) < tol && std::abs(b[5]) < tol;
    const bool flat = std::abs(b[1] - side * R) < tol && std::abs(b[4] - side * R) < tol;
    groups[x0 ? "symmetry-x" : z0 ? "symmetry-z" : flat ? (spec.below ? "base" : "top") : "surface"].push_back(t);
  }
  int tag = 0;
  for (const auto& [name, entities] : groups) {
    gmsh::model::addPhysicalGroup(2, entities, ++tag);
    gmsh::model::setPhysicalName(2, tag, name);
  }
  // Grading: contact_size near the pole, h from 0.6 R on.
  gmsh::vectorpair pole;
  gmsh::model::getEntitiesInBoundingBox(-tol, -tol, -tol, tol, tol, tol, pole, 0);
  if (pole.size() != 1) throw Error("sphere-octant generator: the pole is not a vertex of the geometry", ErrorKind::Internal);
  const int distance = gmsh::model::mesh::field::add("Distance");
  gmsh::model::mesh::field::setNumbers(distance, "PointsList", {static_cast<double>(pole[0].second)});
  const int threshold = gmsh::model::mesh::field::add("Threshold");
  gmsh::model::mesh::field::setNumber(threshold, "InField", distance);
  gmsh::model::mesh::field::setNumber(threshold, "SizeMin", hc);
  gmsh::model::mesh::field::setNumber(threshold, "SizeMax", h);
  gmsh::model::mesh::field::setNumber(threshold, "DistMin", spec.contact_zone);
  gmsh::model::mesh::field::setNumber(threshold, "DistMax", 0.6 * R);
  gmsh::model::mesh::field::setAsBackgroundMesh(threshold);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  set_size_and_generate(3, h, hc);
}

void check_box_args(int dim, const std::array<double, 3>& L, double h) {
  if (dim != 2 && dim != 3) throw Error(fmt::format("box generator: dimension {} (2 or 3)", dim));
  for (int k = 0; k < dim; ++k)
    if (!(L[k] > 0)) throw Error("box generator: every side length must be positive");
  if (!(h > 0)) throw Error("box generator: the target size h must be positive");
}

}  // namespace

Mesh read_msh(const std::string& path) {
  if (!std::filesystem::exists(path)) throw Error(fmt::format("mesh file '{}' not found", path));
  return with_gmsh(fmt::format("cannot read mesh '{}'", path), [&] {
    gmsh_begin();
    gmsh::open(path);
    return extract_current_model(path);
  });
}

Mesh mesh_geo(const std::string& path, double size_factor) {
  if (!std::filesystem::exists(path)) throw Error(fmt::format("geometry file '{}' not found", path));
  if (!(size_factor > 0)) throw Error("mesh_geo: the size factor must be positive", ErrorKind::Internal);
  return with_gmsh(fmt::format("cannot mesh '{}'", path), [&] {
    gmsh_begin();
    gmsh::open(path);
    gmsh::option::setNumber("Mesh.MeshSizeFactor", size_factor);
    const int dim = gmsh::model::getDimension();
    if (dim != 2 && dim != 3) throw Error(fmt::format("'{}' describes no 2D or 3D geometry", path));
    gmsh::model::mesh::generate(dim);
    detail::place_edge_midpoints_on_geometry();
    return extract_current_model(path);
  });
}

Mesh generate_box(int dim, const std::array<double, 3>& L, double h) {
  check_box_args(dim, L, h);
  return with_gmsh("box generator", [&] {
    gmsh_begin();
    build_box_model(dim, L, h);
    return extract_current_model("generated box");
  });
}

Mesh generate_polygon(const PolygonSpec& spec) {
  const auto& xy = spec.xy;
  const size_t n = xy.size() / 2;
  if (xy.size() < 6 || xy.size() % 2) throw Error("polygon generator: give at least 3 points as x, y pairs");
  if (spec.names.size() != n)
    throw Error(fmt::format("polygon generator: {} points need {} side names (side i joins point i to i+1)", n, n));
  if (!(spec.h > 0 && spec.scale > 0)) throw Error("polygon generator: the target size h must be positive");
  if (spec.thickness < 0) throw Error("polygon generator: thickness must be positive (or 0 for 2D)");
  if (!spec.point_sizes.empty() && spec.point_sizes.size() != n)
    throw Error(fmt::format("polygon generator: {} points need {} point sizes", n, n));
  for (double s : spec.point_sizes)
    if (!(s > 0 && s <= spec.h)) throw Error("polygon generator: point sizes must be positive and at most h");
  for (const BoundarySizeField& f : spec.size_fields)
    if (!(f.size > 0 && f.size <= spec.h && f.distance > 0))
      throw Error(fmt::format("polygon generator: the size field on '{}' needs 0 < size <= h and distance > 0", f.boundary));
  for (const auto& [side, c] : spec.arc_centers) {
    if (side < 0 || side >= static_cast<int>(n)) throw Error(fmt::format("polygon generator: no side {} for an arc", side));
    const size_t a = side, b = (side + 1) % n;
    const double ra = std::hypot(xy[2 * a] - c[0], xy[2 * a + 1] - c[1]), rb = std::hypot(xy[2 * b] - c[0], xy[2 * b + 1] - c[1]);
    if (!(ra > 0) || std::abs(ra - rb) > 1e-9 * ra)
      throw Error(fmt::format("polygon generator: side {} is not an arc about ({}, {}): its ends are at radii {} and {}",
                              side, c[0], c[1], ra, rb));
  }
  return with_gmsh("polygon generator", [&] {
    gmsh_begin();
    build_polygon_model(spec);
    return extract_current_model("generated polygon");
  });
}

Mesh generate_sphere_octant(const SphereOctantSpec& spec) {
  if (!(spec.radius > 0 && spec.h > 0 && spec.scale > 0))
    throw Error("sphere-octant generator: radius and h must be positive");
  if (!(spec.contact_size > 0 && spec.contact_size <= spec.h))
    throw Error("sphere-octant generator: contact_size must be positive and at most h");
  if (!(spec.contact_zone >= 0 && spec.contact_zone < 0.6 * spec.radius))
    throw Error("sphere-octant generator: contact_zone must lie in [0, 0.6 radius)");
  return with_gmsh("sphere-octant generator", [&] {
    gmsh_begin();
    build_sphere_octant_model(spec);
    return extract_current_model("generated sphere octant");
  });
}

void write_box_msh(int dim, const std::array<double, 3>& L, double h, const std::string& path, bool binary) {
  check_box_args(dim, L, h);
  with_gmsh("box generator", [&] {
    gmsh_begin();
    build_box_model(dim, L, h);
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::option::setNumber("Mesh.Binary", binary ? 1 : 0);
    gmsh::write(path);
    return 0;
  });
}

}  // namespace stiction::mesh
