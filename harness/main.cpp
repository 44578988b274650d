// stiction: large-deformation contact FEM and a side-by-side benchmark of linear solvers.
//
//   stiction solve SCENE [--level N] [--solver NAME] [--out DIR] [-petsc_option value ...]
//   stiction bench | tradeoff | atlas | replay | report | scenes | solvers  (command_line.cpp)
//
// Arguments of the form -name (one dash) are PETSc options, e.g. -lu_mumps_mat_mumps_icntl_14 50.
// Exit codes: 0 success, 2 bad input, 3 numerical failure, 4 internal error.
#include <fmt/format.h>

#include <cctype>
#include <filesystem>
#include <optional>
#include <ostream>
#include <set>

#include "atlas_report.hpp"
#include "bench_report.hpp"
#include "builtin_scenes.hpp"
#include "command_line.hpp"
#include "mpi_processes.hpp"
#include "readme_headline.hpp"
#include "common/error.hpp"
#include "common/petsc.hpp"
#include "common/process_memory.hpp"
#include "registry.hpp"
#include "run_info.hpp"
#include "scene/scene.hpp"
#include "tradeoff_report.hpp"

using namespace stiction;

namespace {

bool is_petsc_option(const std::string& a) {
  return a.size() > 2 && a[0] == '-' && a[1] != '-' && std::isalpha(static_cast<unsigned char>(a[1]));
}
bool looks_like_value(const std::string& a) {
  return !a.empty() && (a[0] != '-' || (a.size() > 1 && (std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.')));
}

// The command line split into PETSc options ("-key value" pairs) and stiction's own arguments.
struct SplitArguments {
  std::vector<char*> cli, petsc;
  std::set<std::string> petsc_given;
  std::vector<std::string> petsc_pairs;
};

SplitArguments split_arguments(int argc, char** argv) {
  SplitArguments split{{argv[0]}, {argv[0]}, {}, {}};
  for (int i = 1; i < argc; ++i) {
    if (!is_petsc_option(argv[i])) {
      split.cli.push_back(argv[i]);
      continue;
    }
    split.petsc.push_back(argv[i]);
    split.petsc_given.insert(argv[i]);
    std::string pair = argv[i];
    if (i + 1 < argc && looks_like_value(argv[i + 1])) {
      split.petsc.push_back(argv[++i]);
      pair += std::string(" ") + argv[i];
    }
    split.petsc_pairs.push_back(pair);
  }
  return split;
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

// report.md of a sweep directory, whichever sweep wrote it.
void write_report(const std::string& dir) {
  if (std::filesystem::exists(dir + "/tradeoff.csv")) harness::write_tradeoff_report(dir);
  else if (std::filesystem::exists(dir + "/atlas.csv")) harness::write_atlas_report(dir);
  else harness::write_bench_report(dir);
}

// The subcommands that run inside a PETSc session.
void run_petsc_command(harness::CommandLine& cl, const SplitArguments& args, int argc, char** argv) {
  if (*cl.scenes_cmd) list_scenes(cl.schema);
  if (*cl.solvers_cmd) list_solvers();
  if (*cl.solve_cmd) {
    cl.solve.write_vtu = !cl.no_vtu;
    harness::run_solve(cl.solve, harness::collect_run_info(argc, argv));
    reject_unused(args.petsc_given);
  }
  if (*cl.atlas_cmd) harness::run_atlas(cl.atlas, harness::collect_run_info(argc, argv));
  if (*cl.tradeoff_cmd) {
    cl.tradeoff.petsc_options = args.petsc_pairs;
    harness::run_tradeoff(cl.tradeoff, harness::collect_run_info(argc, argv));
  }
  if (*cl.replay_cmd) {
    harness::run_replay(cl.replay, harness::collect_run_info(argc, argv));
    reject_unused(args.petsc_given);
  }
}

}  // namespace


int main(int argc, char** argv) {
  restart_with_huge_pages_for_mapped_blocks(argv);
  SplitArguments args = split_arguments(argc, argv);
  harness::CommandLine cl;
  for (const auto& pair : args.petsc_pairs) cl.solve.petsc_options += pair + "\n";

  const harness::MpiProcesses launched = harness::launched_processes();
  try {
    cl.app.parse(static_cast<int>(args.cli.size()), args.cli.data());
  } catch (const CLI::ParseError& e) {
    std::ostream quiet(nullptr);  // under mpirun, rank 0 alone prints the usage error
    const int code = launched.rank == 0 ? cl.app.exit(e) : cl.app.exit(e, quiet, quiet);
    return code == 0 ? 0 : static_cast<int>(ErrorKind::Input);
  }
  const std::string command = cl.app.get_subcommands().front()->get_name();

  // The sweep and the report start no PETSc: each run is its own `stiction solve` process.
  try {
    if (*cl.bench_cmd || *cl.report_cmd) harness::require_one_process(launched, command);
    if (*cl.bench_cmd) {
      cl.bench.petsc_options = args.petsc_pairs;
      harness::run_bench(cl.bench, harness::collect_run_info(argc, argv));
      return 0;
    }
    if (*cl.report_cmd && cl.report_headline) {
      fmt::print("{}", harness::readme_headline(cl.report_dir));
      return 0;
    }
    if (*cl.report_cmd) {
      write_report(cl.report_dir);
      return 0;
    }
  } catch (const Error& e) {
    return harness::report_failure(launched, e.kind(), e.reach(), e.what(), false);
  }

  // argv[argc] is a null pointer (C 5.1.2.2.1): Open MPI's MPI_Init walks the array to it,
  // and without one it read past the end (a crash inside MPI_Init whenever a PETSc option
  // was given, depending on what lay after the vector).
  int petsc_argc = static_cast<int>(args.petsc.size());
  args.petsc.push_back(nullptr);
  char** petsc_args = args.petsc.data();
  std::optional<PetscSession> petsc;
  try {
    petsc.emplace(&petsc_argc, &petsc_args);
  } catch (const Error& e) {
    return harness::report_failure(launched, e.kind(), e.reach(), e.what(), false);
  }
  // Failures are reported while MPI is up, so that one met by a single process can end the job.
  const harness::MpiProcesses processes = harness::petsc_processes();
  try {
    if (!*cl.solve_cmd) harness::require_one_process(processes, command);
    run_petsc_command(cl, args, argc, argv);
  } catch (const Error& e) {
    return harness::report_failure(processes, e.kind(), e.reach(), e.what(), true);
  } catch (const std::exception& e) {
    return harness::report_failure(processes, ErrorKind::Internal, Reach::OneProcess, e.what(), true,
                                   "internal error");
  }
  return 0;
}
