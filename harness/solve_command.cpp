#include "solve_command.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>

#include "checkpoint.hpp"
#include "common/error.hpp"
#include "contact/contact_state.hpp"
#include "ksp_solver.hpp"
#include "registry.hpp"
#include "run_output.hpp"
#include "run_scene.hpp"
#include "run_metrics.hpp"
#include "system_record.hpp"

namespace stiction::harness {
namespace {

// One line per changed contact state, on stderr: where the node is, its gap and multiplier,
// so a cycling or wandering active set can be read per Newton iteration.
void print_state_change(const nonlinear::QuasiStaticSolver::StateChange& c, const scene::SceneView& view) {
  const auto& n = c.after;
  const auto state = [](char s) { return contact::to_string(static_cast<contact::NodeState>(s)); };
  const double lt = std::hypot(n.tangential[0], n.tangential[1], n.tangential[2]);
  fmt::print(stderr,
             "  step {} iteration {}: {} node {} (vertex {}) {} -> {}, gap {:.3e}, lambda_n {:.3e}, |lambda_t| {:.3e}, "
             "x ({:.6g}, {:.6g}, {:.6g})\n",
             c.step, c.iteration, c.constraint, c.node, view.whole_vertex(n.vertex), state(c.before), state(n.state), n.gap, n.normal, lt,
             n.position[0], n.position[1], n.position[2]);
}

// The scene's GMRES restart as the options text it stands for, for a backend whose options
// set one (a GMRES backend); empty otherwise.
std::string scene_restart_options(const SolveOptions& o, const nonlinear::NewtonSettings& newton) {
  if (newton.krylov_restart <= 0 || solvers::default_options(o.solver).find("-ksp_gmres_restart") == std::string::npos)
    return "";
  return fmt::format("# the scene's newton.krylov_restart\n-ksp_gmres_restart {}\n", newton.krylov_restart);
}

// The comment lines every table of the run starts with: provenance, scene, bodies, mesh and
// unknowns (whole), solver and Newton settings.
std::string describe_run(const SolveOptions& o, const RunInfo& info, const scene::SceneView& view,
                         const std::string& krylov_rtol_origin) {
  const scene::Scene& scene = *view.scene;
  const nonlinear::NewtonSettings& newton = scene.newton;
  std::string header = format_run_info(info, "# ");
  header += fmt::format("# scene: {} ({}), level {}, basis {}\n", scene.name, scene.origin, view.level,
                        fem::to_string(view.space->kind()));
  for (size_t b = 0; b < scene.body_names.size(); ++b)
    header += fmt::format("# body {}: {}\n", scene.body_names[b], scene.material_of_body[b]);
  header += fmt::format("# mesh: {} vertices, {} cells; unknowns: u_l {}, u_q {}, total {}\n", view.n_vertices,
                        view.n_cells, view.n_linear, view.n_quadratic, view.n_dofs());
  header += fmt::format("# solver: {}; newton atol {:g}, rtol {:g}, max_iterations {}, forcing {}, krylov rtol {}, "
                        "gmres restart {}\n",
                        o.solver, newton.atol, newton.rtol, newton.max_iterations, nonlinear::to_string(newton.forcing),
                        newton.krylov_rtol > 0 ? fmt::format("{:g} ({})", newton.krylov_rtol, krylov_rtol_origin)
                                               : std::string("the backend's"),
                        scene_restart_options(o, newton).empty()
                            ? std::string("the backend's")
                            : fmt::format("{} (scene)", newton.krylov_restart));
  return header;
}

// The header line of a run on several processes: how the cells were split and what each
// process holds.
std::string describe_processes(const RunScene& run, int processes, const std::string& partitioner) {
  if (!run.part)
    return fmt::format("# MPI processes: {} (cells split by {}; the mesh whole on each, the Newton state held per "
                       "process)\n", processes, partitioner);
  return fmt::format("# MPI processes: {} (cells split by {}{}; each holds its part of the mesh{}, with the space "
                     "and the Newton state over it)\n", processes, run.part->partitioner,
                     run.refined_in_parts > 0
                         ? fmt::format(" at level 0, each part then refined to level {} where it is", run.level())
                         : std::string(),
                     run.part->contacts.empty() ? "" : " and the contact surfaces whole");
}

// The command line's Newton settings over the scene's; returns where the Krylov tolerance
// comes from. Its precedence: --krylov-rtol, then a -<backend>_ksp_rtol given by the user
// (command line, PETSC_OPTIONS), then the scene's newton.krylov_rtol, then the backend's
// options file. The GMRES restart's: -<backend>_ksp_gmres_restart given by the user, then
// the scene's newton.krylov_restart, then the options file. Called before the backend is
// created (solvers::backend_option_given).
std::string apply_newton_options(const SolveOptions& o, nonlinear::NewtonSettings& newton) {
  if (!o.forcing.empty()) newton.forcing = nonlinear::forcing_from_string(o.forcing);
  if (o.newton_rtol >= 0) newton.rtol = o.newton_rtol;
  if (solvers::backend_option_given(o.solver, "ksp_gmres_restart")) newton.krylov_restart = 0;
  if (o.krylov_rtol >= 0) {
    newton.krylov_rtol = o.krylov_rtol;
    return "--krylov-rtol";
  }
  if (solvers::backend_option_given(o.solver, "ksp_rtol")) newton.krylov_rtol = 0;
  return "scene";
}

// The checkpoint of --restart, checked against the scene and level being run.
Checkpoint read_resume(const SolveOptions& o, const RunScene& run) {
  Checkpoint resume = read_checkpoint(PETSC_COMM_WORLD, o.restart_dir + "/checkpoint.bin");
  if (resume.scene != run.scene->name || resume.level != run.level())
    throw Error(fmt::format("checkpoint in '{}' is of scene '{}' level {}, not '{}' level {}", o.restart_dir,
                            resume.scene, resume.level, run.scene->name, run.level()));
  return resume;
}

// The --metrics record; a restarted run's record continues the earlier segments'.
std::unique_ptr<RunRecorder> make_recorder(const SolveOptions& o, const RunScene& run, int processes,
                                           const Checkpoint* resume, std::chrono::steady_clock::time_point t_start) {
  // The options the backend ran with: its defaults, then the scene's restart, then
  // PETSC_OPTIONS, then the command line's (a later option of the same key won).
  const char* environment = std::getenv("PETSC_OPTIONS");
  const std::string from_environment =
      environment && *environment ? fmt::format("# PETSC_OPTIONS\n{}\n", environment) : std::string();
  RunSummary base{o.solver, solvers::default_options(o.solver) + scene_restart_options(o, run.scene->newton) +
                                from_environment + o.petsc_options};
  base.processes = processes;
  return std::make_unique<RunRecorder>(
      o.metrics_path, *run.view, base, PETSC_COMM_WORLD,
      resume ? read_earlier_segments(o.metrics_path, run.scene->name, run.level(), o.solver, resume->state.step)
             : std::nullopt,
      t_start);
}

void print_step_line(const nonlinear::StepResult& r, int n_steps) {
  fmt::print(stderr, "step {}/{}{}: t = {:.6g}, {} after {} Newton iterations, residual {:.3e} (reference {:.3e}), "
             "{:.2f} s{}\n",
             r.step, n_steps, r.cut > 0 ? fmt::format(" (increment / {})", 1 << r.cut) : "", r.time,
             nonlinear::to_string(r.reason), r.iterations.size(), r.final_residual, r.reference_residual,
             r.wall_seconds, r.retried ? "; retried over half the increment" : "");
}

}  // namespace

void run_solve(const SolveOptions& o, const RunInfo& info) {
  const auto t_start = std::chrono::steady_clock::now();
  // On several MPI processes rank 0 alone prints the progress and writes the files, but
  // for each process's piece of a VTU, which it writes from the state it holds.
  int rank = 0, processes = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &processes);
  const bool writer = rank == 0;
  if (processes > 1 && !o.record_dir.empty())
    throw Error(fmt::format("--record runs on one MPI process (launched on {})", processes));
  RunScene run = open_run_scene(PETSC_COMM_WORLD, o.scene, o.level, o.overrides, o.whole_mesh);
  auto& scene = run.scene;
  const scene::SceneView& view = *run.view;
  const std::string krylov_rtol_origin = apply_newton_options(o, scene->newton);
  auto solver = solvers::create_solver(o.solver, PETSC_COMM_WORLD);
  const bool restart = !o.restart_dir.empty();
  std::string out_dir = o.out_dir.empty() ? fmt::format("out/{}-L{}", scene->name, run.level()) : o.out_dir;
  if (restart && o.out_dir.empty()) out_dir = o.restart_dir;
  const Checkpoint resume = restart ? read_resume(o, run) : Checkpoint{};
  std::error_code ec;
  if (writer) std::filesystem::create_directories(out_dir, ec);
  if (ec) throw Error(fmt::format("cannot create output directory '{}': {}", out_dir, ec.message()));

  std::string header = describe_run(o, info, view, krylov_rtol_origin);
  if (restart)
    header += fmt::format("# restarted from '{}' after load step {} (t = {:g})\n", o.restart_dir, resume.state.step,
                          resume.state.time);
  const auto newton_ptr = make_quasi_static_solver(PETSC_COMM_WORLD, run, *solver);
  nonlinear::QuasiStaticSolver& newton = *newton_ptr;
  if (processes > 1) header += describe_processes(run, processes, newton.partition().partitioner);
  const bool verbose = !o.quiet && writer;
  if (verbose) fmt::print(stderr, "{}", header);
  RunOutput output(run, newton, out_dir, header, restart, o.write_vtu);
  if (restart) {
    newton.restore(resume.state);
    newton.set_linear_tally(resume.tally);
    newton.set_cut_back(resume.cut_back);
  }
  if (!o.record_dir.empty()) {
    const RecordContext context{scene->name, run.level(), o.solver, info};
    const std::set<std::pair<int, int>> only = parse_system_selection(o.record_only);
    newton.set_system_observer([&, context, only](const nonlinear::NewtonSystem& sys, Vec du,
                                                  const nonlinear::LinearSolveStats& stats, int step, int iteration) {
      if (only.empty() || only.count({step, iteration})) record_system(o.record_dir, sys, du, stats, step, iteration, context);
    });
  } else if (!o.record_only.empty()) {
    throw Error("--record-only needs --record DIR");
  }
  if (o.trace_contact && writer) newton.set_state_change_observer(
      [&view](const nonlinear::QuasiStaticSolver::StateChange& c) { print_state_change(c, view); });
  std::unique_ptr<RunRecorder> record;
  if (!o.metrics_path.empty()) {
    record = make_recorder(o, run, processes, restart ? &resume : nullptr, t_start);
    newton.set_iteration_observer(
        [&](int step, double t, const nonlinear::NewtonIteration& it) { record->add_iteration(step, t, it); });
  }
  double until = o.until >= 0 ? o.until : std::numeric_limits<double>::infinity();
  if (o.quick) until = std::min(until, scene->quick_until);
  const int first_step = restart ? resume.state.step + 1 : 1;
  auto results = newton.run([&](const nonlinear::StepResult& r) {
    output.add_rows(r);
    if (record) record->add(r);  // before the checkpoint
    if (r.completes_step) output.complete_step(r);
    if (verbose) print_step_line(r, scene->problem.n_steps());
  }, first_step, scene->problem.step_reaching(until));
  if (results.empty()) {
    if (verbose) fmt::print(stderr, "nothing to do: the run had completed load step {}\n", first_step - 1);
    return;
  }
  const std::string description = solver->describe();  // collective: a KSP view
  if (writer) std::ofstream(out_dir + "/solver.txt") << description;
  const auto& last = results.back();
  if (record) record->finish();
  if (!last.converged())
    throw Error(fmt::format("Newton did not converge at load step {} of scene '{}': {}{}{}", last.step, scene->name,
                            nonlinear::to_string(last.reason), last.detail.empty() ? "" : ": ", last.detail),
                ErrorKind::Numerical, Reach::EveryProcess);
  if (verbose) fmt::print(stderr, "results in {}\n", out_dir);
}

}  // namespace stiction::harness
