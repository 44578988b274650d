#pragma once
// The analytic solutions the built-in contact scenes model, each read from its folder of
// reference/ (formulas and sources in the folder's README), and the figures of a computed
// state they are compared with:
//   Hertz (reference/hertz): contact half-width (radius) and peak pressure, fitted to a
//     computed pressure profile by least squares on p^2 = p0^2 (1 - r^2 / a^2);
//   Cattaneo-Mindlin (reference/cattaneo-mindlin): the stick zone's half-width;
//   the contact patch test (reference/contact-patch): a uniform interface pressure.
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace stiction::harness {

struct HertzCase {
  std::string scene;
  int dim = 2;
  double R_star = 0, E_star = 0;
  double force_factor = 1;  // total force P over the modelled part's vertical contact force
};

// The case the scene models (reference/hertz/hertz-cases.csv), if any.
std::optional<HertzCase> hertz_case(const std::string& scene_name);

struct HertzComparison {
  double a_hertz = 0, p0_hertz = 0;  // Hertz's, for the computed force
  double a_fit = 0, p0_fit = 0;      // of the computed profile
  double a_error() const;
  double p0_error() const;
};

// vertical_force: the modelled part's contact force (its sign is ignored); in_contact: (r,
// p) of every slave node in contact, r its reference distance from the axis of symmetry, p
// the magnitude of its multiplier. Needs two nodes at different r.
HertzComparison compare_with_hertz(const HertzCase& c, double vertical_force,
                                   const std::vector<std::pair<double, double>>& in_contact);

// Plane-strain partial slip of two similar cylinders
// (reference/cattaneo-mindlin/cattaneo-mindlin-cases.csv).
struct MindlinCase {
  std::string scene;
  double R_star = 0, E_star = 0, mu = 0;
};
std::optional<MindlinCase> mindlin_case(const std::string& scene_name);

struct MindlinComparison {
  double a = 0, c = 0;   // Hertz's half-width and Mindlin's stick-zone half-width for P, Q
  double c_computed = 0;  // midway between the outermost stick and the innermost slip node
  double stick_zone_error() const;  // |c_computed - c| / a
};

// P, Q: the normal and tangential contact force (per unit length; Q < mu P); stick and
// slip: the distances |x| from the initial contact point of the slave nodes that stick and
// that slip. Needs at least one of each.
MindlinComparison compare_with_mindlin(const MindlinCase& m, double P, double Q, const std::vector<double>& stick,
                                       const std::vector<double>& slip);

// Two stacked blocks between rollers shortened by delta (reference/contact-patch/patch-cases.csv).
struct PatchCase {
  std::string scene;
  double delta = 0, H1 = 0, E1 = 0, H2 = 0, E2 = 0, nu = 0;
  double pressure() const;  // delta / (H1 / M1 + H2 / M2), M the constrained modulus
};
std::optional<PatchCase> patch_case(const std::string& scene_name);

// The largest |p_i / p - 1| over the slave nodes' normal multipliers p_i.
double patch_pressure_error(const PatchCase& c, const std::vector<double>& normal_multipliers);

}  // namespace stiction::harness
