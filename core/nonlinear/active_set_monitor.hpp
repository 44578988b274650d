#pragma once
// When the contact states of a Newton solve may change, and when their changes go round in
// circles (paper Sec. 4.5 applies the state machine after every linear solve).
//
// Gate (choice, where the paper updates after every solve): the states are updated only at an
// iterate whose residual for the current states is at most update_tolerance times the
// reference, max(||r_u|| / r_ref, ||r_c|| / r_c,ref) <= update_tolerance, or once the states
// have been held for max_held iterations: a wild iterate never decides the states. Cause of
// the cycles it removes, measured on the frictionless shallow ironing (ironing-2d-frictionless,
// level 0, lu-mumps): the first solve after contact moves the indenter by the whole load
// increment, and the iterate right after the states enter is off by the nonlinear error of
// that jump (residual 1.6e2 x the reference). The state machine read its gaps and
// multipliers: a node at the edge of the contact zone penetrated (gn / m = -1.8e-3) because
// its neighbours' pressures were not yet right, entered, showed a tension of -31 (pressures
// near 80) at the next iterate, left, came back: DIVERGED_ACTIVE_SET_CYCLE in the first
// contact step, whatever the normal linearisation. Held until the iterate solved its states,
// the step converged with the seven nodes of the first guess and that node free (gap
// positive). Newton iterations of the first contact steps (t = 0.3, 0.4) and of step 2 of
// the sphere on a flat block (tests/verification/test_master_point.cpp, paper rule 5 + 6):
//   update_tolerance 1e-3: 6, 10 and 12;  0.1: 5, 9 and 9;  1 (default): 5, 7 and <= 8;
//   0 (the paper): cycle at t = 0.3.
// Its price where the paper's rule converged (level-0 iteration baseline, lu-mumps, Newton
// iterations over all steps, paper -> gate): hertz-cylinder-2d 5 -> 6, hertz-cylinders-2d
// 10 -> 11, hertz-sphere-3d 7 -> 8, hertz-spheres-3d 10 -> 11, sliding-block-2d 7 -> 8,
// self-contact-2d 28 -> 31; state_update_tolerance = 0 restores the paper's Newton path.
// Cycle: a set of states that recurs without the residual having fallen since it was last
// left. The remedy (before the step gives up with DIVERGED_ACTIVE_SET_CYCLE) tightens the
// gate by remedy_factor, so the next updates read better-converged iterates; cycle_remedies
// such tightenings are allowed per increment.
#include <map>
#include <vector>

namespace stiction::nonlinear {

struct ActiveSetSettings {
  double update_tolerance = 1.0;   // relative; 0: update after every linear solve (the paper)
  int max_held = 8;                // iterations the states may be held before an update is forced
  int cycle_remedies = 2;          // gate tightenings per increment before a cycle stops it
  double remedy_factor = 1e-2;     // what each tightening multiplies update_tolerance by
};

class ActiveSetMonitor {
public:
  explicit ActiveSetMonitor(const ActiveSetSettings& settings) : settings_(settings), gate_(settings.update_tolerance) {}

  // Whether the states are updated at an iterate whose fixed-state residual is `progress`
  // (relative, as above); `converged` iterates are always checked.
  bool may_update(double progress, bool converged);

  enum class Verdict { Continue, Remedied, Cycle };
  // After an update from `before` (left with residual `left_at`) to `now` (residual
  // `residual_now`): Cycle when `now` recurs without progress and no remedy is left.
  Verdict after_update(const std::vector<char>& before, const std::vector<char>& now, double left_at,
                       double residual_now);

  double gate() const { return gate_; }
  int remedies_used() const { return remedies_; }

private:
  ActiveSetSettings settings_;
  double gate_;
  int held_ = 0;
  int remedies_ = 0;
  std::map<std::vector<char>, double> seen_;  // states left, with the residual when they were left
};

}  // namespace stiction::nonlinear
