// Record/replay: a recorded Newton system replays to its recorded solution with the
// recording backend (round-off) and with another backend (Krylov tolerance), to the
// recording solve's Krylov tolerance; a damaged record is a clear error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "builtin_scenes.hpp"
#include "common/error.hpp"
#include "nonlinear/newton.hpp"
#include "registry.hpp"
#include "replay_command.hpp"
#include "system_record.hpp"

namespace stiction::harness {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / name;
  fs::remove_all(dir);
  return dir;
}

// Records the Newton systems of a scene's first load step at level 0, solved by `backend`
// (to krylov_rtol and with GMRES(krylov_restart) when given); returns the record's folder and
// the Krylov iterations of each recorded solve.
struct Recording {
  fs::path dir;
  std::vector<int> krylov_iterations;
};
Recording record_first_step(const std::string& scene_name, const std::string& backend, const std::string& name,
                            double krylov_rtol = 0, int krylov_restart = 0) {
  Recording rec{fresh_dir(name), {}};
  auto scene = open_scene(scene_name, 0);
  if (krylov_rtol > 0) scene->newton.krylov_rtol = krylov_rtol;
  scene->newton.krylov_restart = krylov_restart;
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

// The recorded system solved again by `backend`, to the tolerance `choice` gives
// (ReplayOptions::krylov_rtol).
ReplayedSolve replay(const std::string& system_dir, const std::string& backend, const std::string& choice = "backend") {
  RecordedSystem r = load_system(system_dir, PETSC_COMM_WORLD);
  auto solver = solvers::create_solver(backend, PETSC_COMM_WORLD);
  ReplayedSolve out = replay_system(r, *solver, replay_krylov_rtol(choice, r.krylov_rtol, false),
                                    replay_krylov_restart(choice, r.krylov_restart, false));
  EXPECT_TRUE(out.stats.converged) << out.stats.reason;
  return out;
}

double replay_difference(const std::string& system_dir, const std::string& backend) {
  return replay(system_dir, backend).relative_difference;
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
    EXPECT_EQ(replay(systems[0], "schur-amg").stats.iterations, rec.krylov_iterations[0]);
  }
}

// A record keeps the Krylov tolerance its solve ran to (here the scene's, 1e-8, tighter
// than the backend's own 1e-4), and a replay solves to it unless told otherwise: the counts
// then compare with the recording solve's.
TEST(RecordReplay, ReplaysToTheRecordedKrylovTolerance) {
  const Recording rec = record_first_step("contact-patch-2d", "schur-amg", "record-rtol", 1e-8);
  const auto systems = recorded_system_dirs(rec.dir.string());
  ASSERT_EQ(systems.size(), rec.krylov_iterations.size());
  EXPECT_DOUBLE_EQ(load_system(systems[0], PETSC_COMM_WORLD).krylov_rtol, 1e-8);
  const ReplayedSolve recorded = replay(systems[0], "schur-amg", "recorded");
  EXPECT_DOUBLE_EQ(recorded.krylov_rtol, 1e-8);
  EXPECT_EQ(recorded.stats.iterations, rec.krylov_iterations[0]);
  const ReplayedSolve own = replay(systems[0], "schur-amg", "backend");
  EXPECT_EQ(own.krylov_rtol, 0);
  EXPECT_LT(own.stats.iterations, recorded.stats.iterations);
  EXPECT_EQ(replay(systems[0], "schur-amg", "1e-6").krylov_rtol, 1e-6);
  // A tolerance on the command line (-schur_amg_ksp_rtol) wins over the recorded one (the
  // command line itself: StictionCli.RecordThenReplayWithAnotherBackend).
  EXPECT_EQ(replay_krylov_rtol("recorded", 1e-8, true), 0);
  for (const std::string bad : {"tight", "0", "2", "1e-6x"}) EXPECT_THROW(replay_krylov_rtol(bad, 1e-8, false), Error);
  // A direct solve records none: its replay runs to the backend's own tolerance.
  const Recording direct = record_first_step("contact-patch-2d", "lu-mumps", "record-rtol-direct");
  EXPECT_EQ(replay(recorded_system_dirs(direct.dir.string())[0], "schur-amg", "recorded").krylov_rtol, 0);
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

// A record keeps the GMRES restart its solve ran with (here the scene's, 3, against the
// backend's 100), and a replay under "recorded" runs with it, so that its counts are the
// recording solve's; under "backend", or with -<backend>_ksp_gmres_restart given, the
// backend's own. A direct solve records none.
TEST(RecordReplay, ReplaysWithTheRecordedGmresRestart) {
  const Recording rec = record_first_step("contact-patch-2d", "schur-amg", "record-restart", 0, 3);
  const auto systems = recorded_system_dirs(rec.dir.string());
  ASSERT_EQ(systems.size(), rec.krylov_iterations.size());
  ASSERT_GE(systems.size(), 2u);
  // The totals compare the solves recorded at the backend's own tolerance: Newton raises the
  // tolerance of a load step's last solve (terminal_forcing), which "backend" would not.
  int recorded_total = 0, own_total = 0, compared = 0;
  for (size_t k = 0; k < systems.size(); ++k) {
    SCOPED_TRACE(systems[k]);
    const RecordedSystem system = load_system(systems[k], PETSC_COMM_WORLD);
    EXPECT_EQ(system.krylov_restart, 3);
    const ReplayedSolve recorded = replay(systems[k], "schur-amg", "recorded");
    EXPECT_EQ(recorded.krylov_restart, 3);
    EXPECT_EQ(recorded.stats.iterations, rec.krylov_iterations[k]);
    const ReplayedSolve own = replay(systems[k], "schur-amg", "backend");
    EXPECT_EQ(own.krylov_restart, 100);
    if (system.krylov_rtol != own.stats.extra.at("ksp_rtol")) continue;
    recorded_total += recorded.stats.iterations, own_total += own.stats.iterations, ++compared;
  }
  ASSERT_GE(compared, 1);
  EXPECT_LT(own_total, recorded_total);  // the restart shaped the recorded counts
  EXPECT_EQ(replay_krylov_restart("recorded", 3, true), 0);
  EXPECT_EQ(replay_krylov_restart("1e-6", 3, false), 3);
  const Recording direct = record_first_step("contact-patch-2d", "lu-mumps", "record-restart-direct");
  EXPECT_EQ(load_system(recorded_system_dirs(direct.dir.string())[0], PETSC_COMM_WORLD).krylov_restart, 0);
}

}  // namespace
}  // namespace stiction::harness
