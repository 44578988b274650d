#pragma once
// A constraint enforced by Lagrange multipliers with an active set (contact, paper Sec. 4-5).
// The Newton driver appends its multipliers after the displacement (and pressure) unknowns
// and solves the augmented system (30)
//
//   [ A     -B^T ] [du     ]   [ -r_u ]
//   [ C_u   C_l  ] [dlambda] = [ -r_c ]
//
// where r_u already contains the constraint forces (-B^T lambda) and r_c the constraint
// rows of the current states. States (inactive / stick / slip) are frozen during one linear
// solve and updated after it; the step converges only when no state changed.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <mpi.h>
#include <petscsys.h>

#include "fem/app_view.hpp"

namespace stiction::fem {
class FieldSpace;
}

namespace stiction::nonlinear {

// Sparse entries (row, col, value) in the augmented numbering; duplicates are summed.
struct SparseEntries {
  std::vector<PetscInt> rows, cols;
  std::vector<double> values;
  void add(PetscInt r, PetscInt c, double v) {
    rows.push_back(r);
    cols.push_back(c);
    values.push_back(v);
  }
  size_t size() const { return values.size(); }
  void clear() { rows.clear(), cols.clear(), values.clear(); }
};

// What a constraint tells a preconditioner of its multipliers, in their numbering. The
// solver side forms the paper's Schur approximation (32) from it (solvers/multiplier_schur_parts).
//   mass         M_lambda, the slave surface's mass matrix (alike on each node's components);
//   laplacian    K = int grad_s phi_i . grad_s phi_j on the same surface, likewise;
//   projector    Pi, block-diagonal: the directions each node's state constrains (all of a
//                sticking node, its normal n n^T when slipping, none when inactive);
//   constrained  the identity on the nodes that carry a constraint (not the inactive ones);
//   slip_rows    block-diagonal: dc_i/dS_i where a constrained row depends on the
//                displacement through more than Pi (a slipping node's tangential row through
//                its slip S_i, (19)); zero elsewhere.
// Only non-zero entries are listed, so the zero blocks stay out of the matrices' patterns.
struct MultiplierSurfaceEntries {
  SparseEntries mass, laplacian, projector, constrained, slip_rows;
};

// What one constraint reports per load step.
struct ConstraintSummary {
  std::string name;
  int inactive = 0, stick = 0, slip = 0;
  std::array<double, 3> force{0, 0, 0};  // integral of lambda over the slave surface (F3)
};

// One multiplier node as a user checks contact: where it is, its gap, its multiplier and
// state (contact.csv and the VTU output).
struct MultiplierNode {
  int vertex = -1;                          // mesh vertex of the node
  std::array<double, 3> position{0, 0, 0};  // current position x = X + u
  double gap = 0;                           // mean normal gap gn_i / m_i (negative: penetration)
  std::array<double, 3> multiplier{0, 0, 0};  // lambda_i, the traction on the slave
  double normal = 0;                        // lambda_n = n . lambda (positive presses)
  std::array<double, 3> tangential{0, 0, 0};  // lambda_t = lambda - n lambda_n
  char state = 0;                           // 0 inactive, 1 stick, 2 slip
};

class MultiplierConstraint {
public:
  virtual ~MultiplierConstraint() = default;
  virtual std::string name() const = 0;
  virtual int n_multipliers() const = 0;
  // The mesh vertex (slave node) each multiplier belongs to, n_multipliers() entries: the
  // rank that owns the vertex owns the multiplier's row (fem::DofLayout).
  virtual std::vector<int> multiplier_vertices() const = 0;
  // In a run on several processes: the communicator and which of the constraint's
  // multipliers this process owns (owned[k] for multiplier k; the rows of a node's
  // multipliers have one owner). From then on a constraint may evaluate on each process only
  // what that process owns, provided evaluate still returns, on every process, every r_c
  // entry, adds to r_u a share of the constraint force such that the shares of all
  // processes sum to the whole force (the caller sums them: fem::GhostedVector::
  // add_ghosts_to_owners), and computes each Jacobian entry (any row) on one process alone:
  // the system builder sends each entry to the owner of its row. Without the call, or with
  // owned empty, every process evaluates everything.
  virtual void distribute(MPI_Comm comm, const std::vector<char>& owned) {}
  // At the start of a load increment from pseudo-time t_start, u is the converged state there:
  // the reference of the tangential slip increments (15)-(16).
  virtual void begin_increment(double t_start, fem::StateView u) = 0;
  // Adds the constraint forces to r_u (r_u -= B^T lambda), writes the constraint rows r_c
  // (n_multipliers entries) for the current states, and, when jacobian is not null, adds
  // the blocks -B^T, C_u and C_l. Multiplier k of this constraint is unknown
  // `offset + k` of the augmented system; lambda points at this constraint's multipliers.
  virtual void evaluate(double t, fem::StateView u, const double* lambda, fem::ResidualView r_u,
                        double* r_c, SparseEntries* jacobian, PetscInt offset) const = 0;
  // The constraint rows r_c alone, for the current states: after a state update at an
  // iterate already evaluated, the new states change the rows, not the forces on r_u.
  virtual void evaluate_rows(double t, fem::StateView u, const double* lambda, double* r_c) const = 0;
  // After a Newton update: applies the state machine (transitions A-E of Sec. 4.5) at the
  // new iterate; returns how many states changed.
  virtual int update_states(double t, fem::StateView u, const double* lambda, const double* dlambda) = 0;
  // After a Newton update at which the driver held the states (active_set_monitor.hpp):
  // what the constraint tracks of the multipliers' progress besides its states.
  virtual void states_held(const double* lambda, const double* dlambda) {}
  // The current states, one char per multiplier node (for cycle detection and the step
  // predictor); kFreeState marks a node that carries no constraint (inactive).
  static constexpr char kFreeState = 0;
  virtual std::vector<char> states() const = 0;
  // The multiplier surface as a preconditioner needs it (MultiplierSurfaceEntries), at the
  // last iterate evaluated with its Jacobian; multiplier k is row/column `offset + k`.
  virtual void describe_surface(MultiplierSurfaceEntries& out, PetscInt offset) const = 0;
  virtual ConstraintSummary summary(const double* lambda) const = 0;
  // Everything besides the multipliers that a converged state carries into the next
  // increment (the contact states), to retry a failed increment from it.
  virtual std::vector<double> save_state() const = 0;
  virtual void restore_state(const std::vector<double>& saved) = 0;
  // The boundary facets the constraint acts on, by role ("slave", "master"), for the
  // traction integrals the Newton driver reports per load step (paper's F4, F5).
  virtual std::vector<std::pair<std::string, int>> surfaces() const { return {}; }
  // Every multiplier node at (t, u, lambda) for reports; lambda points at this constraint's
  // multipliers. One process may call it alone (it writes the output).
  virtual std::vector<MultiplierNode> nodes(double t, fem::StateView u, const double* lambda) const = 0;
  // The same constraint as built (its settings; no state, no distribution) over another
  // space whose mesh holds the same surfaces: a mesh part that holds them whole
  // (mesh::local_part with surface_tags). Its multipliers are the same nodes in the same
  // order, at the part's vertices.
  virtual std::unique_ptr<MultiplierConstraint> over(const fem::FieldSpace& space) const = 0;
};

}  // namespace stiction::nonlinear
