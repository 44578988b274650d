// stiction launched by mpirun on two processes: `solve` follows the one-process Newton path
// (the same Newton iterations, forces to 1e-8, Krylov counts within a band), rank 0 alone
// writes but for each process's piece of a VTU; every other command, and a backend that runs on one process, is refused with one
// message from rank 0 and exit code 2 before any work; bad input and a diverging Newton
// name their cause once; no process is left running (each run is under `timeout`, which
// exits 124 on a hang). Labelled `mpi` (ctest -L mpi).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "csv_table.hpp"
#include "vtu_reader.hpp"

namespace {

namespace fs = std::filesystem;
using stiction::test::CliRun;
using stiction::test::shell_quote;

constexpr int kExitInput = 2;

// mpirun on PATH (openmpi-bin, installed with the build dependencies).
std::string find_mpirun() {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "";
  for (size_t start = 0; start <= dirs.size();) {
    const size_t end = dirs.find(':', start);
    const fs::path candidate = fs::path(dirs.substr(start, end - start)) / "mpirun";
    if (fs::exists(candidate)) return candidate.string();
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return {};
}

class StictionUnderMpirun : public ::testing::Test {
protected:
  void SetUp() override {
    mpirun_ = find_mpirun();
    ASSERT_FALSE(mpirun_.empty()) << "mpirun is not on PATH (Debian package openmpi-bin)";
    dir_ = stiction::test::make_temporary_directory("stiction-mpi");
    ASSERT_FALSE(dir_.empty()) << "cannot create a temporary directory";
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }

  CliRun run(int processes, const std::vector<std::string>& args) const {
    // Open MPI refuses root without these; --oversubscribe: a CI machine may have one core.
    std::string launcher = shell_quote(mpirun_) + " -n " + std::to_string(processes) + " --oversubscribe";
    if (geteuid() == 0) launcher += " --allow-run-as-root";
    return CliRun::of_command(launcher + " " + shell_quote(STICTION_BINARY), args, dir_);
  }
  void expect_level_one_refined_in_parts(const std::string& scene, bool contact) const;

  std::string mpirun_;
  fs::path dir_;
};

TEST_F(StictionUnderMpirun, OtherCommandsOnTwoProcessesAreRefusedOnce) {
  const CliRun r = run(2, {"scenes"});
  EXPECT_EQ(r.exit_code, kExitInput) << r.err;
  ASSERT_EQ(r.error_lines().size(), 1u) << r.err;
  EXPECT_NE(r.error_lines()[0].find("`stiction scenes` runs on one MPI process (launched on 2)"), std::string::npos)
      << r.err;
}

TEST_F(StictionUnderMpirun, OneProcessBackendOnTwoProcessesIsRefusedOnceBeforeAnyWork) {
  const CliRun r = run(2, {"solve", "cantilever-2d", "--solver", "lu-umfpack", "--quiet", "--no-vtu", "--out",
                           (dir_ / "out").string()});
  EXPECT_EQ(r.exit_code, kExitInput) << r.err;
  ASSERT_EQ(r.error_lines().size(), 1u) << r.err;
  EXPECT_NE(r.error_lines()[0].find("'lu-umfpack' runs on one MPI process (launched on 2)"), std::string::npos) << r.err;
  EXPECT_NE(r.error_lines()[0].find("lu-mumps"), std::string::npos) << "the message names the usable backends";
  EXPECT_FALSE(fs::exists(dir_ / "out" / "steps.csv")) << "the refused run wrote results";
}

// A CSV file of stiction's (steps.csv, runs.csv) as rows of named fields (its comment lines
// skipped; fields hold no commas).
std::vector<std::map<std::string, std::string>> read_rows(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    std::stringstream split(line);
    for (std::string f; std::getline(split, f, ',');) fields.push_back(f);
    if (header.empty()) {
      header = fields;
      continue;
    }
    std::map<std::string, std::string> row;
    for (size_t k = 0; k < header.size() && k < fields.size(); ++k) row[header[k]] = fields[k];
    rows.push_back(row);
  }
  return rows;
}

// The force columns of steps.csv: every column after wall_seconds (reactions, tractions,
// contact forces).
bool is_force_column(const std::string& name) {
  for (const char* part : {"reaction_", "traction_", "contact_"})
    if (name.rfind(part, 0) == 0) return true;
  return false;
}

// The steps.csv of two runs of the same scene: the same rows and Newton path (step, cut,
// converged, reason, Newton iterations in every row), every force column to 1e-8 of the
// largest force. Returns the total Krylov iterations of each run.
std::pair<double, double> expect_same_newton_path(const fs::path& one, const fs::path& other) {
  const auto a = read_rows(one / "steps.csv"), b = read_rows(other / "steps.csv");
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a.size(), b.size());
  if (a.empty() || a.size() != b.size()) return {0, 0};
  double force_scale = 0;
  for (const auto& row : a) {
    for (const auto& [name, value] : row)
      if (is_force_column(name)) force_scale = std::max(force_scale, std::abs(std::stod(value)));
  }
  EXPECT_GT(force_scale, 0) << "no force column to compare";
  double krylov_a = 0, krylov_b = 0;
  for (size_t k = 0; k < a.size(); ++k) {
    for (const char* same : {"step", "cut", "converged", "reason", "newton_iterations"})
      EXPECT_EQ(a[k].at(same), b[k].at(same)) << same << " of row " << k;
    for (const auto& [name, value] : a[k]) {
      if (!is_force_column(name)) continue;
      EXPECT_NEAR(std::stod(value), std::stod(b[k].at(name)), 1e-8 * force_scale) << name << " of row " << k;
    }
    krylov_a += std::stod(a[k].at("krylov_iterations"));
    krylov_b += std::stod(b[k].at("krylov_iterations"));
  }
  return {krylov_a, krylov_b};
}

struct ParallelCase {
  const char* scene;
  const char* backend;
  double krylov_band;       // largest relative change of the total Krylov iterations
  const char* krylov_rtol;  // "" for the scene's
};

void PrintTo(const ParallelCase& c, std::ostream* os) { *os << c.scene << " with " << c.backend; }

class SolveOnTwoProcesses : public StictionUnderMpirun, public ::testing::WithParamInterface<ParallelCase> {};

TEST_P(SolveOnTwoProcesses, FollowsTheOneProcessNewtonPath) {
  const ParallelCase& c = GetParam();
  auto args = [&](const std::string& out) {
    std::vector<std::string> a{"solve", c.scene, "--quick", "--solver", c.backend, "--quiet", "--no-vtu", "--out",
                               (dir_ / out).string(), "--metrics", (dir_ / (out + ".toml")).string()};
    if (*c.krylov_rtol) a.insert(a.end(), {"--krylov-rtol", c.krylov_rtol});
    return a;
  };
  const CliRun one = run(1, args("one"));
  const CliRun two = run(2, args("two"));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_TRUE(two.error_lines().empty()) << two.err;
  const auto [krylov_a, krylov_b] = expect_same_newton_path(dir_ / "one", dir_ / "two");
  EXPECT_LE(std::abs(krylov_b - krylov_a), c.krylov_band * krylov_a) << krylov_a << " -> " << krylov_b;
  const std::string metrics = stiction::test::read_file(dir_ / "two.toml");
  EXPECT_NE(metrics.find("processes = 2"), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("peak_rss_mb_sum"), std::string::npos) << metrics;
}

// Direct solves follow the path exactly. Krylov counts move with the parallel set-up:
// BoomerAMG's and GAMG's coarsening is per process (measured within 3% on cantilever-2d),
// and ilu-gmres becomes block Jacobi with ILU(0) per process (PETSc has no parallel ILU):
// +3% on hertz-cylinder-2d, +10% on block-compression, +30% on cook-membrane-2d, and 2.4x
// on the slender cantilever-2d, which its two blocks cut across. On cantilever-2d a Krylov
// tolerance of 1e-4 lets the inexact Newton path change by one iteration: the AMG cases
// solve to 1e-8 so that the Newton path is the one to compare. schur-amg's quadratic-block
// and pressure SSOR sweeps are process-local on two processes: +15% on cantilever-2d, +22%
// on block-compression, +4% on cook-membrane-2d (mixed), +10% on hertz-cylinder-2d
// (contact, its S~ factored by MUMPS). fieldsplit-schur: +0% on sliding-block-2d.
INSTANTIATE_TEST_SUITE_P(Backends, SolveOnTwoProcesses,
                         ::testing::Values(ParallelCase{"cantilever-2d", "lu-mumps", 0, ""},
                                           ParallelCase{"hertz-cylinder-2d", "lu-mumps", 0, ""},
                                           ParallelCase{"sliding-block-2d", "lu-mumps", 0, ""},
                                           ParallelCase{"cook-membrane-2d", "lu-mumps", 0, ""},
                                           ParallelCase{"hertz-spheres-3d", "lu-mumps", 0, ""},
                                           ParallelCase{"cantilever-2d", "boomeramg", 0.1, "1e-8"},
                                           ParallelCase{"cantilever-2d", "gamg", 0.1, "1e-8"},
                                           ParallelCase{"cantilever-2d", "schur-amg", 0.25, "1e-8"},
                                           ParallelCase{"cook-membrane-2d", "schur-amg", 0.15, "1e-8"},
                                           ParallelCase{"hertz-cylinder-2d", "schur-amg", 0.25, "1e-8"},
                                           ParallelCase{"sliding-block-2d", "fieldsplit-schur", 0.1, "1e-8"},
                                           ParallelCase{"hertz-cylinder-2d", "ilu-gmres", 0.15, ""}),
                         [](const auto& info) {
                           std::string n = std::string(info.param.scene) + "_" + info.param.backend;
                           for (char& ch : n)
                             if (ch == '-') ch = '_';
                           return n;
                         });

// `stiction bench --ranks 1,2` runs each configuration alone and under `mpirun -n 2`: one row
// per process count, and the report's strong-scaling table compares them.
TEST_F(StictionUnderMpirun, BenchRanksAxisRunsEachConfigurationOnEachProcessCount) {
  const fs::path sweep = dir_ / "sweep";
  const CliRun r = CliRun::of({"bench", "--scenes", "cantilever-2d", "--solvers", "lu-mumps", "--ranks", "1,2",
                               "--quick", "--out", sweep.string()},
                              dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = read_rows(sweep / "runs.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("processes"), "1");
  EXPECT_EQ(rows[1].at("processes"), "2");
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("status"), "ok") << row.at("detail");
    EXPECT_GT(std::stod(row.at("peak_rss_mb_per_process")), 0);
  }
  EXPECT_EQ(rows[0].at("newton_iterations"), rows[1].at("newton_iterations"));
  // The job's peak is the sum over its processes: above one process's.
  EXPECT_GT(std::stod(rows[1].at("peak_rss_mb")), std::stod(rows[1].at("peak_rss_mb_per_process")));
  const std::string metrics = stiction::test::read_file(sweep / "runs" / "cantilever-2d-L0-lu-mumps-np2" / "metrics.toml");
  EXPECT_NE(metrics.find("processes = 2"), std::string::npos) << metrics;
  const std::string report = stiction::test::read_file(sweep / "report.md");
  EXPECT_NE(report.find("## Strong scaling"), std::string::npos);
  EXPECT_NE(report.find("| cantilever-2d | 0 | lu-mumps | 2 | ok |"), std::string::npos) << report;
  EXPECT_NE(report.find("MPI processes per run: 1, 2"), std::string::npos) << report;
}

TEST_F(StictionUnderMpirun, BenchRanksAxisRefusesAOneProcessBackend) {
  const CliRun r = CliRun::of({"bench", "--scenes", "cantilever-2d", "--solvers", "lu-umfpack", "--ranks", "1,2",
                               "--quick", "--out", (dir_ / "sweep").string()},
                              dir_);
  EXPECT_EQ(r.exit_code, kExitInput) << r.err;
  ASSERT_EQ(r.error_lines().size(), 1u) << r.err;
  EXPECT_NE(r.error_lines()[0].find("'lu-umfpack' runs on one MPI process"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "sweep" / "runs.csv")) << "the refused sweep started runs";
}

// The two-process output in `two` of the run whose one-process output is in `one`: the PVD
// names step-001.pvtu, whose pieces (one per process, each its own cells, from the state it
// holds) together hold every cell once and, at every point and cell, the one-process
// solution of step-001.vtu (values to 1e-8 of the largest; with contact, the contact state).
void expect_pieces_join_into_the_whole(const fs::path& one, const fs::path& two, bool contact) {
  EXPECT_FALSE(fs::exists(two / "step-001.vtu")) << "two processes write pieces, not the whole";
  std::ifstream pvd(two / "solution.pvd");
  const std::string collection((std::istreambuf_iterator<char>(pvd)), std::istreambuf_iterator<char>());
  EXPECT_NE(collection.find("file=\"step-001.pvtu\""), std::string::npos) << collection;
  std::ifstream pvtu_file(two / "step-001.pvtu");
  const std::string pvtu((std::istreambuf_iterator<char>(pvtu_file)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(pvtu.empty()) << "no step-001.pvtu";

  const auto whole = stiction::test::read_vtu((one / "step-001.vtu").string());
  const auto& points = whole.array("Points").values;
  const auto& u = whole.array("displacement").values;
  std::map<std::pair<long long, long long>, size_t> point_at;  // 2D: (x, y) to 1e-9
  for (size_t k = 0; k + 2 < points.size(); k += 3)
    point_at[{std::llround(points[k] * 1e9), std::llround(points[k + 1] * 1e9)}] = k / 3;
  double u_max = 0;
  for (double v : u) u_max = std::max(u_max, std::abs(v));
  ASSERT_GT(u_max, 0);
  // The PVTU declares every array the one-process file has, and the pieces' process number.
  for (const auto& a : whole.arrays) {
    if (a.name != "Points" && a.name != "connectivity" && a.name != "offsets" && a.name != "types") {
      EXPECT_NE(pvtu.find("Name=\"" + a.name + "\""), std::string::npos) << a.name << " not declared:\n" << pvtu;
    }
  }

  // Cells are matched by their vertices' centroid (2D, to 1e-9).
  const auto centroids = [](const stiction::test::VtuFile& f) {
    const auto& x = f.array("Points").values;
    const auto& connectivity = f.array("connectivity").values;
    const auto& offsets = f.array("offsets").values;
    std::vector<std::pair<long long, long long>> out;
    for (size_t c = 0; c < offsets.size(); ++c) {
      const size_t first = c == 0 ? 0 : static_cast<size_t>(offsets[c - 1]);
      double cx = 0, cy = 0;
      for (size_t k = first; k < first + 3; ++k) {  // the triangle's vertices come first
        cx += x[static_cast<size_t>(connectivity[k]) * 3] / 3;
        cy += x[static_cast<size_t>(connectivity[k]) * 3 + 1] / 3;
      }
      out.emplace_back(std::llround(cx * 1e9), std::llround(cy * 1e9));
    }
    return out;
  };
  std::map<std::pair<long long, long long>, size_t> cell_at;
  const auto whole_centroids = centroids(whole);
  for (size_t c = 0; c < whole_centroids.size(); ++c) cell_at[whole_centroids[c]] = c;
  const auto& mises = whole.array("von_mises").values;
  double mises_max = 0;
  for (double v : mises) mises_max = std::max(mises_max, v);
  ASSERT_GT(mises_max, 0);

  int cells = 0;
  for (int rank = 0; rank < 2; ++rank) {
    const std::string name = "step-001-p" + std::to_string(rank) + ".vtu";
    EXPECT_NE(pvtu.find("<Piece Source=\"" + name + "\"/>"), std::string::npos) << pvtu;
    const auto piece = stiction::test::read_vtu((two / name).string());
    const int n_cells = std::stoi(piece.piece.at("NumberOfCells"));
    EXPECT_GT(n_cells, 0) << name;
    cells += n_cells;
    for (double p : piece.array("process").values) ASSERT_EQ(p, rank) << name;
    const auto& x = piece.array("Points").values;
    const auto& pu = piece.array("displacement").values;
    for (size_t k = 0; k + 2 < x.size(); k += 3) {
      const auto at = point_at.find({std::llround(x[k] * 1e9), std::llround(x[k + 1] * 1e9)});
      ASSERT_NE(at, point_at.end()) << name << ": point " << k / 3 << " is not a point of the whole mesh";
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(pu[k + c], u[at->second * 3 + c], 1e-8 * u_max) << name << " point " << k / 3;
      if (contact) {
        EXPECT_EQ(piece.array("contact_state").values[k / 3], whole.array("contact_state").values[at->second])
            << name << " point " << k / 3;
      }
    }
    const auto piece_centroids = centroids(piece);
    const auto& piece_mises = piece.array("von_mises").values;
    for (size_t c = 0; c < piece_centroids.size(); ++c) {
      const auto at = cell_at.find(piece_centroids[c]);
      ASSERT_NE(at, cell_at.end()) << name << ": cell " << c << " is not a cell of the whole mesh";
      EXPECT_NEAR(piece_mises[c], mises[at->second], 1e-8 * mises_max) << name << " cell " << c;
    }
  }
  EXPECT_EQ(cells, std::stoi(whole.piece.at("NumberOfCells"))) << "the pieces hold every cell once";
}

// On two processes each process holds its part of the mesh with the contact surfaces whole
// and writes its own cells as a VTU piece, from the state it holds (its owned unknowns and
// ghosts), and rank 0 a PVTU joining them (the Newton path is the same). Rank 0 writes
// contact.csv from the contact surfaces it holds, with the whole mesh's vertex ids: the
// one-process table.
TEST_F(StictionUnderMpirun, EachProcessWritesItsPieceOfTheSolutionAndRankZeroJoinsThem) {
  const fs::path one = dir_ / "one", two = dir_ / "two";
  const std::vector<std::string> common{"solve", "sliding-block-2d", "--quick", "--quiet", "--out"};
  auto with_out = [&](const fs::path& out) {
    std::vector<std::string> a = common;
    a.push_back(out.string());
    return a;
  };
  const CliRun r1 = run(1, with_out(one)), r2 = run(2, with_out(two));
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  EXPECT_NE(stiction::test::read_file(two / "steps.csv").find("each holds its part of the mesh and the contact surfaces whole"),
            std::string::npos)
      << "the two processes did not run on mesh parts";
  expect_pieces_join_into_the_whole(one, two, true);

  const auto contact_one = stiction::harness::read_csv((one / "contact.csv").string());
  const auto contact_two = stiction::harness::read_csv((two / "contact.csv").string());
  ASSERT_FALSE(contact_one.rows.empty());
  ASSERT_EQ(contact_two.rows.size(), contact_one.rows.size());
  double lambda_max = 0;
  for (const auto& row : contact_one.rows) lambda_max = std::max(lambda_max, std::abs(std::stod(row.at("lambda_n"))));
  ASSERT_GT(lambda_max, 0) << "no node presses";
  for (size_t k = 0; k < contact_one.rows.size(); ++k) {
    const auto &a = contact_one.rows[k], &b = contact_two.rows[k];
    EXPECT_EQ(a.at("vertex"), b.at("vertex")) << "row " << k;
    EXPECT_EQ(a.at("state"), b.at("state")) << "row " << k;
    EXPECT_NEAR(std::stod(a.at("lambda_n")), std::stod(b.at("lambda_n")), 1e-8 * lambda_max) << "row " << k;
    EXPECT_NEAR(std::stod(a.at("x")), std::stod(b.at("x")), 1e-9) << "row " << k;
  }
}

// Each process holds only its part of the mesh, with the space and Newton state over it
// (and, with contact, the contact surfaces whole). cook-membrane-2d's and sliding-block-2d's
// levels are uniform refinements of level 0, so level 0 is divided and the parts refined:
// level 1 on two processes ends where the whole level-1 mesh on one process does (the same
// Newton iterations, forces to 1e-8), and the VTU pieces join into its solution. With
// --whole-mesh every process holds the whole mesh, to the same result.
void StictionUnderMpirun::expect_level_one_refined_in_parts(const std::string& scene, bool contact) const {
  const fs::path one = dir_ / "one", parts = dir_ / "parts", whole = dir_ / "whole";
  auto args = [&](const fs::path& out, bool whole_mesh) {
    std::vector<std::string> a{"solve", scene, "--level", "1", "--quick", "--quiet", "--out", out.string()};
    if (whole_mesh) a.insert(a.end(), {"--whole-mesh", "--no-vtu"});
    return a;
  };
  const CliRun r1 = run(1, args(one, false)), r2 = run(2, args(parts, false)), r3 = run(2, args(whole, true));
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  ASSERT_EQ(r3.exit_code, 0) << r3.err;
  const std::string in_parts = stiction::test::read_file(parts / "steps.csv");
  const std::string held = contact ? "each holds its part of the mesh and the contact surfaces whole"
                                   : "each holds its part of the mesh, with";
  EXPECT_NE(in_parts.find("at level 0, each part then refined to level 1 where it is; " + held), std::string::npos)
      << in_parts.substr(0, 2000);
  EXPECT_NE(in_parts.find("# mesh: "), std::string::npos);
  const std::string one_header = stiction::test::read_file(one / "steps.csv");
  const auto mesh_line = [](const std::string& text) {
    const size_t at = text.find("# mesh: ");
    return at == std::string::npos ? std::string() : text.substr(at, text.find('\n', at) - at);
  };
  EXPECT_EQ(mesh_line(in_parts), mesh_line(one_header)) << "the header counts the whole mesh and space";
  EXPECT_NE(stiction::test::read_file(whole / "steps.csv").find("the mesh whole on each"), std::string::npos);
  expect_same_newton_path(one, parts);
  expect_same_newton_path(one, whole);
  expect_pieces_join_into_the_whole(one, parts, contact);
}

TEST_F(StictionUnderMpirun, SceneWithoutContactRunsOnMeshPartsRefinedInParts) {
  expect_level_one_refined_in_parts("cook-membrane-2d", false);
}

TEST_F(StictionUnderMpirun, SceneWithContactRunsOnMeshPartsRefinedInParts) {
  expect_level_one_refined_in_parts("sliding-block-2d", true);
}

// A checkpoint written on two processes holds the whole state (gathered on rank 0), in the
// numbering of the mesh, not of the processes: restarted on two processes or on one, the run
// ends where the uninterrupted one-process run does (the same Newton iterations, forces to
// 1e-8).
TEST_F(StictionUnderMpirun, CheckpointOfTwoProcessesRestartsOnAnyProcessCount) {
  const std::string scene = "hertz-cylinders-2d";
  auto solve = [&](int processes, const fs::path& out, std::vector<std::string> extra) {
    std::vector<std::string> a{"solve", scene, "--quiet", "--no-vtu", "--out", out.string()};
    a.insert(a.end(), extra.begin(), extra.end());
    return run(processes, a);
  };
  const CliRun whole = solve(1, dir_ / "whole", {});
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  for (int processes : {2, 1}) {
    const fs::path out = dir_ / ("restarted-on-" + std::to_string(processes));
    const CliRun first = solve(2, out, {"--until", "0.5"});
    ASSERT_EQ(first.exit_code, 0) << first.err;
    ASSERT_EQ(read_rows(out / "steps.csv").size(), 1u) << "the first run stops after its first load step";
    const CliRun rest = solve(processes, out, {"--restart", out.string()});
    ASSERT_EQ(rest.exit_code, 0) << rest.err;
    const auto a = read_rows(dir_ / "whole" / "steps.csv"), b = read_rows(out / "steps.csv");
    ASSERT_EQ(a.size(), b.size()) << "restarted on " << processes;
    double force_scale = 0;
    for (const auto& [name, value] : a.back())
      if (is_force_column(name)) force_scale = std::max(force_scale, std::abs(std::stod(value)));
    ASSERT_GT(force_scale, 0);
    EXPECT_EQ(a.back().at("newton_iterations"), b.back().at("newton_iterations")) << "restarted on " << processes;
    for (const auto& [name, value] : a.back())
      if (is_force_column(name)) {
        EXPECT_NEAR(std::stod(value), std::stod(b.back().at(name)), 1e-8 * force_scale)
            << name << ", restarted on " << processes;
      }
  }
}

TEST_F(StictionUnderMpirun, DivergingNewtonOnTwoProcessesGivesOneMessageAndKeepsItsRows) {
  const CliRun r = run(2, {"solve", "hertz-cylinder-2d", "--set", "newton.max_iterations=1", "--set",
                           "newton.rtol=1e-30", "--set", "newton.atol=1e-30", "--quiet", "--no-vtu", "--out",
                           (dir_ / "out").string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  ASSERT_EQ(r.error_lines().size(), 1u) << r.err;
  EXPECT_NE(r.error_lines()[0].find("Newton did not converge"), std::string::npos) << r.err;
  const auto rows = read_rows(dir_ / "out" / "steps.csv");
  ASSERT_FALSE(rows.empty()) << "the finished rows were lost";
  EXPECT_EQ(rows.back().at("converged"), "0");
}

TEST_F(StictionUnderMpirun, OneProcessUnderMpirunSolves) {
  const CliRun r = run(1, {"solve", "cantilever-2d", "--quiet", "--no-vtu", "--out", (dir_ / "out").string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.error_lines().empty()) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "steps.csv"));
}

TEST_F(StictionUnderMpirun, BadInputOnTwoProcessesGivesOneMessage) {
  const CliRun missing = run(2, {"solve", (dir_ / "no-such-scene.toml").string(), "--quiet"});
  EXPECT_EQ(missing.exit_code, kExitInput) << missing.err;
  EXPECT_EQ(missing.error_lines().size(), 1u) << missing.err;

  // Rank 0 alone reads a checkpoint: the others learn of its absence from it.
  const CliRun no_checkpoint = run(2, {"solve", "cantilever-2d", "--quiet", "--restart", (dir_ / "nowhere").string()});
  EXPECT_EQ(no_checkpoint.exit_code, kExitInput) << no_checkpoint.err;
  ASSERT_EQ(no_checkpoint.error_lines().size(), 1u) << no_checkpoint.err;
  EXPECT_NE(no_checkpoint.error_lines()[0].find("no checkpoint"), std::string::npos) << no_checkpoint.err;

  const CliRun unknown_option = run(2, {"solve", "cantilever-2d", "--no-such-option"});
  EXPECT_EQ(unknown_option.exit_code, kExitInput) << unknown_option.err;
  EXPECT_EQ(unknown_option.err.find("no-such-option"), unknown_option.err.rfind("no-such-option"))
      << "the usage error was printed by more than one process:\n"
      << unknown_option.err;
  EXPECT_NE(unknown_option.err.find("no-such-option"), std::string::npos) << unknown_option.err;
}

TEST_F(StictionUnderMpirun, SweepOnTwoProcessesIsRefusedOnce) {
  const CliRun r = run(2, {"bench", "--scenes", "cantilever-2d", "--solvers", "lu-mumps", "--quick", "--out",
                           (dir_ / "sweep").string()});
  EXPECT_EQ(r.exit_code, kExitInput) << r.err;
  ASSERT_EQ(r.error_lines().size(), 1u) << r.err;
  EXPECT_NE(r.error_lines()[0].find("`stiction bench` runs on one MPI process"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "sweep" / "runs.csv")) << "the refused sweep started runs";
}

}  // namespace
