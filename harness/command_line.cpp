#include "command_line.hpp"

namespace stiction::harness {

namespace {

// --forcing and --krylov-rtol, which solve and bench share (their help texts differ).
void add_krylov_tolerance_options(CLI::App* cmd, std::string& forcing, const std::string& forcing_help,
                                  double& krylov_rtol, const std::string& krylov_rtol_help) {
  cmd->add_option("--forcing", forcing, forcing_help + ": fixed or eisenstat-walker")
      ->check(CLI::IsMember({"fixed", "eisenstat-walker"}));
  cmd->add_option("--krylov-rtol", krylov_rtol, krylov_rtol_help)->check(CLI::Range(0.0, 1.0));
}

}  // namespace

CommandLine::CommandLine()
    : app{"stiction: large-deformation frictional contact by FEM, and a benchmark of the linear solvers of its "
          "Newton systems"} {
  app.require_subcommand(1);
  declare_solve();
  declare_replay();
  scenes_cmd = app.add_subcommand("scenes", "list the built-in scenes");
  scenes_cmd->add_flag("--schema", schema, "print every key a scene file accepts");
  solvers_cmd = app.add_subcommand("solvers", "list the linear-solver backends");
  declare_bench();
  declare_tradeoff();
  declare_atlas();
  report_cmd = app.add_subcommand("report", "rebuild report.md of a sweep from its CSV files");
  report_cmd->add_option("dir", report_dir, "the sweep's output directory")->required();
  report_cmd->add_flag("--headline", report_headline,
                       "print README.md's headline table from the sweep (a published reports/paper-tables) instead");
}

void CommandLine::declare_solve() {
  solve_cmd = app.add_subcommand("solve", "solve a scene with one linear-solver backend");
  solve_cmd->add_option("scene", solve.scene, "scene file (.toml) or built-in scene name")->required();
  solve_cmd->add_option("--level", solve.level, "mesh level (uniform refinements of level 0)")->check(CLI::Range(0, 4));
  solve_cmd->add_option("--solver", solve.solver, "linear-solver backend (see `stiction solvers`)");
  solve_cmd->add_option("--out", solve.out_dir, "output directory (default out/<scene>-L<level>)");
  solve_cmd->add_flag("--quiet", solve.quiet, "no progress on stderr");
  solve_cmd->add_option("--metrics", solve.metrics_path, "write a TOML record of the run (used by `stiction bench`)");
  solve_cmd->add_option("--record", solve.record_dir, "record every Newton system here (see `stiction replay`)");
  solve_cmd->add_option("--record-only", solve.record_only,
                        "with --record, only these systems: STEP:ITERATION (load step, Newton iteration from 1), "
                        "comma separated")
      ->delimiter(',');
  add_krylov_tolerance_options(solve_cmd, solve.forcing, "Krylov tolerance per Newton step", solve.krylov_rtol,
                               "relative tolerance of every Krylov solve, overriding the scene's newton.krylov_rtol "
                               "(0: the backend's -ksp_rtol)");
  solve_cmd->add_option("--set", solve.overrides,
                        "set a scene key, KEY=VALUE (contact[0].friction=0.6, newton.max_iterations=40); repeatable");
  solve_cmd
      ->add_option("--newton-rtol", solve.newton_rtol,
                   "Newton tolerance relative to each step's reference residual, overriding the scene's newton.rtol")
      ->check(CLI::Range(0.0, 1.0));
  solve_cmd->add_flag("--no-vtu", no_vtu, "do not write VTU/PVD output");
  solve_cmd->add_option("--until", solve.until, "stop after the load step that reaches this pseudo-time")
      ->check(CLI::NonNegativeNumber);
  solve_cmd->add_flag("--trace-contact", solve.trace_contact,
                     "print each contact state change per Newton iteration (node, gap, multiplier, position)");
  solve_cmd->add_flag("--quick", solve.quick, "the scene's short version: stop at its load.quick_until");
  solve_cmd->add_flag("--whole-mesh", solve.whole_mesh,
                      "under mpirun, every process holds the whole mesh (default: each its part, refined "
                      "where it is when the scene's levels are refinements of level 0)");
  solve_cmd->add_option("--restart", solve.restart_dir,
                        "continue a failed or killed run from DIR/checkpoint.bin (output appended in DIR unless --out)");
}

void CommandLine::declare_replay() {
  replay_cmd = app.add_subcommand("replay", "solve recorded Newton systems with a backend");
  replay_cmd->add_option("record", replay.record_dir, "folder written by `stiction solve --record`")->required();
  replay_cmd->add_option("--solver", replay.solver, "linear-solver backend (see `stiction solvers`)");
  replay_cmd->add_option("--csv", replay.csv_path, "also write the table as CSV");
  replay_cmd->add_flag("--stop-on-failure", replay.stop_on_failure,
                       "stop at the first system whose solve does not converge");
  replay_cmd->add_option("--krylov-rtol", replay.krylov_rtol,
                         "relative tolerance of each Krylov solve: 'recorded' (default: the recording solve's, unless "
                         "-<backend>_ksp_rtol is given), 'backend' (the backend's own) or a number; the GMRES restart "
                         "is the recording solve's except under 'backend' or with -<backend>_ksp_gmres_restart");
}

void CommandLine::declare_bench() {
  bench_cmd = app.add_subcommand("bench", "sweep scenes x solvers x mesh levels, each run in its own process");
  bench_cmd->add_option("--scenes", bench.scenes, "scenes (comma separated; default: every built-in)")->delimiter(',');
  bench_cmd->add_option("--solvers", bench.solvers, "backends (comma separated; default: every backend)")->delimiter(',');
  bench_cmd->add_option("--levels", bench.levels, "mesh levels (comma separated; default 0)")->delimiter(',');
  bench_cmd->add_option("--ranks", bench.ranks,
                        "MPI processes per run, comma separated (default 1; above 1 each run is `mpirun -n N stiction "
                        "solve ...`, and the report adds a strong-scaling table)")
      ->delimiter(',');
  bench_cmd->add_option("--out", bench.out_dir, "output directory (runs.csv, steps.csv, report.md, runs/)");
  bench_cmd->add_flag("--resume", bench.resume, "continue a sweep: skip the runs already in runs.csv");
  bench_cmd->add_flag("--allow-other-revision", bench.allow_other_revision,
                      "with --resume, accept a binary of another revision than the one that started the sweep");
  bench_cmd->add_option("--sample", bench.sample,
                        "record these Newton systems (STEP:ITERATION, comma separated) on one whole run per scene and "
                        "level, and time every backend on them (samples.csv)")
      ->delimiter(',');
  bench_cmd->add_option("--path-solver", bench.path_solver,
                        "with --sample, the backend whose whole runs solve each Newton path and record it (schur-amg)");
  bench_cmd->add_option("--whole", bench.whole,
                        "with --sample, more whole runs beside the path run: SOLVER:LEVEL, comma separated")
      ->delimiter(',');
  bench_cmd->add_flag("--quick", bench.quick, "every scene's short version (stiction solve --quick)");
  bench_cmd->add_option("--time-limit", bench.time_limit_seconds, "wall-time limit per run, seconds (default 3600)");
  bench_cmd->add_option("--memory-limit-mb", bench.memory_limit_mb, "resident-memory limit per run (default 90% of RAM)");
  add_krylov_tolerance_options(bench_cmd, bench.forcing, "Newton forcing for every run", bench.krylov_rtol,
                               "Krylov tolerance for every run (stiction solve --krylov-rtol; default: each scene's)");
}

void CommandLine::declare_tradeoff() {
  tradeoff_cmd = app.add_subcommand("tradeoff", "speed against accuracy: knobs swept against a tight reference");
  tradeoff_cmd->add_option("scene", tradeoff.scene, "scene file (.toml) or built-in scene name")->required();
  tradeoff_cmd->add_option("--level", tradeoff.level, "mesh level")->check(CLI::Range(0, 4));
  tradeoff_cmd->add_option("--solvers", tradeoff.solvers, "backends (comma separated; default schur-amg)")->delimiter(',');
  tradeoff_cmd->add_option("--newton-rtols", tradeoff.newton_rtols, "Newton tolerances (default 1e-4,1e-6,1e-8)")
      ->delimiter(',');
  tradeoff_cmd->add_option("--krylov-rtols", tradeoff.krylov_rtols,
                           "Krylov tolerances of the iterative backends (default 1e-2,1e-4,1e-6,1e-8)")
      ->delimiter(',');
  tradeoff_cmd->add_option("--forcings", tradeoff.forcings, "fixed and/or eisenstat-walker (default fixed)")
      ->delimiter(',');
  tradeoff_cmd->add_option("--knob", tradeoff.knobs,
                           "a backend's own knob, option=v1,v2,... (PETSc option without its dash); repeatable");
  tradeoff_cmd->add_option("--coarser-levels", tradeoff.coarser_levels,
                           "mesh levels below --level where every backend also runs at its defaults (comma separated)")
      ->delimiter(',')
      ->check(CLI::Range(0, 3));
  tradeoff_cmd->add_flag("--discretisation", tradeoff.discretisation,
                         "also solve the reference one level finer: the discretisation error beside the solver's");
  tradeoff_cmd->add_option("--reference-solver", tradeoff.reference_solver, "backend of the reference (lu-mumps)");
  tradeoff_cmd->add_option("--reference-newton-rtol", tradeoff.reference_newton_rtol,
                           "Newton tolerance of the reference (1e-12)");
  tradeoff_cmd->add_option("--out", tradeoff.out_dir, "output directory (tradeoff.csv, report.md, runs/)");
  tradeoff_cmd->add_flag("--resume", tradeoff.resume, "continue a sweep: skip the runs already in tradeoff.csv");
  tradeoff_cmd->add_option("--time-limit", tradeoff.time_limit_seconds, "wall-time limit per run, seconds (3600)");
  tradeoff_cmd->add_option("--memory-limit-mb", tradeoff.memory_limit_mb, "resident-memory limit per run (90% of RAM)");
}

void CommandLine::declare_atlas() {
  atlas_cmd = app.add_subcommand("atlas", "where each backend breaks: scene keys swept one at a time");
  atlas_cmd->add_option("scene", atlas.scene, "base scene file (.toml) or built-in scene name")->required();
  atlas_cmd->add_option("--level", atlas.level, "mesh level")->check(CLI::Range(0, 4));
  atlas_cmd->add_option("--solvers", atlas.solvers, "backends (comma separated; default schur-amg,lu-mumps)")
      ->delimiter(',');
  atlas_cmd->add_option("--axis", atlas.axes, "KEY=v1,v2,... (a scene key path, or level; ';' between values that hold commas); repeatable");
  atlas_cmd
      ->add_option("--pair", atlas.pairs,
                   "two axes swept together, KEY1=v1,v2,... KEY2=w1,w2,... (every combination); repeatable")
      ->expected(2)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  atlas_cmd->add_option("--out", atlas.out_dir, "output directory (atlas.csv, report.md, runs/)");
  atlas_cmd->add_flag("--resume", atlas.resume, "continue: skip the cells already in atlas.csv");
  atlas_cmd->add_option("--set", atlas.base, "a key of the base scene, KEY=VALUE, in every cell; repeatable");
  atlas_cmd->add_flag("--quick", atlas.quick, "every cell runs the scene's short version (its load.quick_until)");
  atlas_cmd->add_option("--time-limit", atlas.time_limit_seconds, "wall-time limit per cell, seconds (600)");
  atlas_cmd->add_option("--memory-limit-mb", atlas.memory_limit_mb, "resident-memory limit per cell (90% of RAM)");
}

}  // namespace stiction::harness
