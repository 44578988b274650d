#pragma once
// How far one run's final state lies from a reference run's on the same scene and mesh
// (the trade-off sweep's accuracy, never a proxy such as a residual): the displacement in
// the L2 norm and the H1 seminorm, the contact force, the peak contact pressure and the
// contact states at the last load step, each relative to the reference.
#include <optional>
#include <string>

#include "scene/scene.hpp"

namespace stiction::harness {

struct SolutionAccuracy {
  double displacement_l2 = 0;   // ||u - u_ref||_L2 / ||u_ref||_L2
  double displacement_h1 = 0;   // |u - u_ref|_H1 / |u_ref|_H1
  bool contact = false;         // the scene has contact pairs (the figures below are set)
  double contact_force = 0;     // |F - F_ref| / |F_ref| over every pair's force (F3)
  double peak_pressure = 0;     // |max lambda_n - max lambda_n,ref| / max lambda_n,ref
  int state_changes = 0;        // slave nodes whose state (inactive / stick / slip) differs
};

// How much a finer mesh changes the answer (the discretisation error a solver tolerance
// cannot go below usefully): the relative differences of the displacement's L2 norm and H1
// seminorm (a lower bound of the norms of the difference, which lives on two meshes),
// of the contact force and of the peak contact pressure between the two levels' final states.
struct LevelDifference {
  double displacement_l2 = 0, displacement_h1 = 0;
  bool contact = false;
  double contact_force = 0, peak_pressure = 0;
};

LevelDifference compare_levels(const scene::Scene& coarse, const std::string& coarse_dir, const scene::Scene& fine,
                               const std::string& fine_dir);

// Against the analytic solution, where the scene models one (harness/analytic_reference.hpp),
// at the last load step; a figure is unset when the final state has too few contact nodes
// to measure it:
//   Hertz: the relative errors of the contact half-width (radius) and peak pressure fitted
//     to the pressure profile, against Hertz's for the computed force;
//   Cattaneo-Mindlin: the distance of the computed stick-zone edge from Mindlin's, over a;
//   contact patch test: the largest relative deviation of a slave node's pressure.
struct AnalyticAccuracy {
  std::optional<double> hertz_a, hertz_p0, stick_zone, patch_pressure;
};
std::optional<AnalyticAccuracy> analytic_accuracy(const scene::Scene& scene, const std::string& run_dir);

// run_dir and reference_dir are `stiction solve` output directories of `scene` (their
// checkpoint.bin, steps.csv and contact.csv) that both completed every load step. Throws
// stiction::Error when either is missing, of another scene or level, or did not finish.
SolutionAccuracy compare_to_reference(const scene::Scene& scene, const std::string& run_dir,
                                      const std::string& reference_dir);

}  // namespace stiction::harness
