#pragma once
// ParaView output: one VTU per load step (quadratic cells for P2, with nodal values at
// vertices and edge midpoints), or on several MPI processes one VTU piece per process and a
// PVTU joining them, and a PVD collection indexing them by load step. The arrays
// are zlib-compressed binary in the appended section (vtk_binary.hpp), or ASCII text when
// the scene asks for `[output] vtu_format = "ascii"`.
#include <string>
#include <vector>

#include "fem/app_view.hpp"
#include "scene/scene.hpp"
#include "scene/scene_view.hpp"

namespace stiction::harness {

// Von Mises stress of a 3x3 Cauchy stress (row-major).
double von_mises(const double* sigma);

// Writes displacement and, for mixed bodies, pressure (point data) and Cauchy stress, von Mises, body id (cell data, at
// cell centroids) for the coefficients u; with contact, at the slave nodes (pseudo-time t, multipliers
// lambda) the multiplier (traction on the slave), its normal part lambda_n and the contact state (0 inactive,
// 1 stick, 2 slip; -1 at every point that carries no multiplier).
void write_vtu(const std::string& path, const scene::Scene& scene, fem::StateView u,
               const std::vector<double>& lambda = {}, double t = 0);
// The same for the given cells only (one process's) of the scene or of this process's part
// of it, with the nodes they use and a cell array "process" holding `process`. u need hold only the nodes of these cells and, with
// contact, of the contact surfaces (a process's ghosted storage).
void write_vtu_piece(const std::string& path, const scene::SceneView& scene, fem::StateView u,
                     const std::vector<double>& lambda, double t, const std::vector<int>& cells, int process);
// The PVTU that joins the pieces (file names relative to it) written by write_vtu_piece
// for the same state (lambda: whether they carry the contact arrays).
void write_pvtu(const std::string& path, const scene::SceneView& scene, const std::vector<double>& lambda,
                const std::vector<std::string>& piece_files);

class PvdCollection {
public:
  explicit PvdCollection(std::string path) : path_(std::move(path)) {}
  // Adds a dataset and rewrites the collection, so it is valid after every step.
  void add(double time, const std::string& vtu_file_name);

private:
  std::string path_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace stiction::harness
