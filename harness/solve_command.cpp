#include "solve_command.hpp"

#include <fmt/format.h>
#include <fmt/os.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "builtin_scenes.hpp"
#include "common/error.hpp"
#include "ksp_solver.hpp"
#include "registry.hpp"
#include "run_metrics.hpp"
#include "system_record.hpp"
#include "vtu_writer.hpp"

namespace stiction::harness {

namespace {

// CSV of per-step quantities, written and flushed row by row.
class StepTable {
public:
  // (key in StepResult::surface_forces, column prefix) of every traction integral.
  static std::vector<std::pair<std::string, std::string>> traction_columns(const scene::Scene& s) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& bc : s.problem.dirichlet) out.emplace_back(bc.name, "traction_" + bc.name);
    for (const auto* c : s.problem.constraints)
      for (const auto& [role, tag] : c->surfaces())
        out.emplace_back(c->name() + "/" + role, fmt::format("contact_{}_{}_traction", c->name(), role));
    return out;
  }

  StepTable(const std::string& path, const std::string& header_comment, const scene::Scene& s) : out_(path) {
    if (!out_) throw Error(fmt::format("cannot write '{}'", path));
    out_ << header_comment;
    out_ << "step,converged,reason,newton_iterations,initial_residual,reference_residual,final_residual,"
            "krylov_iterations,assembly_seconds,setup_seconds,solve_seconds,wall_seconds";
    // Forces on each Dirichlet boundary: nodal reactions (the paper's F2), then the
    // integral of the traction P N on each Dirichlet boundary (F1) and contact surface
    // (slave: F4, master: -F5).
    for (const auto& bc : s.problem.dirichlet)
      for (int k = 0; k < s.mesh.dim; ++k) out_ << fmt::format(",reaction_{}_{}", bc.name, "xyz"[k]);
    for (const auto& [key, column] : traction_columns(s))
      for (int k = 0; k < s.mesh.dim; ++k) out_ << fmt::format(",{}_{}", column, "xyz"[k]);
    // Contact: the integral of lambda over the slave surface (F3), the final states and how
    // many states changed over the step's Newton iterations.
    for (const auto* c : s.problem.constraints) {
      for (int k = 0; k < s.mesh.dim; ++k) out_ << fmt::format(",contact_{}_force_{}", c->name(), "xyz"[k]);
      out_ << fmt::format(",contact_{0}_inactive,contact_{0}_stick,contact_{0}_slip", c->name());
    }
    if (!s.problem.constraints.empty()) out_ << ",state_changes";
    out_ << "\n";
    out_.flush();
  }
  void add(const nonlinear::StepResult& r, const scene::Scene& s) {
    int krylov = 0;
    double assembly = 0, setup = 0, solve = 0;
    for (const auto& it : r.iterations) {
      krylov += it.linear.iterations;
      assembly += it.assembly_seconds;
      setup += it.linear.setup_seconds;
      solve += it.linear.solve_seconds;
    }
    out_ << fmt::format("{},{},{},{},{:.6e},{:.6e},{:.6e},{},{:.4f},{:.4f},{:.4f},{:.4f}", r.step, r.converged() ? 1 : 0,
                        nonlinear::to_string(r.reason), r.iterations.size(), r.initial_residual,
                        r.reference_residual, r.final_residual, krylov, assembly, setup, solve, r.wall_seconds);
    for (const auto& bc : s.problem.dirichlet) {
      auto it = r.reactions.find(bc.name);
      for (int k = 0; k < s.mesh.dim; ++k)
        out_ << (it == r.reactions.end() ? std::string(",") : fmt::format(",{:.10e}", it->second[k]));
    }
    for (const auto& [key, column] : traction_columns(s)) {
      auto it = r.surface_forces.find(key);
      for (int k = 0; k < s.mesh.dim; ++k)
        out_ << (it == r.surface_forces.end() ? std::string(",") : fmt::format(",{:.10e}", it->second[k]));
    }
    for (size_t c = 0; c < s.problem.constraints.size(); ++c) {
      if (c >= r.contact.size()) {  // not converged: no contact figures
        out_ << std::string(static_cast<size_t>(s.mesh.dim) + 3, ',');
        continue;
      }
      const auto& cs = r.contact[c];
      for (int k = 0; k < s.mesh.dim; ++k) out_ << fmt::format(",{:.10e}", cs.force[k]);
      out_ << fmt::format(",{},{},{}", cs.inactive, cs.stick, cs.slip);
    }
    if (!s.problem.constraints.empty()) {
      int changes = 0;
      for (const auto& it : r.iterations) changes += it.state_changes;
      out_ << fmt::format(",{}", changes);
    }
    out_ << "\n";
    out_.flush();
  }

private:
  std::ofstream out_;
};

}  // namespace

void run_solve(const SolveOptions& o, const RunInfo& info) {
  const auto t_start = std::chrono::steady_clock::now();
  auto scene = open_scene(o.scene, o.level);
  if (!o.forcing.empty()) scene->newton.forcing = nonlinear::forcing_from_string(o.forcing);
  auto solver = solvers::create_solver(o.solver, PETSC_COMM_WORLD);
  const std::string out_dir = o.out_dir.empty() ? fmt::format("out/{}-L{}", scene->name, scene->level) : o.out_dir;
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) throw Error(fmt::format("cannot create output directory '{}': {}", out_dir, ec.message()));

  const auto& space = *scene->space;
  std::string header = format_run_info(info, "# ");
  header += fmt::format("# scene: {} ({}), level {}, basis {}\n", scene->name, scene->origin, scene->level,
                        fem::to_string(space.kind()));
  for (size_t b = 0; b < scene->body_names.size(); ++b)
    header += fmt::format("# body {}: {}\n", scene->body_names[b], scene->material_of_body[b]);
  header += fmt::format("# mesh: {} vertices, {} cells; unknowns: u_l {}, u_q {}, total {}\n", scene->mesh.n_vertices(),
                        scene->mesh.n_cells(), space.linear_block().second - space.linear_block().first,
                        space.quadratic_block().second - space.quadratic_block().first, space.n_dofs());
  header += fmt::format("# solver: {}; newton atol {:g}, rtol {:g}, max_iterations {}, forcing {}\n", o.solver,
                        scene->newton.atol, scene->newton.rtol, scene->newton.max_iterations,
                        nonlinear::to_string(scene->newton.forcing));
  if (!o.quiet) fmt::print(stderr, "{}", header);

  std::unique_ptr<StepTable> table;
  if (scene->output.csv) table = std::make_unique<StepTable>(out_dir + "/steps.csv", header, *scene);
  PvdCollection pvd(out_dir + "/solution.pvd");
  nonlinear::QuasiStaticSolver newton(PETSC_COMM_WORLD, scene->problem, scene->newton, *solver);
  if (!o.record_dir.empty()) {
    const RecordContext context{scene->name, scene->level, o.solver, info};
    newton.set_system_observer([&, context](const nonlinear::NewtonSystem& sys, Vec du,
                                            const nonlinear::LinearSolveStats& stats, int step, int iteration) {
      record_system(o.record_dir, sys, du, stats, step, iteration, context);
    });
  }
  auto results = newton.run([&](const nonlinear::StepResult& r) {
    if (table) table->add(r, *scene);
    if (scene->output.vtu && o.write_vtu && r.converged()) {
      const std::string name = fmt::format("step-{:03d}.vtu", r.step);
      write_vtu(out_dir + "/" + name, *scene, newton.displacement());
      pvd.add(r.step, name);
    }
    if (!o.quiet)
      fmt::print(stderr, "step {}/{}: {} after {} Newton iterations, residual {:.3e} (reference {:.3e}), {:.2f} s\n",
                 r.step, scene->problem.n_steps, nonlinear::to_string(r.reason), r.iterations.size(),
                 r.final_residual, r.reference_residual, r.wall_seconds);
  });
  {
    std::ofstream desc(out_dir + "/solver.txt");
    desc << solver->describe();
  }
  const auto& last = results.back();
  if (!o.metrics_path.empty()) {
    RunSummary summary{o.solver, solvers::default_options(o.solver) + o.petsc_options,
                       std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count(),
                       last.converged(), last.converged() ? "CONVERGED" : nonlinear::to_string(last.reason),
                       last.detail};
    write_metrics(o.metrics_path, *scene, summary, results);
  }
  if (!last.converged())
    throw Error(fmt::format("Newton did not converge at load step {} of scene '{}': {}{}{}", last.step, scene->name,
                            nonlinear::to_string(last.reason), last.detail.empty() ? "" : ": ", last.detail),
                ErrorKind::Numerical);
  if (!o.quiet) fmt::print(stderr, "results in {}\n", out_dir);
}

}  // namespace stiction::harness
