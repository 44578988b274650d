#include "mesh/structured_tube.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "common/error.hpp"

namespace stiction::mesh {

namespace {

int max_facet_tag(const Mesh& m) {
  int largest = 0;
  for (const auto& [name, tag] : m.facet_tag_names) largest = std::max(largest, tag);
  return largest;
}

}  // namespace

Mesh structured_tube(const TubeSpec& spec) {
  if (!(spec.inner_radius > 0) || !(spec.thickness > 0) || !(spec.length > 0))
    throw Error("tube generator: inner_radius, thickness and length must be positive");
  const double span = spec.angles_degrees[1] - spec.angles_degrees[0];
  if (!(span > 0) || span > 360) throw Error("tube generator: angles must increase by at most 360 degrees");
  if (span == 360) throw Error("tube generator: a closed ring is not supported (the seam would be two faces)");
  for (int n : spec.cells)
    if (n < 1) throw Error("tube generator: cells must be positive");
  if (spec.axis < 0 || spec.axis > 2) throw Error("tube generator: axis must be x, y or z");
  const bool split = !std::isnan(spec.inner_split_degrees);
  const double split_at = (spec.inner_split_degrees - spec.angles_degrees[0]) / span;  // in the unit box
  if (split && !(split_at > 0 && split_at < 1))
    throw Error("tube generator: inner_split must lie strictly between the two angles");

  // Unit box cells in (radial, angular, axial) parameters, then the map onto the cylinders.
  Mesh m = structured_box(3, {1.0, 1.0, 1.0}, spec.cells);
  const int inner = m.facet_tag_names.at("xmin"), inner1 = split ? max_facet_tag(m) + 1 : inner;
  if (split)
    for (int f = 0; f < m.n_facets(); ++f) {
      if (m.facet_tags[f] != inner) continue;
      double angular = 0;
      for (int k = 0; k < 3; ++k) angular += m.vertex(m.facet(f)[k])[1] / 3;
      if (angular > split_at) m.facet_tags[f] = inner1;
    }
  const int e = spec.axis, a = (e + 1) % 3, b = (e + 2) % 3;
  const double theta0 = spec.angles_degrees[0] * M_PI / 180, dtheta = span * M_PI / 180;
  auto to_tube = [&](const double* unit, double* x) {
    const double r = spec.inner_radius + spec.thickness * unit[0], theta = theta0 + dtheta * unit[1],
                 s = spec.length * unit[2];
    double out[3];
    out[a] = r * std::cos(theta), out[b] = r * std::sin(theta), out[e] = s;
    for (int c = 0; c < 3; ++c) x[c] = spec.center[c] + out[c];
  };
  const std::vector<double> unit = m.coords;
  for (int v = 0; v < m.n_vertices(); ++v) to_tube(&unit[3 * static_cast<size_t>(v)], m.coords.data() + 3 * static_cast<size_t>(v));
  // Edges that cut the cylinders get their true midpoints: the image of the parameter
  // midpoint (the map is smooth, so that is on the geometry to the order P2 needs).
  for (auto [p, q] : build_edges(m).edges) {
    double mid_unit[3], mid[3];
    for (int c = 0; c < 3; ++c) mid_unit[c] = 0.5 * (unit[3 * static_cast<size_t>(p) + c] + unit[3 * static_cast<size_t>(q) + c]);
    to_tube(mid_unit, mid);
    m.set_edge_midpoint(p, q, mid);
  }
  // The map (r, theta, s) -> x has det = r (a x b = e): orientation kept; check anyway.
  for (int c = 0; c < m.n_cells(); ++c)
    if (signed_measure(m, c) <= 0) throw Error("tube generator: a cell inverted in the map", ErrorKind::Internal);
  const std::pair<const char*, const char*> renames[] = {{"xmin", "inner"}, {"xmax", "outer"}, {"ymin", "side0"},
                                                         {"ymax", "side1"}, {"zmin", "start"}, {"zmax", "end"}};
  std::map<std::string, int> names;
  for (const auto& [from, to] : renames) names[to] = m.facet_tag_names.at(from);
  if (split) {
    names.erase("inner");
    names["inner0"] = inner, names["inner1"] = inner1;
  }
  m.facet_tag_names = std::move(names);
  return m;
}

}  // namespace stiction::mesh
