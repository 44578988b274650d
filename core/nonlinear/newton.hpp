#pragma once
// Quasi-static load stepping with Newton's method on the hyperelastic residual.
//
// Its parts: the Dirichlet lifting (dirichlet_lifting.hpp), the constraints' multiplier block
// (constraint_set.hpp), the system each iteration hands to the backend (system_builder.hpp)
// and the gate on contact-state updates (active_set_monitor.hpp); this file is the loop.
//
// On several MPI processes (comm) each holds the whole mesh, the multipliers and the
// contact states, and of the displacement (and pressure) state only its owned unknowns and
// the ghosts it reads (fem::GhostedVector: the nodes of the cells that reach its owned rows,
// of its own cells, whose output it writes, and of the contact surfaces). Each process
// assembles the cells that reach its rows, so its owned rows of the residual are complete;
// the contact forces are summed into their owners' rows; the norms
// every decision reads are reduced over processes to the same bits everywhere, so every
// process takes every decision alike. The backend solves the Newton system distributed
// (fem::DofLayout's numbering), each process takes its owned part of the increment, and the
// ghosts are updated from their owners.
//
// Convergence: ||r_free|| <= max(atol, rtol * r_ref), where r_ref is the larger of the
// step's initial free residual and the right side of its first (lifted) system, i.e. the
// size of the load increment. Every stop without convergence carries a named reason. A
// Krylov solve that stops unconverged within ten times its tolerance, or below what Newton's
// own test asks, still gives the update (inexact_direction.hpp); otherwise it is a failed
// linear solve.
//
// Contact (problem.constraints): the multipliers follow the displacement (and pressure)
// unknowns, the system is the augmented (30), and a step converges only when, in addition,
// the states were checked at the final iterate and none changed, and ||r_c|| <= max(atol,
// rtol * r_c,ref), r_c,ref being the largest constraint residual seen in the step. When the
// states may change and when they cycle: active_set_monitor.hpp.
//
// Load increments (run): load step k goes from step_times[k-1] to step_times[k]. An increment
// that fails is retried from the last converged state over half of it (a failed linear solve
// only past the increment's first solve and once per load step), down to max_cuts
// halvings of the step; the reduced size carries over into the next steps and doubles after
// two converged parts at one size (never past a step's end, which every step reaches
// exactly), after twice as many each time the doubled size fails again (up to
// max_regrow_wait). Every attempt, failed or not, reaches the caller as a StepResult.
#include <array>
#include <chrono>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "fem/app_view.hpp"
#include "fem/dof_layout.hpp"
#include "fem/elasticity_assembly.hpp"
#include "fem/ghosted_vector.hpp"
#include "fem/mesh_partition.hpp"
#include "fem/part_ownership.hpp"
#include "mesh/local_mesh.hpp"
#include "nonlinear/active_set_monitor.hpp"
#include "nonlinear/constraint_set.hpp"
#include "nonlinear/dirichlet_lifting.hpp"
#include "nonlinear/linear_solver.hpp"
#include "nonlinear/problem.hpp"
#include "nonlinear/system_builder.hpp"

namespace stiction::nonlinear {

// How tightly each linear system is solved (Krylov backends): Fixed keeps the backend's own
// -ksp_rtol (or newton.krylov_rtol); EisenstatWalker is the inexact Newton of Dembo et al.
// that the paper relies on (Sec. 5), with Eisenstat & Walker's choice 2 on the norms of
// successive Newton right sides (gamma 0.9, alpha 2, first term 0.3, at most 0.9, at most the
// fixed rtol with contact, safeguard when gamma eta^2 > 0.1, PETSc's SNES defaults) and
// Kelley's floor 0.5 tol / ||r||. Under both (the fixed one at the backend's own tolerance:
// a newton.krylov_rtol holds for every solve), once the contact states have settled, a solve
// stops once its residual is below the one Newton's stopping test reads
// (inexact_direction.hpp: terminal_forcing), so the last iteration of a load step is not
// over-solved. The Newton stopping test is the same either way: only the work per linear
// solve changes.
enum class Forcing { Fixed, EisenstatWalker };
Forcing forcing_from_string(const std::string& name);  // "fixed", "eisenstat-walker"
std::string to_string(Forcing f);

struct NewtonSettings {
  double atol = 1e-10;          // absolute tolerance on the free residual norm
  // Relative to the step's reference residual. 1e-6: in the speed/accuracy sweeps
  // (reports/tradeoff) it needs 20-38% fewer Newton and Krylov iterations than 1e-8 on the
  // block with strips, the block without contact and Cattaneo-Mindlin's partial slip (the
  // same on the Hertz sphere), and its error against a tight reference stays below the
  // mesh's own error (against the next level's reference) on all four.
  double rtol = 1e-6;
  int max_iterations = 25;
  int max_backtracks = 10;      // step halvings when a trial state inverts a cell or is NaN
  double divergence_factor = 1e8;  // residual above this times r_ref: diverged
  Forcing forcing = Forcing::Fixed;
  // Relative tolerance of every Krylov solve under the fixed forcing, in place of the
  // backend's -ksp_rtol; under Eisenstat-Walker with contact, the cap on its forcing term
  // (0: the backend's -ksp_rtol, and the cap kContactForcingCap).
  double krylov_rtol = 0;
  // Restart of every GMRES backend's outer Krylov solve, in place of its -ksp_gmres_restart
  // (0: the backend's). The basis is restart + 1 vectors of the system's size: at millions of
  // unknowns it is a large share of an iterative backend's memory, on a small 2D scene none.
  int krylov_restart = 0;
  int max_cuts = 6;             // halvings of a failed load increment (0: a failed step stops the run)
  // Converged parts at a cut size before the run tries the size above again: 2, doubled each
  // time the size above, grown back to, fails again, up to this (2: always 2). Measured on
  // the frictional ironing at level 2 (reports/ironing-2d-L2): with 2, every second load
  // step tried the whole increment again and failed after 25 Newton iterations, 41% of the
  // run's time (20 failed attempts, 1 608 s, against 2 353 s in the 80 converged parts).
  int max_regrow_wait = 16;
  // An increment whose converged state's smallest det F is below this fraction of the one
  // it started from is rejected and cut (0: never): Newton, its contact states wandering,
  // can converge to another solution of the increment with a crushed cell. Measured on the
  // frictional ironing at level 2 (reports/ironing-2d-L2): 0.70 -> 0.063 over one step of
  // 23 iterations, a slab-top cell at the edge of the contact zone, after which every
  // increment stalled; the same step in quarters keeps 0.70 and the run goes on.
  double min_det_f_ratio = 0.5;
  ActiveSetSettings active_set;
};

enum class NewtonReason {
  ConvergedAbsolute,
  ConvergedRelative,
  DivergedMaxIterations,
  DivergedLinearSolver,
  DivergedInvertedElement,
  DivergedNaN,
  DivergedResidualGrowth,
  DivergedActiveSetCycle,  // contact states recur without the residual falling
};
std::string to_string(NewtonReason r);
inline bool converged(NewtonReason r) {
  return r == NewtonReason::ConvergedAbsolute || r == NewtonReason::ConvergedRelative;
}

struct NewtonIteration {
  double residual = 0;          // free residual after the update
  double step_length = 1;       // after backtracking
  double assembly_seconds = 0;  // residual + tangent for this iteration
  // The constraints' (contact's) part of assembly_seconds: their residual and Jacobian, the
  // bordered matrix and the multiplier surface's blocks; the rest is the volume's.
  double contact_assembly_seconds = 0;
  double constraint_residual = 0;  // ||r_c|| after the update (contact rows; 0 without)
  int state_changes = 0;        // contact states changed by this update
  LinearSolveStats linear;
};

struct StepResult {
  int step = 0;        // the load step this increment belongs to
  double time = 0;     // pseudo-time the increment ends at
  int cut = 0;         // halvings of the step's increment (0: the whole step)
  bool retried = false;  // failed, and retried over a smaller increment from the last converged state
  bool completes_step = false;  // converged at the end of its load step
  NewtonReason reason = NewtonReason::DivergedMaxIterations;
  double initial_residual = 0, reference_residual = 0, final_residual = 0;
  std::vector<NewtonIteration> iterations;
  std::map<std::string, std::array<double, 3>> reactions;  // per Dirichlet condition
  std::vector<ConstraintSummary> contact;                  // per contact pair, when converged
  // Integral of the traction P N over each Dirichlet boundary (by its name: the paper's F1)
  // and each contact surface ("<pair>/slave": F4, "<pair>/master": -F5), when converged.
  std::map<std::string, std::array<double, 3>> surface_forces;
  // Smallest det F of the converged state (fem::InternalForceStatus::min_det_f; +inf with
  // no finite-strain cell), when converged.
  double min_det_f = std::numeric_limits<double>::quiet_NaN();
  double wall_seconds = 0;
  std::string detail;  // human-readable context for a failure
  bool converged() const { return nonlinear::converged(reason); }
};

class QuasiStaticSolver {
public:
  QuasiStaticSolver(MPI_Comm comm, const ElasticityProblem& problem, const NewtonSettings& settings,
                    LinearSolver& linear);
  // Over a mesh part (scene::divide_scene): problem.space is the part's space, ownership its
  // unknowns' owners and indices (kept by the layout: pass it moved when done with it), the
  // contact multipliers among them when problem has constraints over the part's space. Outputs that are whole (displacement(),
  // state()) are in the whole space's app order.
  QuasiStaticSolver(MPI_Comm comm, const ElasticityProblem& problem, const mesh::LocalMesh& part,
                    fem::PartOwnership ownership, const NewtonSettings& settings, LinearSolver& linear);

  // Newton for load step `step` in one increment, from the current state.
  StepResult solve_step(int step);
  // Newton for an increment of load step `step` from the current state to pseudo-time t.
  StepResult solve_increment(int step, double t);
  // Steps first_step..last_step (-1: n_steps) with cut-backs; calls on_step after each
  // attempt; stops at the first step that fails at max_cuts halvings (or on a failed linear
  // solve that may not be retried: retry_allowed).
  std::vector<StepResult> run(const std::function<void(const StepResult&)>& on_step = {}, int first_step = 1,
                              int last_step = -1);

  // What a converged state carries into the next increment, whole: what a checkpoint keeps.
  // state() and restore() are collective: state() gathers u in app order on process 0 only
  // (u is empty on the others), restore() reads u on process 0 only (it sends each process
  // its part) and the rest on every process.
  struct State {
    int step = 0;      // the last load step completed
    double time = 0;   // its pseudo-time (or of the last converged part of the next step)
    std::vector<double> u, lambda;
    std::vector<std::vector<double>> constraints;  // MultiplierConstraint::save_state, in order
  };
  State state() const;
  void restore(const State& s);  // throws when s does not fit this problem
  // The run's linear solves so far and how many of them failed (retry_allowed reads them);
  // a checkpoint carries them, so that a restart retries as the uninterrupted run would.
  struct LinearTally {
    int solves = 0, failures = 0;
  };
  const LinearTally& linear_tally() const { return tally_; }
  void set_linear_tally(const LinearTally& tally) { tally_ = tally; }
  // The cut-back's state as run leaves it between load steps: the halvings in force (they
  // carry over into the next step), the parts converged at that size, the parts to wait at
  // each size before growing back (empty: 2 at every size) and whether the current size was
  // just grown back to. A checkpoint carries it, so that a restart takes the increments the
  // uninterrupted run would (on a frictional path other increments give another solution).
  struct CutBack {
    int cut = 0, converged_at_cut = 0;
    std::vector<int> wait;
    bool probing = false;
  };
  const CutBack& cut_back() const { return cut_back_; }
  void set_cut_back(const CutBack& c) { cut_back_ = c; }

  // The displacement (and pressure) state, whole in app order, on every process (gathered
  // on several: every process must call it).
  std::vector<double> displacement() const;
  // The same as this process holds it (no communication): its owned unknowns and the ghosts
  // of the nodes of its own cells (partition().owned_cells), of the cells that reach its
  // rows and of every constraint's surfaces. What each process writes its output from.
  fem::StateView held_displacement() const { return u_.view(); }
  // Contact multipliers of every constraint, in order (empty without contact).
  const std::vector<double>& multipliers() const { return lambda_; }
  // The last assembled Newton system (for record/replay and tests), in layout()'s numbering.
  const NewtonSystem& system() const { return builder_.system(); }
  Mat tangent_beside_system() const { return builder_.tangent_beside_system(); }
  const fem::DofLayout& layout() const { return layout_; }
  const fem::MeshPartition& partition() const { return partition_; }
  // Called after every linear solve with the system, the increment found and its figures
  // (record/replay hooks in here).
  using SystemObserver =
      std::function<void(const NewtonSystem&, Vec increment, const LinearSolveStats&, int step, int iteration)>;
  void set_system_observer(SystemObserver observer) { observer_ = std::move(observer); }
  // Called for every multiplier node whose contact state a Newton update changed, with the
  // node as it is after the update (`stiction solve --trace-contact` prints them).
  struct StateChange {
    int step = 0, iteration = 0;
    std::string constraint;
    int node = 0;     // multiplier node within its constraint
    char before = 0;  // the state before the update (MultiplierNode::state's codes)
    MultiplierNode after;
  };
  using StateChangeObserver = std::function<void(const StateChange&)>;
  void set_state_change_observer(StateChangeObserver observer) { state_observer_ = std::move(observer); }
  // Called after every Newton iteration with the increment's load step, its target
  // pseudo-time and the iteration's record, before the increment ends (a run's record can
  // then keep the solves of an increment that a time limit cuts short).
  using IterationObserver = std::function<void(int step, double t, const NewtonIteration&)>;
  void set_iteration_observer(IterationObserver observer) { iteration_observer_ = std::move(observer); }

private:
  struct Residuals;
  // The unknowns this process reads besides its own: the nodes of its row cells (assembly),
  // of its own cells (output) and of every constraint's surfaces (contact).
  QuasiStaticSolver(MPI_Comm comm, const ElasticityProblem& problem, const mesh::LocalMesh* part,
                    fem::PartOwnership* ownership, const NewtonSettings& settings, LinearSolver& linear);
  std::vector<PetscInt> unknowns_read() const;
  // The residual r(u) = f_int - f_ext at pseudo-time t (constrained rows included; on
  // several processes complete in the owned rows only), and the status over every process.
  fem::InternalForceStatus residual(double t, fem::StateView u, fem::GhostedVector& r) const;
  // residual's dead loads (body force, tractions).
  void add_loads(double t, fem::ResidualView r) const;
  // Elastic part and constraint part of the residual at (u, lambda).
  fem::InternalForceStatus evaluate(double t, fem::StateView u, const std::vector<double>& lambda,
                                    Residuals& r) const;
  // The retry point of a cut-back: the converged state as this process holds it.
  struct Snapshot {
    int step = 0;
    double time = 0;
    fem::GhostedVector u;
    std::vector<double> lambda;
    std::vector<std::vector<double>> constraints;
  };
  Snapshot snapshot() const;
  void restore(const Snapshot& s);
  // The system at the current iterate for its residual r (the backend's old set-up released first).
  void assemble_system(const Residuals& r, bool lift);
  // The step predictor's states when no node is in contact (see solve_increment).
  int first_states(int step, double t, Residuals& r);
  // After an accepted Newton update dl: the contact states, when the monitor lets them
  // change, and the constraint rows of r for the new states; returns the monitor's verdict.
  struct StateUpdate {
    bool checked = true;  // the states were tested at this iterate
    int changes = 0;
    ActiveSetMonitor::Verdict verdict = ActiveSetMonitor::Verdict::Continue;
  };
  StateUpdate update_states(int step, int iteration, double t, const std::vector<double>& dl, double reference,
                            double c_reference, ActiveSetMonitor& monitor, Residuals& r);
  static bool retry_allowed(const StepResult& failed, bool linear_failure_retried, const LinearTally& tally);
  static constexpr double kSporadicLinearFailures = 0.02;  // retry_allowed
  // Half the smallest of Newton's absolute tolerances on the free and constraint residuals
  // (zero while a Dirichlet lifting is pending): a linear residual below it meets them all.
  double terminal_linear_residual(double reference, double c_reference, bool pending) const;
  void report_state_changes(int step, int iteration, double t, const std::vector<char>& before) const;
  // Pieces of solve_increment's checks and messages: a start state with an inverted or
  // folded cell ends the run (throws); a converged state is refused (the reason returned,
  // empty when it is accepted) when it holds a folded cell or det F fell too far.
  void reject_invalid_start(int step, const fem::InternalForceStatus& start) const;
  std::string unacceptable_converged_state(const fem::InternalForceStatus& start,
                                           const fem::InternalForceStatus& accepted) const;
  std::string contact_residual_detail(double cnorm, double c_reference, int last_changes) const;
  // The Krylov tolerance of the next solve: the scene's (or the backend's), or
  // Eisenstat-Walker's from the right sides of the systems so far (see Forcing above), raised
  // where the solve would otherwise go below terminal_residual (terminal_forcing; 0: never).
  struct ForcingHistory {
    double eta = 0, rhs_prev = 0;
  };
  void set_krylov_tolerance(bool first, double rnorm, double reference, double terminal_residual,
                            ForcingHistory& forcing);
  // The Newton update du of the assembled system; false when the solve gave none usable.
  bool solve_for_direction(int step, int it, double terminal_residual, Vec du, LinearSolveStats& stats);
  std::string linear_failure_detail(const LinearSolveStats& stats) const;
  // Pieces of solve_increment: the split of a Newton update into u (and p) and multipliers,
  // the backtracked step (u_ and lambda_ move only when it succeeds), and the norm of the
  // constraint forces in a residual.
  struct TrialStep {
    double alpha = 1;
    double assembly_seconds = 0;
    fem::InternalForceStatus status;  // of the last trial state evaluated (the accepted one unless failed)
    bool failed = false;
    NewtonReason failure = NewtonReason::DivergedNaN;  // when failed
  };
  void split_update(Vec du, fem::GhostedVector& dv, std::vector<double>& dl) const;
  TrialStep take_step(double t, const fem::GhostedVector& dv, const std::vector<double>& dl, Residuals& rt);
  std::string trial_failure_detail(const TrialStep& trial) const;
  double contact_force_norm(const Residuals& r) const;
  std::string describe_cell(int c) const {
    return part_ ? "cell " + std::to_string(c) + " of the whole mesh" : mesh::describe_cell(problem_.space->mesh(), c);
  }
  // The cells a status names, in the whole mesh's numbering when the mesh is a part's (so
  // that every process names the same cell).
  fem::InternalForceStatus with_whole_cell_ids(fem::InternalForceStatus status) const;
  // The whole space's displacement and pressure unknowns (the part's space holds fewer).
  size_t n_whole_dofs() const { return static_cast<size_t>(layout_.n_total() - constraints_.n_multipliers()); }
  std::map<std::string, std::array<double, 3>> surface_forces() const;

  const ElasticityProblem& problem_;
  NewtonSettings settings_;
  LinearSolver& linear_;
  DirichletLifting lifting_;
  ConstraintSet constraints_;
  fem::MeshPartition partition_;  // the cells this rank assembles (over a part: its own cells)
  const mesh::LocalMesh* part_;   // null over the whole mesh
  fem::DofLayout layout_;         // the Newton system's numbering across ranks
  NewtonSystemBuilder builder_;
  std::shared_ptr<const fem::GhostPattern> pattern_;  // what this process holds of u
  // Over the whole layout, so that the increment copies in whole: its multiplier entries
  // follow the increments but nothing reads them (the multipliers are lambda_), and a
  // restored state leaves them zero.
  fem::GhostedVector u_;
  std::vector<double> lambda_;  // contact multipliers (augmented unknowns n_u..), whole
  // Each process's share of the contact forces before they are summed into their owners'
  // rows (several processes with contact; made at the first evaluation).
  mutable std::unique_ptr<fem::GhostedVector> contact_share_;
  // Seconds the constraints took in the evaluations and assemblies since the last Newton
  // iteration's record (NewtonIteration::contact_assembly_seconds).
  mutable double contact_seconds_ = 0;
  LinearTally tally_;
  CutBack cut_back_;
  double time_ = 0;             // pseudo-time of the current converged state
  double target_time_ = 0;      // pseudo-time of the increment being solved
  int completed_step_ = 0;      // the last load step completed
  SystemObserver observer_;
  StateChangeObserver state_observer_;
  IterationObserver iteration_observer_;
};

}  // namespace stiction::nonlinear
