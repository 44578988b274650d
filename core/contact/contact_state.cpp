#include "contact/contact_state.hpp"

#include <cmath>

namespace stiction::contact {

std::string to_string(NodeState s) {
  switch (s) {
    case NodeState::Inactive: return "inactive";
    case NodeState::Stick: return "stick";
    case NodeState::Slip: return "slip";
  }
  return "unknown";
}

NodeState next_state(NodeState now, const NodeQuantities& q, double mu, const StateTolerances& tol) {
  if (now == NodeState::Inactive) {
    if (q.gn >= -tol.gap) return NodeState::Inactive;
    if (mu > 0 && q.gt_norm <= mu * std::abs(q.gn)) return NodeState::Stick;  // B
    return NodeState::Slip;                                                   // A
  }
  if (q.lambda_n < -tol.force) return NodeState::Inactive;  // C
  if (mu == 0) return NodeState::Slip;                      // frictionless: lambda_t = 0
  if (now == NodeState::Slip && q.lambda_t_norm > tol.force && q.gt_dot_lt > tol.slip * q.gt_norm * q.lambda_t_norm)
    return NodeState::Stick;  // D
  if (now == NodeState::Stick && q.lambda_t_norm > mu * q.lambda_n * (1 + tol.slip) + tol.force)
    return NodeState::Slip;  // E
  return now;
}

}  // namespace stiction::contact
