#include "system_record.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/error.hpp"

namespace stiction::harness {

namespace fs = std::filesystem;

namespace {

// The multiplier surface's matrices by name, in the order a record holds them (Surface:
// MultiplierSurface, const or not).
template <class Surface>
auto surface_matrices(Surface& s) {
  using Entry = std::pair<const char*, decltype(&s.mass)>;
  return std::array<Entry, 5>{Entry{"mass", &s.mass}, Entry{"laplacian", &s.laplacian},
                              Entry{"projector", &s.projector}, Entry{"constrained", &s.constrained},
                              Entry{"slip_rows", &s.slip_rows}};
}

void load_matrix(PetscMat& mat, MPI_Comm comm, PetscViewer viewer) {
  STICTION_PETSC(MatCreate(comm, mat.out()));
  STICTION_PETSC(MatSetType(mat, MATAIJ));
  STICTION_PETSC(MatLoad(mat, viewer));
}

}  // namespace

std::set<std::pair<int, int>> parse_system_selection(const std::vector<std::string>& items) {
  std::set<std::pair<int, int>> selected;
  for (const auto& item : items) {
    int step = 0, iteration = 0;
    char colon = 0, extra = 0;
    if (std::sscanf(item.c_str(), "%d%c%d%c", &step, &colon, &iteration, &extra) != 3 || colon != ':' || step < 1 ||
        iteration < 1)
      throw Error(fmt::format("system '{}': expected STEP:ITERATION, both from 1 (e.g. 6:2)", item));
    selected.insert({step, iteration});
  }
  return selected;
}

void record_system(const std::string& dir, const nonlinear::NewtonSystem& sys, Vec solution,
                   const nonlinear::LinearSolveStats& stats, int step, int iteration, const RecordContext& ctx) {
  const fs::path folder = fs::path(dir) / fmt::format("system-{:03d}-{:02d}", step, iteration);
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw Error(fmt::format("cannot create record folder '{}': {}", folder.string(), ec.message()));

  PetscViewer viewer;
  STICTION_PETSC(PetscViewerBinaryOpen(sys.comm, (folder / "system.petsc").c_str(), FILE_MODE_WRITE, &viewer));
  STICTION_PETSC(MatView(sys.matrix, viewer));
  STICTION_PETSC(VecView(sys.rhs, viewer));
  STICTION_PETSC(VecView(solution, viewer));
  nlohmann::json fields = nlohmann::json::array();
  for (const auto& f : sys.fields) {
    STICTION_PETSC(ISView(f.is, viewer));
    PetscInt n;
    STICTION_PETSC(ISGetSize(f.is, &n));
    fields.push_back({{"name", f.name}, {"size", n}, {"block_size", f.block_size}});
  }
  PetscInt n_null = 0;
  if (sys.near_null_space) {
    PetscBool has_constant;
    const Vec* vecs;
    STICTION_PETSC(MatNullSpaceGetVecs(sys.near_null_space, &has_constant, &n_null, &vecs));
    for (PetscInt i = 0; i < n_null; ++i) STICTION_PETSC(VecView(vecs[i], viewer));
  }
  // What the Schur backends form their approximations from (the pressure mass of a mixed
  // system, the multiplier surface of a contact system): without them a replay could not
  // set those backends up.
  if (sys.pressure_mass) STICTION_PETSC(MatView(sys.pressure_mass, viewer));
  nlohmann::json surface = nlohmann::json::array();
  for (const auto& [name, mat] : surface_matrices(sys.multiplier_surface))
    if (*mat) {
      STICTION_PETSC(MatView(*mat, viewer));
      surface.push_back(name);
    }
  STICTION_PETSC(PetscViewerDestroy(&viewer));

  PetscInt n;
  STICTION_PETSC(MatGetSize(sys.matrix, &n, nullptr));
  nlohmann::json meta{{"scene", ctx.scene},
                      {"level", ctx.level},
                      {"recorded_with", ctx.solver},
                      {"step", step},
                      {"newton_iteration", iteration},
                      {"unknowns", n},
                      {"block_size", sys.block_size},
                      {"fields", fields},
                      {"near_null_space_vectors", n_null},
                      {"pressure_mass", static_cast<bool>(sys.pressure_mass)},
                      {"mixed_shear_modulus", sys.mixed_shear_modulus},
                      {"mixed_bulk_modulus", sys.mixed_bulk_modulus},
                      {"multiplier_surface", surface},
                      {"linear_solve",
                       {{"converged", stats.converged},
                        {"reason", stats.reason},
                        {"iterations", stats.iterations},
                        {"initial_residual", stats.initial_residual},
                        {"final_residual", stats.final_residual}}},
                      {"petsc", ctx.info.petsc_version},
                      {"git_revision", ctx.info.git_revision},
                      {"command", ctx.info.command_line}};
  // The Krylov tolerance the recording solve ran to (the Newton driver's forcing term) and
  // its GMRES restart (the scene's newton.krylov_restart, else the backend's), so that a
  // replay solves the same way.
  if (const auto rtol = stats.extra.find("ksp_rtol"); rtol != stats.extra.end())
    meta["linear_solve"]["krylov_rtol"] = rtol->second;
  if (const auto restart = stats.extra.find("ksp_gmres_restart"); restart != stats.extra.end())
    meta["linear_solve"]["krylov_restart"] = static_cast<int>(restart->second);
  std::ofstream out(folder / "metadata.json");
  out << meta.dump(2) << "\n";
  if (!out) throw Error(fmt::format("cannot write '{}'", (folder / "metadata.json").string()));
}

std::vector<std::string> recorded_system_dirs(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw Error(fmt::format("record '{}' is not a directory", dir));
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.is_directory() && e.path().filename().string().rfind("system-", 0) == 0) out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  if (out.empty()) throw Error(fmt::format("record '{}' holds no recorded system (system-*/ folders)", dir));
  return out;
}

RecordedSystem load_system(const std::string& system_dir, MPI_Comm comm) {
  const fs::path folder(system_dir);
  nlohmann::json meta;
  try {
    std::ifstream in(folder / "metadata.json");
    if (!in) throw Error("missing metadata.json");
    meta = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw Error(fmt::format("unreadable record '{}': {}", system_dir, e.what()));
  }
  const fs::path data = folder / "system.petsc";
  if (!fs::is_regular_file(data)) throw Error(fmt::format("unreadable record '{}': missing system.petsc", system_dir));
  RecordedSystem r;
  r.path = system_dir;
  try {
    r.description = fmt::format("{} level {} step {} iteration {}", meta.at("scene").get<std::string>(),
                                meta.at("level").get<int>(), meta.at("step").get<int>(),
                                meta.at("newton_iteration").get<int>());
    const auto solve = meta.value("linear_solve", nlohmann::json::object());
    r.krylov_rtol = solve.value("krylov_rtol", 0.0);
    r.krylov_restart = solve.value("krylov_restart", 0);
    auto& sys = r.system;
    sys.comm = comm;
    sys.block_size = meta.at("block_size").get<int>();
    PetscViewer viewer;
    STICTION_PETSC(PetscViewerBinaryOpen(comm, data.c_str(), FILE_MODE_READ, &viewer));
    STICTION_PETSC(MatCreate(comm, sys.matrix.out()));
    STICTION_PETSC(MatSetType(sys.matrix, MATAIJ));
    STICTION_PETSC(MatSetBlockSize(sys.matrix, sys.block_size));
    STICTION_PETSC(MatLoad(sys.matrix, viewer));
    for (PetscVec* v : {&sys.rhs, &r.solution}) {
      STICTION_PETSC(VecCreate(comm, v->out()));
      STICTION_PETSC(VecLoad(*v, viewer));
    }
    for (const auto& f : meta.at("fields")) {
      nonlinear::FieldBlock block{f.at("name").get<std::string>(), {}, f.at("block_size").get<int>()};
      STICTION_PETSC(ISCreate(comm, block.is.out()));
      STICTION_PETSC(ISLoad(block.is, viewer));
      STICTION_PETSC(ISSetBlockSize(block.is, block.block_size));
      sys.fields.push_back(std::move(block));
    }
    const int n_null = meta.at("near_null_space_vectors").get<int>();
    if (n_null > 0) {
      std::vector<Vec> vecs(n_null);
      for (Vec& v : vecs) {
        STICTION_PETSC(VecCreate(comm, &v));
        STICTION_PETSC(VecLoad(v, viewer));
      }
      STICTION_PETSC(MatNullSpaceCreate(comm, PETSC_FALSE, n_null, vecs.data(), sys.near_null_space.out()));
      for (Vec& v : vecs) VecDestroy(&v);
      STICTION_PETSC(MatSetNearNullSpace(sys.matrix, sys.near_null_space));
    }
    // Records made before these were kept have none of them.
    if (meta.value("pressure_mass", false)) load_matrix(sys.pressure_mass, comm, viewer);
    sys.mixed_shear_modulus = meta.value("mixed_shear_modulus", 0.0);
    sys.mixed_bulk_modulus = meta.value("mixed_bulk_modulus", 0.0);
    const auto recorded = meta.value("multiplier_surface", std::vector<std::string>{});
    for (const auto& [name, mat] : surface_matrices(sys.multiplier_surface))
      if (std::find(recorded.begin(), recorded.end(), name) != recorded.end()) load_matrix(*mat, comm, viewer);
    STICTION_PETSC(PetscViewerDestroy(&viewer));
  } catch (const Error& e) {
    throw Error(fmt::format("unreadable record '{}': {}", system_dir, e.what()));
  } catch (const std::exception& e) {
    throw Error(fmt::format("unreadable record '{}': metadata: {}", system_dir, e.what()));
  }
  return r;
}

}  // namespace stiction::harness
