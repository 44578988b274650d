#include "nonlinear/newton.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <utility>

#include "common/error.hpp"
#include "fem/elasticity_assembly.hpp"
#include "nonlinear/inexact_direction.hpp"

namespace stiction::nonlinear {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double l2_norm(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

}  // namespace

std::string to_string(NewtonReason r) {
  switch (r) {
    case NewtonReason::ConvergedAbsolute: return "CONVERGED_ATOL";
    case NewtonReason::ConvergedRelative: return "CONVERGED_RTOL";
    case NewtonReason::DivergedMaxIterations: return "DIVERGED_MAX_ITERATIONS";
    case NewtonReason::DivergedLinearSolver: return "DIVERGED_LINEAR_SOLVE";
    case NewtonReason::DivergedInvertedElement: return "DIVERGED_INVERTED_ELEMENT";
    case NewtonReason::DivergedNaN: return "DIVERGED_NAN";
    case NewtonReason::DivergedResidualGrowth: return "DIVERGED_RESIDUAL_GROWTH";
    case NewtonReason::DivergedActiveSetCycle: return "DIVERGED_ACTIVE_SET_CYCLE";
  }
  return "UNKNOWN";
}

Forcing forcing_from_string(const std::string& name) {
  if (name == "fixed") return Forcing::Fixed;
  if (name == "eisenstat-walker") return Forcing::EisenstatWalker;
  throw Error(fmt::format("unknown Newton forcing '{}' (accepted: fixed, eisenstat-walker)", name));
}

std::string to_string(Forcing f) { return f == Forcing::Fixed ? "fixed" : "eisenstat-walker"; }

namespace {

constexpr double kContactForcingCap = 1e-4;  // the backends' fixed Krylov rtol

// Eisenstat-Walker choice 2 with PETSc's defaults and Kelley's floor (see newton.hpp).
// r_now, r_prev: norms of this and the previous system's right side; r_free and tolerance:
// the residual the Newton test reads and its tolerance (Kelley's floor: no solve below half
// of what the Newton test needs).
double next_forcing_term(double eta_prev, double r_now, double r_prev, double r_free, double tolerance, bool first) {
  constexpr double gamma = 0.9, alpha = 2, eta_first = 0.3, eta_max = 0.9, threshold = 0.1;
  double eta = first || !(r_prev > 0) ? eta_first : gamma * std::pow(r_now / r_prev, alpha);
  if (!first && gamma * std::pow(eta_prev, alpha) > threshold) eta = std::max(eta, gamma * std::pow(eta_prev, alpha));
  eta = std::min(eta, eta_max);
  if (r_free > 0) eta = std::max(eta, 0.5 * tolerance / r_free);
  return std::min(std::max(eta, 1e-12), eta_max);
}

}  // namespace

// The residual of the augmented system: u rows (the elastic part kept apart: the contact
// forces are r.u - r.elastic) and constraint rows.
struct QuasiStaticSolver::Residuals {
  explicit Residuals(const std::shared_ptr<const fem::GhostPattern>& pattern) : elastic(pattern), u(pattern) {}
  fem::GhostedVector elastic, u;
  std::vector<double> c;
};

namespace {

const ElasticityProblem& checked(const ElasticityProblem& problem) {
  if (static_cast<int>(problem.cell_material.size()) != problem.space->mesh().n_cells())
    throw Error("problem: one material per cell expected", ErrorKind::Internal);
  return problem;
}

}  // namespace

QuasiStaticSolver::QuasiStaticSolver(MPI_Comm comm, const ElasticityProblem& problem, const NewtonSettings& settings,
                                     LinearSolver& linear)
    : QuasiStaticSolver(comm, problem, nullptr, nullptr, settings, linear) {}

QuasiStaticSolver::QuasiStaticSolver(MPI_Comm comm, const ElasticityProblem& problem, const mesh::LocalMesh& part,
                                     fem::PartOwnership ownership, const NewtonSettings& settings,
                                     LinearSolver& linear)
    : QuasiStaticSolver(comm, problem, &part, &ownership, settings, linear) {}

namespace {

// A part's own cells as the partition of its mesh (its cells' owners in its numbering).
fem::MeshPartition partition_of_part(MPI_Comm comm, const mesh::LocalMesh& part) {
  fem::MeshPartition p;
  MPI_Comm_rank(comm, &p.rank);
  MPI_Comm_size(comm, &p.size);
  p.cell_owner = part.cell_owner;
  for (int c = 0; c < part.n_own_cells; ++c) p.owned_cells.push_back(c);
  return p;
}

}  // namespace

QuasiStaticSolver::QuasiStaticSolver(MPI_Comm comm, const ElasticityProblem& problem, const mesh::LocalMesh* part,
                                     fem::PartOwnership* ownership, const NewtonSettings& settings,
                                     LinearSolver& linear)
    : problem_(checked(problem)),
      settings_(settings),
      linear_(linear),
      lifting_(comm, problem),
      constraints_(problem.constraints),
      partition_(part ? partition_of_part(comm, *part) : fem::partition_cells(comm, problem.space->mesh())),
      part_(part),
      layout_(part ? fem::DofLayout(comm, *part, *problem.space, std::move(*ownership))
                   : fem::DofLayout(comm, *problem.space, partition_, constraints_.multiplier_vertices())),
      builder_(layout_, problem, constraints_.n_multipliers()),
      pattern_(std::make_shared<fem::GhostPattern>(layout_, unknowns_read())),
      u_(pattern_),
      lambda_(constraints_.n_multipliers(), 0.0) {
  constraints_.distribute(layout_, problem.space->n_dofs());
  linear_.set_krylov_restart(settings_.krylov_restart);
}

std::vector<PetscInt> QuasiStaticSolver::unknowns_read() const {
  if (layout_.identity()) return {};
  std::vector<PetscInt> out = fem::unknowns_of_cells(*problem_.space, layout_.row_cells());
  // An own cell whose nodes all belong to other processes is not a row cell.
  const std::vector<PetscInt> own = fem::unknowns_of_cells(*problem_.space, partition_.owned_cells);
  out.insert(out.end(), own.begin(), own.end());
  std::vector<int> tags;
  for (const auto* c : problem_.constraints)
    for (const auto& [role, tag] : c->surfaces()) tags.push_back(tag);
  const std::vector<PetscInt> surfaces = fem::unknowns_of_facets(*problem_.space, tags);
  out.insert(out.end(), surfaces.begin(), surfaces.end());
  return out;
}

fem::InternalForceStatus QuasiStaticSolver::residual(double t, fem::StateView u, fem::GhostedVector& r) const {
  const fem::FieldSpace& space = *problem_.space;
  r.fill(0.0);
  if (partition_.whole()) {
    const auto status = fem::assemble_internal(space, problem_.cell_material, u, r.view(), nullptr);
    add_loads(t, r.view());
    return status;
  }
  // Each rank integrates the cells that reach its owned rows (DofLayout::row_cells), so
  // those rows are complete; the rows of its ghosts are partial and never read.
  auto status = with_whole_cell_ids(
      fem::assemble_internal(space, problem_.cell_material, u, r.view(), nullptr, &layout_.row_cells()));
  add_loads(t, r.view());
  status.inverted_cell = fem::first_cell_over_ranks(layout_.comm(), status.inverted_cell);
  status.folded_cell = fem::first_cell_over_ranks(layout_.comm(), status.folded_cell);
  struct {
    double value;
    int cell;
  } smallest{status.min_det_f, status.min_det_f_cell};
  MPI_Allreduce(MPI_IN_PLACE, &smallest, 1, MPI_DOUBLE_INT, MPI_MINLOC, layout_.comm());
  status.min_det_f = smallest.value, status.min_det_f_cell = smallest.cell;
  return status;
}

fem::InternalForceStatus QuasiStaticSolver::with_whole_cell_ids(fem::InternalForceStatus status) const {
  if (!part_) return status;
  for (int* c : {&status.inverted_cell, &status.folded_cell, &status.min_det_f_cell})
    if (*c >= 0) *c = part_->cell_ids[static_cast<size_t>(*c)];
  return status;
}

void QuasiStaticSolver::add_loads(double t, fem::ResidualView r) const {
  const fem::FieldSpace& space = *problem_.space;
  if (problem_.body_force)
    fem::subtract_body_force(space, [&](const double* X, double* out) { problem_.body_force(X, t, out); }, r);
  for (const auto& load : problem_.tractions)
    fem::subtract_traction(space, load.facet_tag, [&](const double* X, double* out) { load.value(X, t, out); }, r);
}

fem::InternalForceStatus QuasiStaticSolver::evaluate(double t, fem::StateView u,
                                                     const std::vector<double>& lambda, Residuals& r) const {
  const fem::InternalForceStatus status = residual(t, u, r.elastic);
  r.u = r.elastic;
  const auto t0 = std::chrono::steady_clock::now();
  if (layout_.identity()) {
    constraints_.evaluate(t, u, lambda, r.u.view(), r.c);
    if (!constraints_.empty()) contact_seconds_ += seconds_since(t0);
    return status;
  }
  // Each process adds its share of the contact forces, on owned and ghost rows alike; the
  // shares are summed into the owners' rows.
  if (!contact_share_) contact_share_ = std::make_unique<fem::GhostedVector>(pattern_);
  contact_share_->fill(0.0);
  constraints_.evaluate(t, u, lambda, contact_share_->view(), r.c);
  contact_share_->add_ghosts_to_owners();
  const fem::StateView share = std::as_const(*contact_share_).view();
  fem::ResidualView ru = r.u.view();
  for (PetscInt j = 0; j < layout_.n_owned(); ++j) {
    const PetscInt a = layout_.local_of_owned(j);
    if (a < problem_.space->n_dofs()) ru[a] += share[a];
  }
  if (!constraints_.empty()) contact_seconds_ += seconds_since(t0);
  return status;
}

std::map<std::string, std::array<double, 3>> QuasiStaticSolver::surface_forces() const {
  std::map<std::string, std::array<double, 3>> out;
  const auto force = [&](int tag) {
    if (layout_.identity()) return fem::boundary_force(*problem_.space, problem_.cell_material, u_.view(), tag);
    const auto mine = fem::boundary_force(*problem_.space, problem_.cell_material, u_.view(), tag, &layout_);
    std::vector<double> sum(mine.begin(), mine.end());
    fem::sum_over_ranks(layout_.comm(), sum);
    return std::array<double, 3>{sum[0], sum[1], sum[2]};
  };
  for (const auto& bc : problem_.dirichlet) out[bc.name] = force(bc.facet_tag);
  for (const auto* c : problem_.constraints)
    for (const auto& [role, tag] : c->surfaces()) out[c->name() + "/" + role] = force(tag);
  return out;
}

void QuasiStaticSolver::assemble_system(const Residuals& r, bool lift) {
  // A contact system is a new matrix every iteration: the solver's set-up on the last one
  // is freed first, or it would be held while the next one is built.
  if (!constraints_.empty()) linear_.release();
  // The constraint forces the evaluation of their Jacobian writes, not read.
  std::optional<fem::GhostedVector> force_scratch;
  if (!constraints_.empty()) force_scratch.emplace(pattern_);
  contact_seconds_ += builder_.assemble(target_time_, u_.view(), lambda_, std::as_const(r.u).view(), r.c,
                                        constraints_, lifting_, lift,
                                        force_scratch ? force_scratch->view() : fem::ResidualView());
}

void QuasiStaticSolver::report_state_changes(int step, int iteration, double t, const std::vector<char>& before) const {
  constraints_.visit_changes(before, t, u_.view(), lambda_,
                             [&](const MultiplierConstraint& c, int node, char was, const MultiplierNode& now) {
                               state_observer_({step, iteration, c.name(), node, was, now});
                             });
}

// du's owned entries go to dv's (then its ghosts), its multiplier entries to dl on every
// process (the multipliers are whole everywhere; a few percent of the unknowns).
void QuasiStaticSolver::split_update(Vec du, fem::GhostedVector& dv, std::vector<double>& dl) const {
  STICTION_PETSC(VecCopy(du, dv.vec()));
  dv.update_ghosts();
  const PetscInt n_u = problem_.space->n_dofs();
  std::fill(dl.begin(), dl.end(), 0.0);
  const fem::StateView v = std::as_const(dv).view();
  for (PetscInt j = 0; j < layout_.n_owned(); ++j)
    if (const PetscInt a = layout_.local_of_owned(j); a >= n_u) dl[a - n_u] = v[a];
  if (!layout_.identity()) fem::sum_over_ranks(layout_.comm(), dl);
}

QuasiStaticSolver::TrialStep QuasiStaticSolver::take_step(double t_target, const fem::GhostedVector& dv,
                                                          const std::vector<double>& dl, Residuals& rt) {
  // Backtracking: halve the step while the trial state inverts a cell or is not finite.
  TrialStep t;
  fem::GhostedVector trial(pattern_);
  std::vector<double> trial_lambda;
  for (int bt = 0;; ++bt) {
    trial = u_;
    trial_lambda = lambda_;
    // Every held entry, ghosts included: the same sum as the owner's.
    const std::span<double> x = trial.view().storage();
    const std::span<const double> d = dv.view().storage();
    for (size_t i = 0; i < x.size(); ++i) x[i] += t.alpha * d[i];
    for (size_t i = 0; i < dl.size(); ++i) trial_lambda[i] += t.alpha * dl[i];
    if (t.alpha == 1)
      lifting_.impose(trial.view());  // exact, free of round-off
    const auto t0 = std::chrono::steady_clock::now();
    const auto st = evaluate(t_target, std::as_const(trial).view(), trial_lambda, rt);
    t.assembly_seconds += seconds_since(t0);
    const double norm = std::hypot(lifting_.free_norm(layout_, rt.u.view()), l2_norm(rt.c));
    t.status = st;
    if (st.inverted_cell < 0 && std::isfinite(norm)) break;
    if (bt == settings_.max_backtracks) {
      t.failed = true;
      t.failure = st.inverted_cell < 0 ? NewtonReason::DivergedNaN : NewtonReason::DivergedInvertedElement;
      return t;
    }
    t.alpha *= 0.5;
  }
  u_ = trial;
  lambda_.swap(trial_lambda);
  return t;
}

double QuasiStaticSolver::contact_force_norm(const Residuals& r) const {
  fem::GhostedVector contact_force(r.u);
  const std::span<double> f = contact_force.view().storage();
  const std::span<const double> elastic = r.elastic.view().storage();
  for (size_t i = 0; i < f.size(); ++i) f[i] -= elastic[i];
  return lifting_.free_norm(layout_, std::as_const(contact_force).view());
}

// Predictor (choice): while some node is in contact, the first solve of a step keeps the
// previous step's states, so the contact rows carry the master's motion into the body and
// only the nodes at the edge of the contact zone change afterwards. Re-evaluating the states
// on the initial iterate instead (the body not yet moved) activates every node the master's
// rigid motion overlaps; PDAS then releases them one or two per iteration. Measured on
// hertz-cylinder-2d level 1 with 8 load steps, lu-mumps: steps 2-8 took 9, 8, 8, 7, 6, 7, 6
// iterations that way. With no node in contact each pair takes its first states from the
// penetrations of the initial iterate (the deepest part of the overlap:
// ContactPair::entry_depth).
int QuasiStaticSolver::first_states(int step, double t, Residuals& r) {
  if (!constraints_.all_free()) return 0;
  const std::vector<char> before = constraints_.states();
  const int changes = constraints_.update_states(t, u_.view(), lambda_, std::vector<double>(lambda_.size(), 0.0));
  if (changes > 0) constraints_.evaluate_rows(t, u_.view(), lambda_, r.c);
  if (changes > 0 && state_observer_) report_state_changes(step, 0, t, before);
  return changes;
}

QuasiStaticSolver::StateUpdate QuasiStaticSolver::update_states(int step, int iteration, double t,
                                                                const std::vector<double>& dl, double reference,
                                                                double c_reference, ActiveSetMonitor& monitor,
                                                                Residuals& r) {
  StateUpdate out;
  const double r_free = lifting_.free_norm(layout_, r.u.view()), r_c = l2_norm(r.c);
  const bool converged_now = r_free <= std::max(settings_.atol, settings_.rtol * reference) &&
                             r_c <= std::max(settings_.atol, settings_.rtol * c_reference);
  const double progress = std::max(r_free / reference, r_c / std::max(c_reference, settings_.atol));
  out.checked = monitor.may_update(progress, converged_now);
  if (!out.checked) {
    constraints_.states_held(lambda_, dl);
    return out;
  }
  const std::vector<char> before = constraints_.states();
  out.changes = constraints_.update_states(t, u_.view(), lambda_, dl);
  if (out.changes > 0) {
    if (state_observer_) report_state_changes(step, iteration, t, before);
    constraints_.evaluate_rows(t, u_.view(), lambda_, r.c);
    out.verdict = monitor.after_update(before, constraints_.states(), r_free + r_c,
                                       lifting_.free_norm(layout_, r.u.view()) + l2_norm(r.c));
  }
  return out;
}

StepResult QuasiStaticSolver::solve_step(int step) {
  if (step < 1 || step > problem_.n_steps())
    throw Error(fmt::format("load step {} outside 1..{}", step, problem_.n_steps()), ErrorKind::Internal);
  StepResult res = solve_increment(step, problem_.step_times[step]);
  if (res.converged()) {
    time_ = res.time;
    completed_step_ = step;
    res.completes_step = true;
  }
  return res;
}

StepResult QuasiStaticSolver::solve_increment(int step, double t) {
  const auto t_step = std::chrono::steady_clock::now();
  StepResult res;
  res.step = step;
  res.time = t;
  target_time_ = t;
  constraints_.begin_increment(time_, u_.view());
  lifting_.set_targets(t);

  Residuals r(pattern_), rt(pattern_);
  contact_seconds_ = 0;
  auto t0 = std::chrono::steady_clock::now();
  const auto st0 = evaluate(t, u_.view(), lambda_, r);
  double asm_seconds = seconds_since(t0);
  reject_invalid_start(step, st0);
  // A folded cell (fem::InternalForceStatus) may be crossed by Newton's iterates, which
  // leave it again on the way to a valid solution (measured on the frictional ironing at
  // level 1: refusing folded iterates stopped the run at t = 1.18, where every converged
  // state had det F >= 0.58 at every node), but a state that holds one is never accepted:
  // the increment fails and is cut (before, such a state was converged to at t = 1.49, and
  // Newton stalled in the next step on the contact projections of the looped facet).
  fem::InternalForceStatus accepted = st0;  // of the current iterate
  double rnorm = lifting_.free_norm(layout_, r.u.view()), cnorm = l2_norm(r.c), c_reference = cnorm;
  res.initial_residual = res.reference_residual = res.final_residual = rnorm;
  auto finish = [&](NewtonReason why) {
    res.reason = why;
    res.final_residual = rnorm;
    if (res.converged()) {
      res.reactions = lifting_.reactions(layout_, r.u.view());
      res.min_det_f = accepted.min_det_f;
      res.surface_forces = surface_forces();
      res.contact = constraints_.summaries(lambda_);
    }
    res.wall_seconds = seconds_since(t_step);
    return res;
  };
  auto keep_iteration = [&](const NewtonIteration& rec) {
    res.iterations.push_back(rec);
    if (iteration_observer_) iteration_observer_(step, t, rec);
  };
  ActiveSetMonitor monitor(settings_.active_set);
  int last_changes = 0;
  bool states_checked = true;  // the states were tested at the current iterate
  if (!lambda_.empty()) {
    last_changes = first_states(step, t, r);
    cnorm = c_reference = l2_norm(r.c);
  }

  PetscVec du;
  STICTION_PETSC(VecDuplicate(builder_.system().rhs, du.out()));
  ForcingHistory forcing;
  for (int it = 0;; ++it) {
    const bool pending = lifting_.pending(layout_, u_.view());
    const double tol = std::max(settings_.atol, settings_.rtol * res.reference_residual);
    const bool constraints_ok =
        states_checked && last_changes == 0 && cnorm <= std::max(settings_.atol, settings_.rtol * c_reference);
    if (!pending && (it > 0 || rnorm <= settings_.atol) && constraints_ok && rnorm <= tol) {
      res.detail = unacceptable_converged_state(st0, accepted);
      if (!res.detail.empty()) return finish(NewtonReason::DivergedInvertedElement);
      return finish(rnorm <= settings_.atol ? NewtonReason::ConvergedAbsolute : NewtonReason::ConvergedRelative);
    }
    if (it == settings_.max_iterations) {
      res.detail = fmt::format("{} iterations, residual {:.3e} {} tolerance {:.3e}", it, rnorm,
                               rnorm > tol ? "above" : "within", tol);
      if (!lambda_.empty()) res.detail += contact_residual_detail(cnorm, c_reference, last_changes);
      return finish(NewtonReason::DivergedMaxIterations);
    }

    NewtonIteration rec;
    t0 = std::chrono::steady_clock::now();
    assemble_system(r, pending);
    rec.assembly_seconds = asm_seconds + seconds_since(t0);
    rec.contact_assembly_seconds = std::exchange(contact_seconds_, 0.0);
    if (it == 0) res.reference_residual = std::max(rnorm, lifting_.free_norm(layout_, builder_.system().rhs));

    linear_.setup(builder_.system());
    const double terminal = terminal_linear_residual(res.reference_residual, c_reference, pending);
    // The tolerance is raised to the terminal residual only once the contact states have
    // settled (the last update changed none): while they change, the multipliers of the next
    // iterate decide states, and loose solves there flip nodes near their thresholds and
    // lengthen the Newton path (reports/block-strips-studies/level1-terminal-forcing).
    const bool states_settled = last_changes == 0;  // held (unchecked) states count as unchanged
    set_krylov_tolerance(it == 0, rnorm, res.reference_residual, states_settled ? terminal : 0.0, forcing);
    if (!solve_for_direction(step, it, terminal, du, rec.linear)) {
      keep_iteration(rec);
      res.detail = linear_failure_detail(rec.linear);
      return finish(NewtonReason::DivergedLinearSolver);
    }
    fem::GhostedVector dv(pattern_);
    std::vector<double> dl(lambda_.size());
    split_update(du, dv, dl);
    const TrialStep trial = take_step(t, dv, dl, rt);
    asm_seconds = trial.assembly_seconds;
    if (trial.failed) {
      keep_iteration(rec);
      res.detail = trial_failure_detail(trial);
      return finish(trial.failure);
    }
    const double alpha = trial.alpha;
    accepted = trial.status;
    r = std::move(rt);
    ActiveSetMonitor::Verdict verdict = ActiveSetMonitor::Verdict::Continue;
    if (!lambda_.empty()) {
      const StateUpdate update = update_states(step, it + 1, t, dl, res.reference_residual, c_reference, monitor, r);
      states_checked = update.checked;
      last_changes = update.changes;
      verdict = update.verdict;
      c_reference = std::max(c_reference, l2_norm(r.c));
      // Contact carries the load of a displacement-driven master: its forces set the scale.
      res.reference_residual = std::max(res.reference_residual, contact_force_norm(r));
    }
    rnorm = lifting_.free_norm(layout_, r.u.view());
    cnorm = l2_norm(r.c);
    rec.residual = rnorm;
    rec.constraint_residual = cnorm;
    rec.state_changes = last_changes;
    rec.step_length = alpha;
    keep_iteration(rec);
    if (rnorm > settings_.divergence_factor * std::max(res.reference_residual, settings_.atol)) {
      res.detail = fmt::format("residual {:.3e} grew beyond {:g} x the reference {:.3e}", rnorm,
                               settings_.divergence_factor, res.reference_residual);
      return finish(NewtonReason::DivergedResidualGrowth);
    }
    if (verdict == ActiveSetMonitor::Verdict::Cycle) {
      res.detail = fmt::format("contact states of iteration {} recur without the residual {:.3e} having fallen, "
                               "after {} tightenings of the state-update gate (now {:.1e})",
                               it + 1, rnorm + cnorm, monitor.remedies_used(), monitor.gate());
      return finish(NewtonReason::DivergedActiveSetCycle);
    }
  }
}

QuasiStaticSolver::State QuasiStaticSolver::state() const {
  std::vector<double> u = u_.whole_on_root();
  if (!u.empty()) u.resize(n_whole_dofs());
  State s{completed_step_, time_, std::move(u), lambda_, {}};
  s.constraints = constraints_.save_state();
  return s;
}

std::vector<double> QuasiStaticSolver::displacement() const {
  std::vector<double> u = u_.whole();
  u.resize(n_whole_dofs());
  return u;
}

QuasiStaticSolver::Snapshot QuasiStaticSolver::snapshot() const {
  return {completed_step_, time_, u_, lambda_, constraints_.save_state()};
}

void QuasiStaticSolver::restore(const Snapshot& s) {
  constraints_.restore_state(s.constraints);
  u_ = s.u;
  lambda_ = s.lambda;
  time_ = s.time;
  completed_step_ = s.step;
}

void QuasiStaticSolver::restore(const State& s) {
  const size_t n_u = n_whole_dofs();
  unsigned long long u_size = s.u.size();  // process 0's
  MPI_Bcast(&u_size, 1, MPI_UNSIGNED_LONG_LONG, 0, layout_.comm());
  if (u_size != n_u || s.lambda.size() != lambda_.size() || s.constraints.size() != constraints_.size())
    throw Error(fmt::format("a saved state of {} displacement unknowns, {} multipliers and {} constraints does not fit "
                            "this problem ({}, {}, {})",
                            u_size, s.lambda.size(), s.constraints.size(), n_u, lambda_.size(), constraints_.size()));
  if (s.step < 0 || s.step > problem_.n_steps())
    throw Error(fmt::format("a saved state at load step {} does not fit a problem of {} steps", s.step,
                            problem_.n_steps()));
  constraints_.restore_state(s.constraints);
  u_.assign_from_root(s.u);
  lambda_ = s.lambda;
  time_ = s.time;
  completed_step_ = s.step;
}

double QuasiStaticSolver::terminal_linear_residual(double reference, double c_reference, bool pending) const {
  if (pending) return 0;  // the system's right side then carries the lifting, not the residual
  double tol = std::max(settings_.atol, settings_.rtol * reference);
  if (!lambda_.empty()) tol = std::min(tol, std::max(settings_.atol, settings_.rtol * c_reference));
  return 0.5 * tol;
}

void QuasiStaticSolver::reject_invalid_start(int step, const fem::InternalForceStatus& start) const {
  if (start.inverted_cell >= 0)
    throw Error(fmt::format("load step {}: {} is inverted at the start of the step", step,
                            describe_cell(start.inverted_cell)),
                ErrorKind::Numerical, Reach::EveryProcess);
  if (start.folded_cell >= 0)
    throw Error(fmt::format("load step {}: {} is folded (det F <= 0 at one of its nodes) at the start of the step",
                            step, describe_cell(start.folded_cell)),
                ErrorKind::Numerical, Reach::EveryProcess);
}

std::string QuasiStaticSolver::unacceptable_converged_state(const fem::InternalForceStatus& start,
                                                            const fem::InternalForceStatus& accepted) const {
  if (accepted.folded_cell >= 0)
    return fmt::format("the residual converged at a state where {} is folded (det F <= 0 at one of its nodes)",
                       describe_cell(accepted.folded_cell));
  if (accepted.min_det_f < settings_.min_det_f_ratio * start.min_det_f)
    return fmt::format("the smallest det F fell from {:.3g} to {:.3g} in one increment, in {}", start.min_det_f,
                       accepted.min_det_f, describe_cell(accepted.min_det_f_cell));
  return {};
}

std::string QuasiStaticSolver::contact_residual_detail(double cnorm, double c_reference, int last_changes) const {
  const double c_tol = std::max(settings_.atol, settings_.rtol * c_reference);
  return fmt::format(" (contact residual {:.3e} {} its tolerance {:.3e}, {} states changed last)", cnorm,
                     cnorm > c_tol ? "above" : "within", c_tol, last_changes);
}

// Eisenstat-Walker reads the norm of the whole right side of each Newton system (the
// residual the Krylov tolerance is relative to): with contact, a load carried by the
// constraints (a moving ground) leaves the displacement residual at zero at the first
// iterate, and a ratio of displacement residuals would then stay infinite.
void QuasiStaticSolver::set_krylov_tolerance(bool first, double rnorm, double reference, double terminal_residual,
                                             ForcingHistory& forcing) {
  PetscReal rhs_norm;
  STICTION_PETSC(VecNorm(builder_.system().rhs, NORM_2, &rhs_norm));
  const bool rtol_given = settings_.krylov_rtol > 0;  // newton.krylov_rtol: set on purpose
  double rtol = rtol_given ? settings_.krylov_rtol : linear_.relative_tolerance();
  if (settings_.forcing == Forcing::EisenstatWalker) {
    forcing.eta = next_forcing_term(forcing.eta, rhs_norm, forcing.rhs_prev, rnorm,
                                    std::max(settings_.atol, settings_.rtol * reference), first);
    forcing.rhs_prev = rhs_norm;
    // Contact: the state machine reads the gaps and multipliers of every iterate, and
    // loose solves (eta up to 0.9) make the states flip. Measured on hertz-cylinder-2d
    // level 1 with schur-amg: uncapped, 25 iterations and 953 state changes without
    // converging; so eta never exceeds the fixed default there.
    rtol = lambda_.empty() ? forcing.eta
                           : std::min(forcing.eta, rtol_given ? settings_.krylov_rtol : kContactForcingCap);
  }
  // No solve goes below the residual Newton's stopping test reads, unless the scene or the
  // command line set the tolerance on purpose (newton.krylov_rtol): sweeps over it, and the
  // tight solves the ironing scenes need to keep the exact path, mean it for every solve.
  if (settings_.forcing == Forcing::EisenstatWalker || !rtol_given)
    rtol = terminal_forcing(rtol, terminal_residual, rhs_norm);
  if (rtol > 0 && rtol != linear_.relative_tolerance()) linear_.set_relative_tolerance(rtol);
}

// A solve that gives no update is continued once with more memory where the backend can (a
// longer GMRES cycle), before the increment is given up.
bool QuasiStaticSolver::solve_for_direction(int step, int it, double terminal_residual, Vec du,
                                            LinearSolveStats& stats) {
  stats = linear_.solve(builder_.system(), du);
  if (!stats.converged && !usable_direction(stats, terminal_residual))
    linear_.continue_longer(builder_.system(), du, stats);
  if (observer_) observer_(builder_.system(), du, stats, step, it + 1);
  return stats.converged || usable_direction(stats, terminal_residual);
}

std::string QuasiStaticSolver::linear_failure_detail(const LinearSolveStats& stats) const {
  std::string detail = fmt::format("linear solver {} stopped with {}", linear_.name(), stats.reason);
  if (const auto k = stats.extra.find("krylov_continued_restart"); k != stats.extra.end())
    detail += fmt::format(" (also when continued with a restart of {:g})", k->second);
  return detail;
}

std::string QuasiStaticSolver::trial_failure_detail(const TrialStep& trial) const {
  return trial.failure == NewtonReason::DivergedNaN
             ? "the residual is not finite after every step reduction"
             : fmt::format("{} inverts (det F <= 0) even after {} step halvings",
                           describe_cell(trial.status.inverted_cell), settings_.max_backtracks);
}

// A failed linear solve is retried over a smaller increment only where the increment could
// be the cause: not at the increment's first solve (its matrix is the tangent at the last
// converged state whatever the increment's size, so a smaller one hands the solver the same
// system), and once per load step (a solver that cannot solve this problem's systems, such as
// boomeramg on an indefinite one, fails again, and each failure costs a solve to -ksp_max_it),
// unless the backend has solved nearly all of the run's systems (at most
// kSporadicLinearFailures of them failed): its failures are then sporadic, one hard system
// that a smaller increment replaces. Where Newton wanders off within an increment (ironing-2d
// level 1, schur-amg, t = 1.1: residual 31 -> 4e5 in one full step, then a GMRES breakdown),
// half the increment converges; on ironing-2d-frictionless level 1 at t = 1.56 GMRES
// stagnated in the second solve of the whole increment and in the fifth of its half, when
// 18 of the run's 1 047 solves had failed, and the quarter increments converged.
bool QuasiStaticSolver::retry_allowed(const StepResult& failed, bool linear_failure_retried, const LinearTally& tally) {
  if (failed.reason != NewtonReason::DivergedLinearSolver) return true;
  if (failed.iterations.size() <= 1) return false;
  return !linear_failure_retried || tally.failures <= kSporadicLinearFailures * tally.solves;
}

std::vector<StepResult> QuasiStaticSolver::run(const std::function<void(const StepResult&)>& on_step, int first_step,
                                               int last_step) {
  if (last_step < 0) last_step = problem_.n_steps();
  std::vector<StepResult> all;
  auto report = [&](const StepResult& r) {
    all.push_back(r);
    if (on_step) on_step(r);
  };
  // The cut-back's state lives in cut_back_, so that it outlasts this call (checkpoints).
  // wait[c]: converged parts at cut c before the size of cut c - 1 is tried again; `probing`:
  // the current size was grown back to and has not yet converged over a whole increment
  // (a part clamped to a step's end is smaller and proves nothing).
  int& cut = cut_back_.cut;
  int& converged_at_cut = cut_back_.converged_at_cut;
  std::vector<int>& wait = cut_back_.wait;
  wait.resize(static_cast<size_t>(settings_.max_cuts) + 2, 2);
  bool& probing = cut_back_.probing;
  for (int k = first_step; k <= last_step; ++k) {
    const double t_end = problem_.step_times[k], full = t_end - time_;
    double increment = std::ldexp(full, -cut);  // a cut carries over into the next step
    bool linear_failure_retried = false;
    for (;;) {
      // The last part lands exactly on the step's end (no sliver left by round-off).
      const double t = time_ + increment >= t_end - 1e-9 * full ? t_end : time_ + increment;
      const Snapshot saved = snapshot();
      StepResult r = solve_increment(k, t);
      r.cut = cut;
      tally_.solves += static_cast<int>(r.iterations.size());
      if (r.reason == NewtonReason::DivergedLinearSolver) ++tally_.failures;
      if (!r.converged()) {
        r.retried = cut < settings_.max_cuts && retry_allowed(r, linear_failure_retried, tally_);
        report(r);
        if (!r.retried) return all;
        if (r.reason == NewtonReason::DivergedLinearSolver) linear_failure_retried = true;
        if (probing) wait[cut + 1] = std::min(2 * wait[cut + 1], std::max(settings_.max_regrow_wait, 2));
        probing = false;
        restore(saved);
        // Half of what was attempted: a grown-back increment may have been clamped to the
        // step's end, and halving the nominal one would attempt the same increment again.
        increment = 0.5 * (t - time_);
        ++cut;
        converged_at_cut = 0;
        continue;
      }
      if (probing && t - time_ >= (1 - 1e-9) * increment) {
        wait[cut + 1] = 2;
        probing = false;
      }
      time_ = t;
      r.completes_step = t == t_end;
      if (r.completes_step) completed_step_ = k;
      report(r);
      if (r.completes_step) break;
      // Grow back after two converged parts at one size (after one, a sliding step that
      // had failed at full size failed again at once: ironing-2d level 0, 25 wasted
      // iterations per load step), or after more where the larger size failed again.
      if (cut > 0 && ++converged_at_cut >= wait[cut]) {
        increment *= 2;
        --cut;
        converged_at_cut = 0;
        probing = true;
      }
    }
  }
  return all;
}

}  // namespace stiction::nonlinear
