#include "result_tables.hpp"

#include <fmt/format.h>

#include <cmath>

#include "common/error.hpp"
#include "contact/contact_state.hpp"

namespace stiction::harness {

namespace {

// (key in StepResult::surface_forces, column prefix) of every traction integral.
std::vector<std::pair<std::string, std::string>> traction_columns(const nonlinear::ElasticityProblem& p) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& bc : p.dirichlet) out.emplace_back(bc.name, "traction_" + bc.name);
  for (const auto* c : p.constraints)
    for (const auto& [role, tag] : c->surfaces())
      out.emplace_back(c->name() + "/" + role, fmt::format("contact_{}_{}_traction", c->name(), role));
  return out;
}

// Opens a table (appending to a non-empty file when asked) and writes the header comment;
// true when the column line is still to be written.
bool open_table(std::ofstream& out, const std::string& path, const std::string& header_comment, bool append) {
  bool had_rows = false;
  if (append) {
    std::ifstream existing(path);
    had_rows = existing && existing.peek() != std::ifstream::traits_type::eof();
  }
  out.open(path, had_rows ? std::ios::app : std::ios::trunc);
  if (!out) throw Error(fmt::format("cannot write '{}'", path));
  out << header_comment;
  return !had_rows;
}

}  // namespace

StepTable::StepTable(const std::string& path, const std::string& header_comment, const scene::SceneView& view,
                     bool append) {
  if (!open_table(out_, path, header_comment, append)) return;
  const nonlinear::ElasticityProblem& p = *view.problem;
  const int dim = view.dim();
  // One row per load increment: `time` is the pseudo-time it ends at, `cut` how many times
  // its step's increment was halved, `retried` marks a failed attempt retried over half of it.
  out_ << "step,time,cut,retried,converged,reason,newton_iterations,initial_residual,reference_residual,final_residual,"
          "krylov_iterations,assembly_seconds,setup_seconds,solve_seconds,wall_seconds";
  // Forces on each Dirichlet boundary: nodal reactions (the paper's F2), then the
  // integral of the traction P N on each Dirichlet boundary (F1) and contact surface
  // (slave: F4, master: -F5).
  for (const auto& bc : p.dirichlet)
    for (int k = 0; k < dim; ++k) out_ << fmt::format(",reaction_{}_{}", bc.name, "xyz"[k]);
  for (const auto& [key, column] : traction_columns(p))
    for (int k = 0; k < dim; ++k) out_ << fmt::format(",{}_{}", column, "xyz"[k]);
  // Contact: the integral of lambda over the slave surface (F3), the final states and how
  // many states changed over the step's Newton iterations.
  for (const auto* c : p.constraints) {
    for (int k = 0; k < dim; ++k) out_ << fmt::format(",contact_{}_force_{}", c->name(), "xyz"[k]);
    out_ << fmt::format(",contact_{0}_inactive,contact_{0}_stick,contact_{0}_slip", c->name());
  }
  if (!p.constraints.empty()) out_ << ",state_changes";
  // The smallest det F of the converged state (empty without finite-strain cells): how
  // close a cell came to folding.
  out_ << ",min_det_f\n";
  out_.flush();
}

void StepTable::add(const nonlinear::StepResult& r, const scene::SceneView& view) {
  const nonlinear::ElasticityProblem& p = *view.problem;
  const int dim = view.dim();
  int krylov = 0;
  double assembly = 0, setup = 0, solve = 0;
  for (const auto& it : r.iterations) {
    krylov += it.linear.iterations;
    assembly += it.assembly_seconds;
    setup += it.linear.setup_seconds;
    solve += it.linear.solve_seconds;
  }
  out_ << fmt::format("{},{:.10g},{},{},{},{},{},{:.6e},{:.6e},{:.6e},{},{:.4f},{:.4f},{:.4f},{:.4f}", r.step, r.time,
                      r.cut, r.retried ? 1 : 0, r.converged() ? 1 : 0,
                      nonlinear::to_string(r.reason), r.iterations.size(), r.initial_residual, r.reference_residual,
                      r.final_residual, krylov, assembly, setup, solve, r.wall_seconds);
  for (const auto& bc : p.dirichlet) {
    auto it = r.reactions.find(bc.name);
    for (int k = 0; k < dim; ++k)
      out_ << (it == r.reactions.end() ? std::string(",") : fmt::format(",{:.10e}", it->second[k]));
  }
  for (const auto& [key, column] : traction_columns(p)) {
    auto it = r.surface_forces.find(key);
    for (int k = 0; k < dim; ++k)
      out_ << (it == r.surface_forces.end() ? std::string(",") : fmt::format(",{:.10e}", it->second[k]));
  }
  for (size_t c = 0; c < p.constraints.size(); ++c) {
    if (c >= r.contact.size()) {  // not converged: no contact figures
      out_ << std::string(static_cast<size_t>(dim) + 3, ',');
      continue;
    }
    const auto& cs = r.contact[c];
    for (int k = 0; k < dim; ++k) out_ << fmt::format(",{:.10e}", cs.force[k]);
    out_ << fmt::format(",{},{},{}", cs.inactive, cs.stick, cs.slip);
  }
  if (!p.constraints.empty()) {
    int changes = 0;
    for (const auto& it : r.iterations) changes += it.state_changes;
    out_ << fmt::format(",{}", changes);
  }
  out_ << (std::isfinite(r.min_det_f) ? fmt::format(",{:.6e}\n", r.min_det_f) : std::string(",\n"));
  out_.flush();
}

std::vector<std::pair<std::string, std::vector<nonlinear::MultiplierNode>>> multiplier_nodes(
    const nonlinear::ElasticityProblem& p, double t, fem::StateView u, const std::vector<double>& lambda) {
  std::vector<std::pair<std::string, std::vector<nonlinear::MultiplierNode>>> out;
  size_t offset = 0;
  for (const auto* c : p.constraints) {
    out.emplace_back(c->name(), c->nodes(t, u, lambda.data() + offset));
    offset += static_cast<size_t>(c->n_multipliers());
  }
  return out;
}

ContactTable::ContactTable(const std::string& path, const std::string& header_comment, int dim, bool append)
    : dim_(dim) {
  if (!open_table(out_, path, header_comment, append)) return;
  // gap: mean normal gap gn_i / m_i (negative: penetration); lambda: the traction on the
  // slave (lambda_n > 0 presses); state: inactive, stick or slip.
  out_ << "step,time,pair,node,vertex";
  for (int k = 0; k < dim_; ++k) out_ << fmt::format(",{}", "xyz"[k]);
  out_ << ",gap";
  for (int k = 0; k < dim_; ++k) out_ << fmt::format(",lambda_{}", "xyz"[k]);
  out_ << ",lambda_n";
  for (int k = 0; k < dim_; ++k) out_ << fmt::format(",lambda_t_{}", "xyz"[k]);
  out_ << ",state\n";
  out_.flush();
}

void ContactTable::add(const nonlinear::StepResult& r, const scene::SceneView& s, fem::StateView u,
                       const std::vector<double>& lambda) {
  for (const auto& [pair, nodes] : multiplier_nodes(*s.problem, r.time, u, lambda))
    for (size_t i = 0; i < nodes.size(); ++i) {
      const auto& n = nodes[i];
      out_ << fmt::format("{},{:.10g},{},{},{}", r.step, r.time, pair, i, s.whole_vertex(n.vertex));
      for (int k = 0; k < dim_; ++k) out_ << fmt::format(",{:.10e}", n.position[k]);
      out_ << fmt::format(",{:.6e}", n.gap);
      for (int k = 0; k < dim_; ++k) out_ << fmt::format(",{:.10e}", n.multiplier[k]);
      out_ << fmt::format(",{:.10e}", n.normal);
      for (int k = 0; k < dim_; ++k) out_ << fmt::format(",{:.10e}", n.tangential[k]);
      out_ << "," << contact::to_string(static_cast<contact::NodeState>(n.state)) << "\n";
    }
  out_.flush();
}

IterationTable::IterationTable(const std::string& path, const std::string& header_comment, bool contact, bool append)
    : contact_(contact) {
  if (!open_table(out_, path, header_comment, append)) return;
  // residual: the free residual after the update; the linear columns describe the solve
  // that produced the update.
  out_ << "step,time,iteration,residual,step_length,krylov_iterations,linear_reason,linear_relative_residual,"
          "assembly_seconds,setup_seconds,solve_seconds";
  if (contact_) out_ << ",constraint_residual,state_changes";
  out_ << "\n";
  out_.flush();
}

void IterationTable::add(const nonlinear::StepResult& r) {
  for (size_t k = 0; k < r.iterations.size(); ++k) {
    const auto& it = r.iterations[k];
    const double relative =
        it.linear.initial_residual > 0 ? it.linear.final_residual / it.linear.initial_residual : 0.0;
    out_ << fmt::format("{},{:.10g},{},{:.6e},{:g},{},{},{:.3e},{:.4f},{:.4f},{:.4f}", r.step, r.time, k + 1, it.residual,
                        it.step_length, it.linear.iterations, it.linear.reason, relative, it.assembly_seconds,
                        it.linear.setup_seconds, it.linear.solve_seconds);
    if (contact_) out_ << fmt::format(",{:.6e},{}", it.constraint_residual, it.state_changes);
    out_ << "\n";
  }
  out_.flush();
}

}  // namespace stiction::harness
