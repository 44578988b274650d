#pragma once
// The contact state of a slave node and the state machine of the paper's Sec. 4.5,
// evaluated after every linear solve with the new iterate.
//
//   A inactive -> slip   if gn < -tol_gap and |gt| >  mu |gn|   (mu = 0: always slip)
//   B inactive -> stick  if gn < -tol_gap and |gt| <= mu |gn|
//   C contact  -> inactive if lambda_n < -tol_force
//   D slip     -> stick  if gt . lambda_t > tol_slip |gt| |lambda_t| (the slip reversed)
//   E stick    -> slip   if |lambda_t| > mu lambda_n (1 + tol_slip)
//
// Choice for C: the paper tests "gn > 0 and lambda_n <= 0", but a contact node's weighted
// gap is zero after every solve (its row of (30) enforces it exactly), so the gap half of
// the test never fires; the dual test on lambda_n alone is the primal-dual active set of
// Hueber & Wohlmuth. The tolerances are scene settings (contact.*_tolerance); their effect
// on the state changes per Newton step is not yet measured (tests/unit/contact checks the
// transitions only).
#include <string>

namespace stiction::contact {

enum class NodeState : char { Inactive = 0, Stick = 1, Slip = 2 };
std::string to_string(NodeState s);

struct StateTolerances {
  double gap = 0;     // absolute, on the weighted gap gn_i
  double force = 0;   // absolute, on lambda_n
  double slip = 1e-9; // relative, on the Coulomb cone in E and the reversal cosine in D
};

// Quantities of one node at the new iterate (weighted gaps, nodal multiplier parts).
struct NodeQuantities {
  double gn = 0;        // weighted normal gap (negative: penetration)
  double gt_norm = 0;   // |gt|, weighted tangential slip increment
  double gt_dot_lt = 0; // gt . lambda_t
  double lambda_n = 0;
  double lambda_t_norm = 0;
};

NodeState next_state(NodeState now, const NodeQuantities& q, double mu, const StateTolerances& tol);

}  // namespace stiction::contact
