#include "vtu_writer.hpp"

#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string_view>
#include <type_traits>
#include <variant>

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

// One DataArray of a piece: name, components, values, and how ASCII prints it.
struct DataArray {
  std::string name;
  int components = 1;
  std::variant<std::vector<double>, std::vector<std::int32_t>> values;
  int per_line = 1, digits = 12;
  std::string attributes() const {
    return fmt::format("Name=\"{}\"{}", name, components > 1 ? fmt::format(" NumberOfComponents=\"{}\"", components) : "");
  }
  const char* type() const {
    return std::holds_alternative<std::vector<double>>(values) ? vtk_type_name<double>() : vtk_type_name<std::int32_t>();
  }
};

// The cells of one piece with their point and cell data: the whole mesh with every node
// (process < 0), or one process's cells with the nodes they use, numbered in ascending
// order of the whole mesh's numbering.
struct Piece {
  int n_points = 0, n_cells = 0, nodes_per_cell = 0;
  std::vector<double> points;
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<std::uint8_t> types;
  std::vector<DataArray> point_data, cell_data;
};

// The piece's points: every node of the whole mesh (whole), or those its cells use, in
// ascending order; local[n] is node n's point number, -1 for a node not in the piece.
std::vector<int> piece_points(const fem::FieldSpace& space, const std::vector<int>& cells, bool whole,
                              std::vector<int>& local) {
  local.assign(space.n_nodes(), whole ? 0 : -1);
  std::vector<int> nodes(space.nodes_per_cell()), used;
  for (int c : cells) {
    space.cell_nodes(c, nodes.data());
    for (int n : nodes) local[n] = 0;
  }
  for (int n = 0; n < space.n_nodes(); ++n)
    if (local[n] == 0) local[n] = static_cast<int>(used.size()), used.push_back(n);
  return used;
}

// Displacement, pressure of mixed bodies, and with contact, at the slave vertices, the
// multiplier, its normal part and the contact state.
void add_point_data(Piece& p, const scene::SceneView& scene, fem::StateView u, const std::vector<double>& lambda, double t,
                    const std::vector<int>& used, const std::vector<int>& local) {
  const fem::FieldSpace& space = *scene.space;
  std::vector<double> displacement(static_cast<size_t>(p.n_points) * 3, 0.0);
  for (int k = 0; k < p.n_points; ++k) space.nodal_value(u, used[k], &displacement[static_cast<size_t>(k) * 3]);
  p.point_data.push_back({"displacement", 3, std::move(displacement), 3});
  if (space.has_pressure()) {
    std::vector<double> mine(p.n_points);
    for (int k = 0; k < p.n_points; ++k) mine[k] = space.nodal_pressure(u, used[k]);
    p.point_data.push_back({"pressure", 1, std::move(mine)});
  }
  if (scene.problem->constraints.empty() || lambda.empty()) return;
  std::vector<std::int32_t> state(p.n_points, -1);
  std::vector<double> multiplier(static_cast<size_t>(p.n_points) * 3, 0.0), normal(p.n_points, 0.0);
  if (p.n_points > 0) {  // a piece without points (a PVTU's declaration) reads no state
    for (const auto& [pair, slave_nodes] : multiplier_nodes(*scene.problem, t, u, lambda))
      for (const auto& node : slave_nodes) {  // a slave vertex is node `vertex` (vertices come first)
        const int k = local[node.vertex];
        if (k < 0) continue;  // in another process's piece
        state[k] = node.state;
        normal[k] = node.normal;
        for (int c = 0; c < 3; ++c) multiplier[static_cast<size_t>(k) * 3 + c] = node.multiplier[c];
      }
  }
  p.point_data.push_back({"contact_multiplier", 3, std::move(multiplier), 3});
  p.point_data.push_back({"contact_pressure", 1, std::move(normal)});
  p.point_data.push_back({"contact_state", 1, std::move(state)});
}

// Cauchy stress and von Mises at the centroids, body id, and a piece's process number.
void add_cell_data(Piece& p, const scene::SceneView& scene, fem::StateView u, const std::vector<int>& cells, int process) {
  std::vector<double> stress = fem::cell_cauchy_stress(*scene.space, scene.problem->cell_material, u, &cells);
  std::vector<double> mises(cells.size());
  std::vector<std::int32_t> body(cells.size());
  for (size_t k = 0; k < cells.size(); ++k) {
    mises[k] = von_mises(&stress[k * 9]);
    body[k] = (*scene.body_of_cell)[cells[k]];
  }
  p.cell_data.push_back({"cauchy_stress", 9, std::move(stress), 9, 10});
  p.cell_data.push_back({"von_mises", 1, std::move(mises), 1, 10});
  p.cell_data.push_back({"body_id", 1, std::move(body)});
  if (process >= 0) p.cell_data.push_back({"process", 1, std::vector<std::int32_t>(cells.size(), process)});
}

Piece build_piece(const scene::SceneView& scene, fem::StateView u, const std::vector<double>& lambda, double t,
                  const std::vector<int>& cells, int process) {
  const fem::FieldSpace& space = *scene.space;
  const int d = space.dim(), npc = space.nodes_per_cell();
  const bool quad = fem::is_quadratic(space.kind());
  Piece p;
  p.n_cells = static_cast<int>(cells.size());
  p.nodes_per_cell = npc;
  std::vector<int> local;
  const std::vector<int> used = piece_points(space, cells, process < 0, local);
  p.n_points = static_cast<int>(used.size());
  p.points.assign(used.size() * 3, 0.0);
  for (size_t k = 0; k < used.size(); ++k) space.node_position(used[k], &p.points[k * 3]);
  std::vector<int> nodes(npc);
  for (size_t k = 0; k < cells.size(); ++k) {
    space.cell_nodes(cells[k], nodes.data());  // local order = VTK order (mesh::SimplexEdges)
    for (int n : nodes) p.connectivity.push_back(local[n]);
    p.offsets.push_back(static_cast<std::int64_t>(k + 1) * npc);
  }
  p.types.assign(cells.size(), d == 2 ? (quad ? 22 : 5) : (quad ? 24 : 10));
  add_point_data(p, scene, u, lambda, t, used, local);
  add_cell_data(p, scene, u, cells, process);
  return p;
}

void write_piece(const std::string& path, const Piece& p, bool binary) {
  try {
    auto out = fmt::output_file(path);
    out.print("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"{}\" byte_order=\"LittleEndian\"{}{}>\n"
              "<UnstructuredGrid>\n<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
              binary ? "1.0" : "0.1", binary ? " " : "", binary ? vtk_compressed_file_attributes : "", p.n_points,
              p.n_cells);
    ArrayWriter arrays(out, binary);
    const auto write_data = [&](const DataArray& a) {
      std::visit([&](const auto& v) { arrays.write(a.attributes(), v, a.per_line, a.digits); }, a.values);
    };
    out.print("<Points>\n");
    arrays.write("NumberOfComponents=\"3\"", p.points, 3, 10);
    out.print("</Points>\n<Cells>\n");
    arrays.write("Name=\"connectivity\"", p.connectivity, p.nodes_per_cell);
    arrays.write("Name=\"offsets\"", p.offsets);
    arrays.write("Name=\"types\"", p.types);
    out.print("</Cells>\n<PointData Vectors=\"displacement\">\n");
    for (const auto& a : p.point_data) write_data(a);
    out.print("</PointData>\n<CellData>\n");
    for (const auto& a : p.cell_data) write_data(a);
    out.print("</CellData>\n</Piece>\n</UnstructuredGrid>\n");
    arrays.finish();
    out.print("</VTKFile>\n");
  } catch (const std::system_error& e) {
    throw Error(fmt::format("cannot write '{}': {}", path, e.what()));
  }
}

std::vector<int> all_cells(const scene::Scene& scene) {
  std::vector<int> cells(scene.mesh.n_cells());
  std::iota(cells.begin(), cells.end(), 0);
  return cells;
}

}  // namespace

void write_vtu(const std::string& path, const scene::Scene& scene, fem::StateView u,
               const std::vector<double>& lambda, double t) {
  write_piece(path, build_piece(scene, u, lambda, t, all_cells(scene), -1),
              scene.output.vtu_format == scene::VtuFormat::Binary);
}

void write_vtu_piece(const std::string& path, const scene::SceneView& scene, fem::StateView u,
                     const std::vector<double>& lambda, double t, const std::vector<int>& cells, int process) {
  write_piece(path, build_piece(scene, u, lambda, t, cells, process),
              scene.scene->output.vtu_format == scene::VtuFormat::Binary);
}

void write_pvtu(const std::string& path, const scene::SceneView& scene, const std::vector<double>& lambda,
                const std::vector<std::string>& piece_files) {
  const Piece declared = build_piece(scene, {}, lambda, 0, {}, 0);  // the pieces' arrays, without data
  const auto declare = [](const DataArray& a) {
    return fmt::format("<PDataArray type=\"{}\" {}/>\n", a.type(), a.attributes());
  };
  try {
    auto out = fmt::output_file(path);
    out.print("<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" "
              "byte_order=\"LittleEndian\">\n<PUnstructuredGrid GhostLevel=\"0\">\n"
              "<PPoints>\n<PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n</PPoints>\n"
              "<PPointData Vectors=\"displacement\">\n");
    for (const auto& a : declared.point_data) out.print("{}", declare(a));
    out.print("</PPointData>\n<PCellData>\n");
    for (const auto& a : declared.cell_data) out.print("{}", declare(a));
    out.print("</PCellData>\n");
    for (const auto& f : piece_files) out.print("<Piece Source=\"{}\"/>\n", f);
    out.print("</PUnstructuredGrid>\n</VTKFile>\n");
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
