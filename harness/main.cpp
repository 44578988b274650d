// stiction: large-deformation contact FEM and a side-by-side benchmark of linear solvers.
//
//   stiction solve SCENE [--level N] [--solver NAME] [--out DIR] [-petsc_option value ...]
//   stiction scenes [--schema]
//   stiction solvers
//
// Arguments of the form -name (one dash) are PETSc options, e.g. -lu_mumps_mat_mumps_icntl_14 50.
// Exit codes: 0 success, 2 bad input, 3 numerical failure, 4 internal error.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cctype>
#include <filesystem>
#include <optional>
#include <ostream>
#include <set>

#include "atlas_command.hpp"
#include "atlas_report.hpp"
#include "bench_command.hpp"
#include "bench_report.hpp"
#include "builtin_scenes.hpp"
#include "mpi_processes.hpp"
#include "common/error.hpp"
#include "common/petsc.hpp"
#include "common/process_memory.hpp"
#include "registry.hpp"
#include "run_info.hpp"
#include "scene/scene.hpp"
#include "replay_command.hpp"
#include "solve_command.hpp"
#include "tradeoff_command.hpp"
#include "tradeoff_report.hpp"

using namespace stiction;

namespace {

bool is_petsc_option(const std::string& a) {
  return a.size() > 2 && a[0] == '-' && a[1] != '-' && std::isalpha(static_cast<unsigned char>(a[1]));
}
bool looks_like_value(const std::string& a) {
  return !a.empty() && (a[0] != '-' || (a.size() > 1 && (std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.')));
}

void list_scenes(bool schema) {
  if (schema) {
    fmt::print("Scene file keys (TOML):\n{}", scene::document(scene::scene_schema(), "  "));
    return;
  }
  for (const auto& [name, text] : harness::builtin_scenes()) fmt::print("{:<24} {}\n", name, harness::scene_summary(text));
}

void list_solvers() {
  for (const auto& b : solvers::backends()) {
    const std::string why = b.unavailable_reason();
    fmt::print("{:<14} {:<12} {}\n", b.name, why.empty() ? "available" : "unavailable", b.description);
    if (!why.empty()) fmt::print("{:<14} {}\n", "", why);
  }
}

// PETSc options the user gave that nothing used: a typo or a backend that was not run.
void reject_unused(const std::set<std::string>& given) {
  PetscInt n = 0;
  char** names = nullptr;
  char** values = nullptr;
  STICTION_PETSC(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  std::string unused;
  for (PetscInt i = 0; i < n; ++i)
    if (given.count(std::string("-") + names[i])) unused += fmt::format(" -{}", names[i]);
  PetscOptionsLeftRestore(nullptr, &n, &names, &values);
  if (!unused.empty())
    throw Error(fmt::format("PETSc option(s) not used by the chosen backend:{} (check the name and prefix; "
                            "`stiction solvers` lists the backends)", unused));
}

}  // namespace

int main(int argc, char** argv) {
  restart_with_huge_pages_for_mapped_blocks(argv);
  std::vector<char*> cli_argv{argv[0]}, petsc_argv{argv[0]};
  std::set<std::string> petsc_given;
  std::vector<std::string> petsc_pairs;  // "-key value", as given
  harness::SolveOptions solve;
  for (int i = 1; i < argc; ++i) {
    if (is_petsc_option(argv[i])) {
      petsc_argv.push_back(argv[i]);
      petsc_given.insert(argv[i]);
      std::string pair = argv[i];
      if (i + 1 < argc && looks_like_value(argv[i + 1])) {
        petsc_argv.push_back(argv[++i]);
        pair += std::string(" ") + argv[i];
      }
      solve.petsc_options += pair + "\n";
      petsc_pairs.push_back(pair);
    } else {
      cli_argv.push_back(argv[i]);
    }
  }

  CLI::App app{"stiction: large-deformation frictional contact by FEM, and a benchmark of the linear solvers of its "
               "Newton systems"};
  app.require_subcommand(1);
  auto* solve_cmd = app.add_subcommand("solve", "solve a scene with one linear-solver backend");
  solve_cmd->add_option("scene", solve.scene, "scene file (.toml) or built-in scene name")->required();
  solve_cmd->add_option("--level", solve.level, "mesh level (uniform refinements of level 0)")->check(CLI::Range(0, 4));
  solve_cmd->add_option("--solver", solve.solver, "linear-solver backend (see `stiction solvers`)");
  solve_cmd->add_option("--out", solve.out_dir, "output directory (default out/<scene>-L<level>)");
  solve_cmd->add_flag("--quiet", solve.quiet, "no progress on stderr");
  solve_cmd->add_option("--metrics", solve.metrics_path, "write a TOML record of the run (used by `stiction bench`)");
  solve_cmd->add_option("--record", solve.record_dir, "record every Newton system here (see `stiction replay`)");
  solve_cmd->add_option("--forcing", solve.forcing, "Krylov tolerance per Newton step: fixed or eisenstat-walker")
      ->check(CLI::IsMember({"fixed", "eisenstat-walker"}));
  solve_cmd
      ->add_option("--krylov-rtol", solve.krylov_rtol,
                   "relative tolerance of every Krylov solve, overriding the scene's newton.krylov_rtol (0: the "
                   "backend's -ksp_rtol)")
      ->check(CLI::Range(0.0, 1.0));
  solve_cmd->add_option("--set", solve.overrides,
                        "set a scene key, KEY=VALUE (contact[0].friction=0.6, newton.max_iterations=40); repeatable");
  solve_cmd
      ->add_option("--newton-rtol", solve.newton_rtol,
                   "Newton tolerance relative to each step's reference residual, overriding the scene's newton.rtol")
      ->check(CLI::Range(0.0, 1.0));
  bool no_vtu = false;
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
  harness::ReplayOptions replay;
  auto* replay_cmd = app.add_subcommand("replay", "solve recorded Newton systems with a backend");
  replay_cmd->add_option("record", replay.record_dir, "folder written by `stiction solve --record`")->required();
  replay_cmd->add_option("--solver", replay.solver, "linear-solver backend (see `stiction solvers`)");
  replay_cmd->add_option("--csv", replay.csv_path, "also write the table as CSV");
  replay_cmd->add_option("--krylov-rtol", replay.krylov_rtol,
                         "relative tolerance of each Krylov solve: 'recorded' (default: the recording solve's, unless "
                         "-<backend>_ksp_rtol is given), 'backend' (the backend's own) or a number");
  bool schema = false;
  auto* scenes_cmd = app.add_subcommand("scenes", "list the built-in scenes");
  scenes_cmd->add_flag("--schema", schema, "print every key a scene file accepts");
  auto* solvers_cmd = app.add_subcommand("solvers", "list the linear-solver backends");

  harness::BenchOptions bench;
  auto* bench_cmd = app.add_subcommand("bench", "sweep scenes x solvers x mesh levels, each run in its own process");
  bench_cmd->add_option("--scenes", bench.scenes, "scenes (comma separated; default: every built-in)")->delimiter(',');
  bench_cmd->add_option("--solvers", bench.solvers, "backends (comma separated; default: every backend)")->delimiter(',');
  bench_cmd->add_option("--levels", bench.levels, "mesh levels (comma separated; default 0)")->delimiter(',');
  bench_cmd->add_option("--ranks", bench.ranks,
                        "MPI processes per run, comma separated (default 1; above 1 each run is `mpirun -n N stiction "
                        "solve ...`, and the report adds a strong-scaling table)")
      ->delimiter(',');
  bench_cmd->add_option("--out", bench.out_dir, "output directory (runs.csv, steps.csv, report.md, runs/)");
  bench_cmd->add_flag("--resume", bench.resume, "continue a sweep: skip the runs already in runs.csv");
  bench_cmd->add_flag("--quick", bench.quick, "every scene's short version (stiction solve --quick)");
  bench_cmd->add_option("--time-limit", bench.time_limit_seconds, "wall-time limit per run, seconds (default 3600)");
  bench_cmd->add_option("--memory-limit-mb", bench.memory_limit_mb, "resident-memory limit per run (default 90% of RAM)");
  bench_cmd->add_option("--forcing", bench.forcing, "Newton forcing for every run: fixed or eisenstat-walker")
      ->check(CLI::IsMember({"fixed", "eisenstat-walker"}));
  bench_cmd
      ->add_option("--krylov-rtol", bench.krylov_rtol,
                   "Krylov tolerance for every run (stiction solve --krylov-rtol; default: each scene's)")
      ->check(CLI::Range(0.0, 1.0));
  harness::TradeoffOptions tradeoff;
  auto* tradeoff_cmd = app.add_subcommand("tradeoff", "speed against accuracy: knobs swept against a tight reference");
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
  harness::AtlasOptions atlas;
  auto* atlas_cmd = app.add_subcommand("atlas", "where each backend breaks: scene keys swept one at a time");
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
  std::string report_dir;
  auto* report_cmd = app.add_subcommand("report", "rebuild report.md of a sweep from its CSV files");
  report_cmd->add_option("dir", report_dir, "the sweep's output directory")->required();

  const harness::MpiProcesses launched = harness::launched_processes();
  try {
    app.parse(static_cast<int>(cli_argv.size()), cli_argv.data());
  } catch (const CLI::ParseError& e) {
    std::ostream quiet(nullptr);  // under mpirun, rank 0 alone prints the usage error
    const int code = launched.rank == 0 ? app.exit(e) : app.exit(e, quiet, quiet);
    return code == 0 ? 0 : static_cast<int>(ErrorKind::Input);
  }
  const std::string command = app.get_subcommands().front()->get_name();

  // The sweep and the report start no PETSc: each run is its own `stiction solve` process.
  try {
    if (*bench_cmd || *report_cmd) harness::require_one_process(launched, command);
    if (*bench_cmd) {
      bench.petsc_options = petsc_pairs;
      harness::run_bench(bench, harness::collect_run_info(argc, argv));
      return 0;
    }
    if (*report_cmd) {
      if (std::filesystem::exists(report_dir + "/tradeoff.csv")) harness::write_tradeoff_report(report_dir);
      else if (std::filesystem::exists(report_dir + "/atlas.csv")) harness::write_atlas_report(report_dir);
      else harness::write_bench_report(report_dir);
      return 0;
    }
  } catch (const Error& e) {
    return harness::report_failure(launched, e.kind(), e.reach(), e.what(), false);
  }

  // argv[argc] is a null pointer (C 5.1.2.2.1): Open MPI's MPI_Init walks the array to it,
  // and without one it read past the end (a crash inside MPI_Init whenever a PETSc option
  // was given, depending on what lay after the vector).
  int petsc_argc = static_cast<int>(petsc_argv.size());
  petsc_argv.push_back(nullptr);
  char** petsc_args = petsc_argv.data();
  std::optional<PetscSession> petsc;
  try {
    petsc.emplace(&petsc_argc, &petsc_args);
  } catch (const Error& e) {
    return harness::report_failure(launched, e.kind(), e.reach(), e.what(), false);
  }
  // Failures are reported while MPI is up, so that one met by a single process can end the job.
  const harness::MpiProcesses processes = harness::petsc_processes();
  try {
    if (!*solve_cmd) harness::require_one_process(processes, command);
    if (*scenes_cmd) list_scenes(schema);
    if (*solvers_cmd) list_solvers();
    if (*solve_cmd) {
      solve.write_vtu = !no_vtu;
      harness::run_solve(solve, harness::collect_run_info(argc, argv));
      reject_unused(petsc_given);
    }
    if (*atlas_cmd) harness::run_atlas(atlas, harness::collect_run_info(argc, argv));
    if (*tradeoff_cmd) {
      tradeoff.petsc_options = petsc_pairs;
      harness::run_tradeoff(tradeoff, harness::collect_run_info(argc, argv));
    }
    if (*replay_cmd) {
      harness::run_replay(replay, harness::collect_run_info(argc, argv));
      reject_unused(petsc_given);
    }
  } catch (const Error& e) {
    return harness::report_failure(processes, e.kind(), e.reach(), e.what(), true);
  } catch (const std::exception& e) {
    return harness::report_failure(processes, ErrorKind::Internal, Reach::OneProcess, e.what(), true,
                                   "internal error");
  }
  return 0;
}
