#include "vtu_writer.hpp"

#include <fmt/format.h>
#include <fmt/os.h>

#include <cmath>

#include "common/error.hpp"
#include "fem/elasticity_assembly.hpp"
#include "result_tables.hpp"

namespace stiction::harness {

double von_mises(const double* s) {
  const double a = s[0] - s[4], b = s[4] - s[8], c = s[8] - s[0];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3 * (s[1] * s[1] + s[5] * s[5] + s[2] * s[2]));
}

void write_vtu(const std::string& path, const scene::Scene& scene, const std::vector<double>& u,
               const std::vector<double>& lambda, double t) {
  const fem::FieldSpace& space = *scene.space;
  const int d = space.dim(), nn = space.n_nodes(), nc = scene.mesh.n_cells(), npc = space.nodes_per_cell();
  const std::vector<double> nodal = space.nodal_values(u);
  const std::vector<double> stress = fem::cell_cauchy_stress(space, scene.problem.cell_material, u);
  const bool quad = fem::is_quadratic(space.kind());
  const int vtk_type = d == 2 ? (quad ? 22 : 5) : (quad ? 24 : 10);
  try {
    auto out = fmt::output_file(path);
    out.print("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
              "<UnstructuredGrid>\n<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", nn, nc);
    out.print("<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
    double X[3];
    for (int n = 0; n < nn; ++n) {
      X[2] = 0;
      space.node_position(n, X);
      out.print("{:.10g} {:.10g} {:.10g}\n", X[0], X[1], X[2]);
    }
    out.print("</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    std::vector<int> nodes(npc);
    for (int c = 0; c < nc; ++c) {
      space.cell_nodes(c, nodes.data());  // local order = VTK order (mesh::SimplexEdges)
      for (int a = 0; a < npc; ++a) out.print("{} ", nodes[a]);
      out.print("\n");
    }
    out.print("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    for (int c = 1; c <= nc; ++c) out.print("{}\n", static_cast<long>(c) * npc);
    out.print("</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    for (int c = 0; c < nc; ++c) out.print("{}\n", vtk_type);
    out.print("</DataArray>\n</Cells>\n<PointData Vectors=\"displacement\">\n"
              "<DataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\" format=\"ascii\">\n");
    for (int n = 0; n < nn; ++n) {
      const double* v = &nodal[static_cast<size_t>(n) * d];
      out.print("{:.12g} {:.12g} {:.12g}\n", v[0], v[1], d == 3 ? v[2] : 0.0);
    }
    if (space.has_pressure()) {
      out.print("</DataArray>\n<DataArray type=\"Float64\" Name=\"pressure\" format=\"ascii\">\n");
      for (double p : space.nodal_pressure(u)) out.print("{:.12g}\n", p);
    }
    if (!scene.problem.constraints.empty() && !lambda.empty()) {
      std::vector<int> state(nn, -1);
      std::vector<double> multiplier(static_cast<size_t>(nn) * 3, 0.0), normal(nn, 0.0);
      for (const auto& [pair, nodes] : multiplier_nodes(scene, t, u, lambda))
        for (const auto& node : nodes) {  // a slave vertex is point `vertex` (vertices come first)
          state[node.vertex] = node.state;
          normal[node.vertex] = node.normal;
          for (int c = 0; c < 3; ++c) multiplier[static_cast<size_t>(node.vertex) * 3 + c] = node.multiplier[c];
        }
      out.print("</DataArray>\n<DataArray type=\"Float64\" Name=\"contact_multiplier\" NumberOfComponents=\"3\" "
                "format=\"ascii\">\n");
      for (int n = 0; n < nn; ++n)
        out.print("{:.12g} {:.12g} {:.12g}\n", multiplier[3 * n], multiplier[3 * n + 1], multiplier[3 * n + 2]);
      out.print("</DataArray>\n<DataArray type=\"Float64\" Name=\"contact_pressure\" format=\"ascii\">\n");
      for (double p : normal) out.print("{:.12g}\n", p);
      out.print("</DataArray>\n<DataArray type=\"Int32\" Name=\"contact_state\" format=\"ascii\">\n");
      for (int s : state) out.print("{}\n", s);
    }
    out.print("</DataArray>\n</PointData>\n<CellData>\n"
              "<DataArray type=\"Float64\" Name=\"cauchy_stress\" NumberOfComponents=\"9\" format=\"ascii\">\n");
    for (int c = 0; c < nc; ++c) {
      const double* s = &stress[static_cast<size_t>(c) * 9];
      out.print("{:.10g} {:.10g} {:.10g} {:.10g} {:.10g} {:.10g} {:.10g} {:.10g} {:.10g}\n", s[0], s[1], s[2], s[3],
                s[4], s[5], s[6], s[7], s[8]);
    }
    out.print("</DataArray>\n<DataArray type=\"Float64\" Name=\"von_mises\" format=\"ascii\">\n");
    for (int c = 0; c < nc; ++c) out.print("{:.10g}\n", von_mises(&stress[static_cast<size_t>(c) * 9]));
    out.print("</DataArray>\n<DataArray type=\"Int32\" Name=\"body_id\" format=\"ascii\">\n");
    for (int c = 0; c < nc; ++c) out.print("{}\n", scene.body_of_cell[c]);
    out.print("</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
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
