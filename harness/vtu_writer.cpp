#include "vtu_writer.hpp"

#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string_view>
#include <type_traits>

#include "common/error.hpp"
#include "fem/elasticity_assembly.hpp"
#include "result_tables.hpp"
#include "vtk_binary.hpp"

namespace stiction::harness {

double von_mises(const double* s) {
  const double a = s[0] - s[4], b = s[4] - s[8], c = s[8] - s[0];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3 * (s[1] * s[1] + s[5] * s[5] + s[2] * s[2]));
}

namespace {

// Writes each DataArray either inline as ASCII text or, for the binary format, as an empty
// element pointing into the appended section that finish() writes at the end of the file.
class ArrayWriter {
public:
  ArrayWriter(fmt::ostream& out, bool binary) : out_(out), binary_(binary) {}

  // `attributes` follow type (Name, NumberOfComponents); ASCII puts `per_line` values on a line,
  // floating-point ones with `digits` significant digits.
  template <class T>
  void write(const std::string& attributes, const std::vector<T>& v, int per_line = 1, int digits = 12) {
    out_.print("<DataArray type=\"{}\"{}{}", vtk_type_name<T>(), attributes.empty() ? "" : " ", attributes);
    if (binary_) {
      out_.print(" format=\"appended\" offset=\"{}\"/>\n", appended_.add(v));
      return;
    }
    out_.print(" format=\"ascii\">\n");
    for (std::size_t i = 0; i < v.size(); ++i) {
      const char* separator = (i + 1) % per_line == 0 || i + 1 == v.size() ? "\n" : " ";
      if constexpr (std::is_floating_point_v<T>) out_.print("{:.{}g}{}", v[i], digits, separator);
      else out_.print("{}{}", static_cast<std::int64_t>(v[i]), separator);
    }
    out_.print("</DataArray>\n");
  }

  // The appended section (binary format only); call before </VTKFile>.
  void finish() {
    if (!binary_) return;
    out_.print("<AppendedData encoding=\"raw\">\n_{}\n</AppendedData>\n", std::string_view(appended_.bytes()));
  }

private:
  fmt::ostream& out_;
  bool binary_;
  VtkAppendedData appended_;
};

}  // namespace

void write_vtu(const std::string& path, const scene::Scene& scene, const std::vector<double>& u,
               const std::vector<double>& lambda, double t) {
  const fem::FieldSpace& space = *scene.space;
  const int d = space.dim(), nn = space.n_nodes(), nc = scene.mesh.n_cells(), npc = space.nodes_per_cell();
  const std::vector<double> nodal = space.nodal_values(u);
  const std::vector<double> stress = fem::cell_cauchy_stress(space, scene.problem.cell_material, u);
  const bool quad = fem::is_quadratic(space.kind());
  const std::uint8_t vtk_type = d == 2 ? (quad ? 22 : 5) : (quad ? 24 : 10);
  const bool binary = scene.output.vtu_format == scene::VtuFormat::Binary;

  std::vector<double> points(static_cast<size_t>(nn) * 3, 0.0), displacement(static_cast<size_t>(nn) * 3, 0.0);
  for (int n = 0; n < nn; ++n) {
    space.node_position(n, &points[static_cast<size_t>(n) * 3]);
    for (int c = 0; c < d; ++c) displacement[static_cast<size_t>(n) * 3 + c] = nodal[static_cast<size_t>(n) * d + c];
  }
  std::vector<std::int64_t> connectivity(static_cast<size_t>(nc) * npc), offsets(nc);
  std::vector<int> nodes(npc);
  for (int c = 0; c < nc; ++c) {
    space.cell_nodes(c, nodes.data());  // local order = VTK order (mesh::SimplexEdges)
    std::copy(nodes.begin(), nodes.end(), connectivity.begin() + static_cast<std::ptrdiff_t>(c) * npc);
    offsets[c] = static_cast<std::int64_t>(c + 1) * npc;
  }
  std::vector<double> mises(nc);
  for (int c = 0; c < nc; ++c) mises[c] = von_mises(&stress[static_cast<size_t>(c) * 9]);

  try {
    auto out = fmt::output_file(path);
    out.print("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"{}\" byte_order=\"LittleEndian\"{}{}>\n"
              "<UnstructuredGrid>\n<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
              binary ? "1.0" : "0.1", binary ? " " : "", binary ? vtk_compressed_file_attributes : "", nn, nc);
    ArrayWriter arrays(out, binary);
    out.print("<Points>\n");
    arrays.write("NumberOfComponents=\"3\"", points, 3, 10);
    out.print("</Points>\n<Cells>\n");
    arrays.write("Name=\"connectivity\"", connectivity, npc);
    arrays.write("Name=\"offsets\"", offsets);
    arrays.write("Name=\"types\"", std::vector<std::uint8_t>(nc, vtk_type));
    out.print("</Cells>\n<PointData Vectors=\"displacement\">\n");
    arrays.write("Name=\"displacement\" NumberOfComponents=\"3\"", displacement, 3);
    if (space.has_pressure()) arrays.write("Name=\"pressure\"", space.nodal_pressure(u));
    if (!scene.problem.constraints.empty() && !lambda.empty()) {
      std::vector<std::int32_t> state(nn, -1);
      std::vector<double> multiplier(static_cast<size_t>(nn) * 3, 0.0), normal(nn, 0.0);
      for (const auto& [pair, nodes] : multiplier_nodes(scene, t, u, lambda))
        for (const auto& node : nodes) {  // a slave vertex is point `vertex` (vertices come first)
          state[node.vertex] = node.state;
          normal[node.vertex] = node.normal;
          for (int c = 0; c < 3; ++c) multiplier[static_cast<size_t>(node.vertex) * 3 + c] = node.multiplier[c];
        }
      arrays.write("Name=\"contact_multiplier\" NumberOfComponents=\"3\"", multiplier, 3);
      arrays.write("Name=\"contact_pressure\"", normal);
      arrays.write("Name=\"contact_state\"", state);
    }
    out.print("</PointData>\n<CellData>\n");
    arrays.write("Name=\"cauchy_stress\" NumberOfComponents=\"9\"", stress, 9, 10);
    arrays.write("Name=\"von_mises\"", mises, 1, 10);
    arrays.write("Name=\"body_id\"", std::vector<std::int32_t>(scene.body_of_cell.begin(), scene.body_of_cell.end()));
    out.print("</CellData>\n</Piece>\n</UnstructuredGrid>\n");
    arrays.finish();
    out.print("</VTKFile>\n");
  } catch (const std::system_error& e) {
    throw Error(fmt::format("cannot write '{}': {}", path, e.what()));
  }
}

void PvdCollection::add(double time, const std::string& file) {
  entries_.emplace_back(time, file);
  try {
    auto out = fmt::output_file(path_);
    out.print("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n");
    for (const auto& [t, f] : entries_) out.print("<DataSet timestep=\"{}\" part=\"0\" file=\"{}\"/>\n", t, f);
    out.print("</Collection>\n</VTKFile>\n");
  } catch (const std::system_error& e) {
    throw Error(fmt::format("cannot write '{}': {}", path_, e.what()));
  }
}

}  // namespace stiction::harness
