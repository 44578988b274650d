// Record/replay: a recorded Newton system replays to its recorded solution with the
// recording backend (round-off) and with another backend (Krylov tolerance); a damaged
// record is a clear error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "builtin_scenes.hpp"
#include "common/error.hpp"
#include "nonlinear/newton.hpp"
#include "registry.hpp"
#include "system_record.hpp"

namespace stiction::harness {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / name;
  fs::remove_all(dir);
  return dir;
}

// Records the Newton systems of a scene's first load step at level 0, solved by `backend`;
// returns the record's folder and the Krylov iterations of each recorded solve.
struct Recording {
  fs::path dir;
  std::vector<int> krylov_iterations;
};
Recording record_first_step(const std::string& scene_name, const std::string& backend, const std::string& name) {
  Recording rec{fresh_dir(name), {}};
  auto scene = open_scene(scene_name, 0);
  auto solver = solvers::create_solver(backend, PETSC_COMM_WORLD);
  nonlinear::QuasiStaticSolver newton(PETSC_COMM_WORLD, scene->problem, scene->newton, *solver);
  const RecordContext ctx{scene_name, 0, backend, RunInfo{}};
  newton.set_system_observer([&](const nonlinear::NewtonSystem& sys, Vec du, const nonlinear::LinearSolveStats& st,
                                 int step, int it) {
    record_system(rec.dir.string(), sys, du, st, step, it, ctx);
    rec.krylov_iterations.push_back(st.iterations);
  });
  EXPECT_TRUE(newton.solve_step(1).converged());
  return rec;
}

fs::path record_cantilever(const std::string& name) { return record_first_step("cantilever-2d", "lu-mumps", name).dir; }

double replay_difference(const std::string& system_dir, const std::string& backend) {
  RecordedSystem r = load_system(system_dir, PETSC_COMM_WORLD);
  auto solver = solvers::create_solver(backend, PETSC_COMM_WORLD);
  Vec x;
  VecDuplicate(r.system.rhs, &x);
  VecZeroEntries(x);
  solver->setup(r.system);
  EXPECT_TRUE(solver->solve(r.system, x).converged);
  VecAXPY(x, -1.0, r.solution);
  PetscReal d, n;
  VecNorm(x, NORM_2, &d);
  VecNorm(r.solution, NORM_2, &n);
  VecDestroy(&x);
  return d / n;
}

TEST(RecordReplay, ReproducesTheRecordedSolution) {
  const fs::path dir = record_cantilever("record-a");
  const auto systems = recorded_system_dirs(dir.string());
  ASSERT_GE(systems.size(), 2u);  // one per Newton iteration of the step
  RecordedSystem r = load_system(systems[0], PETSC_COMM_WORLD);
  ASSERT_NE(r.system.field("u_l"), nullptr);
  ASSERT_NE(r.system.field("u_q"), nullptr);
  PetscInt bs;
  MatGetBlockSize(r.system.matrix, &bs);
  EXPECT_EQ(bs, 2);
  EXPECT_TRUE(r.system.near_null_space);
  EXPECT_LT(replay_difference(systems[0], "lu-mumps"), 1e-12);
  // Another backend agrees to its Krylov tolerance (pinned here: the default is loose).
  PetscOptionsSetValue(nullptr, "-schur_lu_ksp_rtol", "1e-10");
  EXPECT_LT(replay_difference(systems[0], "schur-lu"), 1e-7);
  PetscOptionsClearValue(nullptr, "-schur_lu_ksp_rtol");
}

// A contact system keeps its multiplier surface and a mixed one its pressure mass and
// moduli, which the Schur backends form their approximations from: replayed with the
// recording backend, each takes the recorded solve's Krylov iterations.
TEST(RecordReplay, SchurBackendsReplayContactAndMixedSystems) {
  for (const std::string scene : {"contact-patch-2d", "cook-membrane-2d"}) {
    SCOPED_TRACE(scene);
    const Recording rec = record_first_step(scene, "schur-amg", "record-" + scene);
    const auto systems = recorded_system_dirs(rec.dir.string());
    ASSERT_EQ(systems.size(), rec.krylov_iterations.size());
    RecordedSystem r = load_system(systems[0], PETSC_COMM_WORLD);
    if (scene == "contact-patch-2d") {
      const auto& surface = r.system.multiplier_surface;
      EXPECT_TRUE(surface.mass && surface.laplacian && surface.projector && surface.constrained && surface.slip_rows);
    } else {
      EXPECT_TRUE(r.system.pressure_mass);
      EXPECT_GT(r.system.mixed_shear_modulus, 0);
      EXPECT_GT(r.system.mixed_bulk_modulus, 0);
    }
    auto solver = solvers::create_solver("schur-amg", PETSC_COMM_WORLD);
    PetscVec x;
    VecDuplicate(r.system.rhs, x.out());
    VecZeroEntries(x);
    solver->setup(r.system);
    const nonlinear::LinearSolveStats st = solver->solve(r.system, x);
    EXPECT_TRUE(st.converged);
    EXPECT_EQ(st.iterations, rec.krylov_iterations[0]);
  }
}

TEST(RecordReplay, DamagedRecordIsAClearError) {
  const fs::path dir = record_cantilever("record-b");
  const std::string first = recorded_system_dirs(dir.string())[0];
  { std::ofstream(fs::path(first) / "metadata.json") << "{ not json"; }
  try {
    load_system(first, PETSC_COMM_WORLD);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unreadable record"), std::string::npos) << e.what();
  }
  fs::remove(fs::path(first) / "system.petsc");
  EXPECT_THROW(load_system(first, PETSC_COMM_WORLD), Error);
  EXPECT_THROW(recorded_system_dirs((dir / "nonexistent").string()), Error);
  const fs::path empty = fresh_dir("record-empty");
  fs::create_directories(empty);
  EXPECT_THROW(recorded_system_dirs(empty.string()), Error);
}

}  // namespace
}  // namespace stiction::harness
