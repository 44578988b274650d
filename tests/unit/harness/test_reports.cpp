// The sweep report's derived figures: growth exponents, and the paper's tables beside a
// sweep (ratios, mesh counts, forces against lu-mumps) from a hand-made sweep directory.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "bench_report.hpp"
#include "csv_table.hpp"
#include "paper_tables.hpp"
#include "run_metrics.hpp"
#include "run_settings.hpp"
#include "scaling_plots.hpp"

namespace stiction::harness {
namespace {

namespace fs = std::filesystem;

// Time per linear solve leaves out the solves that did not converge (a factorisation the
// memory guard refused took 27 s of analysis on block-compression level 2 and used to be
// reported as 27 s per solve).
TEST(RunMetrics, TimePerSolveCountsTheConvergedSolvesOnly) {
  auto solve = [](bool converged, double setup, double seconds) {
    return toml::table{{"converged", converged}, {"setup_seconds", setup}, {"solve_seconds", seconds}};
  };
  toml::array solves{solve(true, 1.0, 2.0), solve(false, 5.0, 0.0), solve(true, 0.5, 0.5)};
  EXPECT_DOUBLE_EQ(seconds_per_converged_solve(&solves), 2.0);
  toml::array refused{solve(false, 27.0, 0.0)};
  EXPECT_EQ(seconds_per_converged_solve(&refused), 0.0);
  EXPECT_EQ(seconds_per_converged_solve(nullptr), 0.0);
}

TEST(ScalingPlots, LogLogSlopeIsThePowerLawsExponent) {
  std::vector<double> n{1e3, 8e3, 64e3}, t;
  for (double x : n) t.push_back(3 * std::pow(x, 1.5));
  EXPECT_NEAR(log_log_slope(n, t), 1.5, 1e-12);
  EXPECT_EQ(log_log_slope({1e3}, {2.0}), 0.0);                 // one point: no slope
  EXPECT_NEAR(log_log_slope({1e3, 0.0, 8e3}, {1.0, 5.0, 8.0}), 1.0, 1e-12);  // non-positive points skipped
}

// A level run with other options (a shorter GMRES restart at the finest level) is shown with
// them, and the growth is taken only between levels run with the same ones.
TEST(ScalingPlots, KrylovGrowthOnlyBetweenLevelsRunWithTheSameOptions) {
  const std::string restart = "-schur_amg_ksp_gmres_restart 50";
  KrylovByLevel levels{{0, {50, ""}}, {1, {60, ""}}, {2, {90, restart}}};
  EXPECT_EQ(krylov_per_level_text(levels), "L0: 50.0; L1: 60.0; L2: 90.0 (" + restart + ")");
  EXPECT_EQ(krylov_growth_text(levels), "1.20 (L0 to L1)");
  levels[0].options = levels[1].options = restart;
  EXPECT_EQ(krylov_growth_text(levels), "1.80");
  EXPECT_EQ(krylov_growth_text({{0, {50, ""}}, {2, {90, restart}}}), "—");
  EXPECT_EQ(krylov_growth_text({{0, {50, ""}}, {1, {55, ""}}, {2, {90, restart}}, {3, {99, restart}}}),
            "1.10 (L0 to L1)")
      << "of two sets spanning as many levels, the defaults'";

  const std::string runs_csv =
      "scene,level,solver,status,krylov_per_linear_solve,petsc_options\n"
      "block-strips,0,schur-amg,ok,47.4,\n"
      "block-strips,1,schur-amg,ok,58.5,\n"
      "block-strips,2,schur-amg,ok,85.3," + restart + "\n"
      "block-strips,0,lu-mumps,ok,1.0,\n"
      "block-strips,1,lu-mumps,ok,1.0,\n";
  const fs::path csv = fs::temp_directory_path() / "stiction-krylov-growth-test.csv";
  std::ofstream(csv) << runs_csv;
  const std::string md = krylov_growth_section(read_csv(csv.string()), fs::temp_directory_path().string());
  EXPECT_NE(md.find("| block-strips | schur-amg | L0: 47.4; L1: 58.5; L2: 85.3 (" + restart + ") | 1.23 (L0 to L1) |"),
            std::string::npos)
      << md;
  EXPECT_EQ(md.find("lu-mumps"), std::string::npos) << "a direct solver has no Krylov growth";
  fs::remove(csv);
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

// The settings a run had are its version's defaults with the sweep's options on top: a
// GMRES(50) given on the command line at level 2 and a GMRES(50) that was the default when
// levels 0 and 1 ran are one method, and the growth spans all three; a level run with the
// older default GMRES(100) is left out.
TEST(ScalingPlots, KrylovGrowthBetweenLevelsOfTheSameSettingsHoweverTheyWereGiven) {
  EXPECT_EQ(effective_backend_settings("# comment -x 1\n-ksp_type gmres\n-ksp_gmres_restart 100  # GMRES(100)\n"
                                       "-pc_sor_omega -1\n-pc_view\n-schur_amg_ksp_gmres_restart 50\n",
                                       "schur-amg"),
            "-ksp_gmres_restart 50 -ksp_type gmres -pc_sor_omega -1 -pc_view");

  const std::string restart = "-schur_amg_ksp_gmres_restart 50";
  const fs::path dir = fs::temp_directory_path() / "stiction-krylov-settings-test";
  fs::remove_all(dir);
  auto metrics = [&](int level, const std::string& options) {
    write(dir / "runs" / ("block-strips-L" + std::to_string(level) + "-schur-amg") / "metrics.toml",
          "[run]\nbackend_options = '''\n-ksp_type gmres\n" + options + "'''\n");
  };
  metrics(0, "-ksp_gmres_restart 50\n");
  metrics(1, "-ksp_gmres_restart 50\n");
  metrics(2, "-ksp_gmres_restart 100\n" + restart + "\n");
  metrics(3, "-ksp_gmres_restart 100\n");
  write(dir / "runs.csv",
        "scene,level,solver,status,krylov_per_linear_solve,petsc_options\n"
        "block-strips,0,schur-amg,ok,48.3,\n"
        "block-strips,1,schur-amg,ok,63.0,\n"
        "block-strips,2,schur-amg,ok,85.3," + restart + "\n"
        "block-strips,3,schur-amg,ok,99.0,\n");
  const std::string md = krylov_growth_section(read_csv((dir / "runs.csv").string()), dir.string());
  EXPECT_NE(md.find("| L0: 48.3; L1: 63.0; L2: 85.3 (" + restart + "); L3: 99.0 | 1.77 (L0 to L2) |"), std::string::npos)
      << md;
  fs::remove_all(dir);
}

// A fresh sweep directory `name` under the temporary directory, holding runs.csv.
fs::path sweep_with_runs(const std::string& name, const std::string& runs_csv) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  write(dir / "runs.csv", runs_csv);
  return dir;
}

// Two runs of block-strips at level 0: lu-mumps (100 s, 2 s per solve, 600 MB) and
// schur-amg (20 s, 0.25 s, 150 MB), whose top forces differ by 1e-3 relative.
TEST(PaperTables, RatiosMeshCountsAndForcesBesideThePapers) {
  const fs::path dir = sweep_with_runs(
      "stiction-paper-tables-test",
      "scene,level,solver,status,unknowns,unknowns_u_l,unknowns_u_q,unknowns_p,multipliers,vertices,cells,"
      "newton_iterations,krylov_per_linear_solve,wall_seconds,seconds_per_linear_solve,peak_rss_mb,newton_rtol,detail\n"
      "block-strips,0,lu-mumps,ok,49482,8025,41457,0,4029,2675,8900,48,1.0,100,2.0,600,1e-06,\n"
      "block-strips,0,schur-amg,ok,49482,8025,41457,0,4029,2675,8900,48,60.0,20,0.25,150,1e-06,\n");
  const std::string steps = "step,time,reaction_block/top_x,reaction_block/top_y,reaction_block/top_z\n";
  write(dir / "runs/block-strips-L0-lu-mumps/steps.csv", steps + "1,1,0,0,5\n8,8,3,0,-4\n");
  write(dir / "runs/block-strips-L0-schur-amg/steps.csv", steps + "8,8,3.003,0,-4.004\n");
  const std::string md = paper_tables_section(read_csv((dir / "runs.csv").string()), CsvTable{}, dir.string());
  // Table 1: ours / paper with the relative difference.
  EXPECT_NE(md.find("| 0 | 2675 / 2654 (+0.8%) | 8900 / 9714 (-8.4%) | 49482 / 50748 (-2.5%) | 4029 / 3771 (+6.8%) |"),
            std::string::npos)
      << md;
  // Table 2: lu-mumps / schur-amg ratios 5, 8, 4 and the force difference 5e-3 / 5 = 1e-3.
  EXPECT_NE(md.find("| 0 | schur-amg | ok | 20.0 | 0.250 | 150 | 48 | 1e-06 | 60.0 | 5.00 | 8.00 | 4.00 | 1.0e-03 |"),
            std::string::npos)
      << md;
  // The paper's level-0 rows: GlobalLU / SchurMHP = 253.3 / 227.4, 2.13 / 1.25, 683.1 / 266.
  EXPECT_NE(md.find("| 0 | paper SchurMHP | ok | 227.4 | 1.250 | 266 | 57 | — | — | 1.11 | 1.70 | 2.57 | — |"),
            std::string::npos)
      << md;
  EXPECT_EQ(md.find("Table 3"), std::string::npos) << "no block-strips-mr run, no Table 3";
  EXPECT_EQ(md.find("Where the memory goes"), std::string::npos) << "no run recorded memory figures";
  EXPECT_EQ(paper_tables_section(CsvTable{}, CsvTable{}, dir.string()), "");
  fs::remove_all(dir);
}

// A run its time limit stopped after some linear solves shows its figures per solve (and the
// ratio per solve against lu-mumps), its peak memory as a lower bound and no totals; one
// stopped before any solve shows none.
TEST(PaperTables, TimeLimitedRunShowsItsFiguresPerSolve) {
  const fs::path dir = sweep_with_runs(
      "stiction-paper-tables-partial-test",
      "scene,level,solver,status,unknowns,multipliers,newton_iterations,linear_solves,krylov_per_linear_solve,"
      "wall_seconds,seconds_per_linear_solve,peak_rss_mb,detail\n"
      "block-strips,2,lu-mumps,ok,100,10,48,48,1.0,1000,20.0,9000,\n"
      "block-strips,2,fieldsplit-schur,time-limit,100,10,3,3,120.0,7200,800.0,9100,stopped after 7200 s\n"
      "block-strips,2,gamg,time-limit,100,10,0,0,0,3600,0,7000,stopped after 3600 s\n");
  const std::string md = paper_tables_section(read_csv((dir / "runs.csv").string()), CsvTable{}, dir.string());
  EXPECT_NE(md.find("| 2 | fieldsplit-schur | time-limit: stopped after 7200 s | — | 800.000 | ≥ 9100 | — | — | 120.0 | — | "
                    "0.03 | — | — |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| 2 | gamg | time-limit: stopped after 3600 s | — | — | — | — | — | — | — | — | — | — |"),
            std::string::npos)
      << md;
  fs::remove_all(dir);
}

// The total ratio and the force are compared only between runs stopped at the same Newton
// tolerance (time per solve and memory do not depend on it); a run recorded before runs.csv
// had the column gives its tolerance in its steps.csv header.
TEST(PaperTables, TotalsAndForcesOnlyBetweenRunsOfTheSameNewtonTolerance) {
  const fs::path dir = sweep_with_runs(
      "stiction-paper-tables-tolerance-test",
      "scene,level,solver,status,unknowns,newton_iterations,krylov_per_linear_solve,wall_seconds,"
      "seconds_per_linear_solve,peak_rss_mb,newton_rtol,detail\n"
      "block-strips,1,lu-mumps,ok,100,44,1.0,1800,36.0,7500,,\n"
      "block-strips,1,schur-amg,ok,100,50,60.0,600,9.0,1000,1e-06,\n"
      "block-strips,1,schur-gamg,ok,100,60,60.0,900,12.0,1000,1e-08,\n");
  const std::string steps = "step,time,reaction_block/top_x,reaction_block/top_y,reaction_block/top_z\n";
  write(dir / "runs/block-strips-L1-lu-mumps/steps.csv",
        "# solver: lu-mumps; newton atol 1e-10, rtol 1e-08, max_iterations 25, forcing fixed, krylov rtol the "
        "backend's\n" + steps + "8,8,3,0,-4\n");
  write(dir / "runs/block-strips-L1-schur-amg/steps.csv", steps + "8,8,3.003,0,-4.004\n");
  write(dir / "runs/block-strips-L1-schur-gamg/steps.csv", steps + "8,8,3.003,0,-4.004\n");
  const std::string md = paper_tables_section(read_csv((dir / "runs.csv").string()), CsvTable{}, dir.string());
  EXPECT_NE(md.find("| 1 | lu-mumps | ok | 1800.0 | 36.000 | 7500 | 44 | 1e-08 | 1.0 | 1.00 | 1.00 | 1.00 | 0.0e+00 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| 1 | schur-amg | ok | 600.0 | 9.000 | 1000 | 50 | 1e-06 | 60.0 | — | 4.00 | 7.50 | — |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| 1 | schur-gamg | ok | 900.0 | 12.000 | 1000 | 60 | 1e-08 | 60.0 | 2.00 | 3.00 | 7.50 | 1.0e-03 |"),
            std::string::npos)
      << md;
  fs::remove_all(dir);
}

// The memory breakdown reads the solve that held the most heap from each run's metrics.
TEST(PaperTables, MemoryBreakdownAtTheLargestSolve) {
  const fs::path dir = sweep_with_runs(
      "stiction-memory-breakdown-test",
      "scene,level,solver,status,peak_rss_mb,detail\nblock-strips,1,schur-amg,ok,900,\nblock-strips,1,lu-mumps,ok,2000,\n"
      "block-strips,1,ilu-gmres,ok,700,\n");
  write(dir / "runs/block-strips-L1-lu-mumps/metrics.toml",
        "[[linear_solve]]\nmemory_heap_MB = 1500.0\nmemory_matrix_MB = 320.0\nmemory_setup_MB = 1000.0\n"
        "memory_krylov_MB = 0.0\n");
  write(dir / "runs/block-strips-L1-schur-amg/metrics.toml",
        "[[linear_solve]]\nmemory_heap_MB = 600.0\nmemory_matrix_MB = 300.0\nmemory_setup_MB = 50.0\n"
        "memory_block_copies_MB = 20.0\nmemory_krylov_MB = 80.0\n"
        "[[linear_solve]]\nmemory_heap_MB = 700.0\nmemory_matrix_MB = 320.0\nmemory_setup_MB = 60.0\n"
        "memory_block_copies_MB = 25.0\nmemory_krylov_MB = 200.0\nmemory_heap_free_MB = 90.0\n");
  const std::string md = paper_tables_section(read_csv((dir / "runs.csv").string()), CsvTable{}, dir.string());
  // 700 - 320 - 60 - 200 = 120 for the rest, and the freed heap of that solve; a backend
  // without copied blocks says nothing of them, a run without the freed heap has a dash;
  // the run without figures (ilu-gmres) is left out.
  EXPECT_NE(md.find("| block-strips | 1 | schur-amg | 900 | 700 | 320 | 60 (25 copied blocks) | 200 | 120 | 90 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| block-strips | 1 | lu-mumps | 2000 | 1500 | 320 | 1000 | 0 | 180 | — |"), std::string::npos)
      << md;
  EXPECT_EQ(md.find("| block-strips | 1 | ilu-gmres"), std::string::npos) << md;
  fs::remove_all(dir);
}

// The report splits the assembly per Newton iteration into contact and volume for the
// finished runs with contact: 10 Newton iterations, 5 s of assembly, 2 s of it contact
// (0.2 / 0.3 s per iteration, 0.67); a run without contact or that did not finish has no row.
TEST(BenchReport, SplitsTheAssemblyPerNewtonIterationIntoContactAndVolume) {
  const fs::path dir = sweep_with_runs(
      "stiction-assembly-split-test",
      "scene,level,solver,status,newton_iterations,assembly_seconds,contact_assembly_seconds,detail\n"
      "hertz-spheres-3d,1,schur-amg,ok,10,5.0,2.0,\n"
      "block-compression,0,schur-amg,ok,4,1.0,0.0,\n"
      "hertz-spheres-3d,1,gamg,newton-failed,1,0.5,0.1,\n");
  write_bench_report(dir.string());
  std::ifstream in(dir / "report.md");
  const std::string md((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("## Assembly per Newton iteration: contact and volume"), std::string::npos) << md;
  EXPECT_NE(md.find("| hertz-spheres-3d | 1 | schur-amg | 0.500 | 0.200 | 0.300 | 0.67 |"), std::string::npos) << md;
  EXPECT_EQ(md.find("| block-compression | 0 | schur-amg | 0.250 |"), std::string::npos) << md;
  EXPECT_EQ(md.find("| hertz-spheres-3d | 1 | gamg | 0.500 |"), std::string::npos) << md;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace stiction::harness
