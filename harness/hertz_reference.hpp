#pragma once
// Hertz's contact half-width (radius) and peak pressure for the built-in scenes that model
// a Hertz case (reference/hertz: formulas, source and the cases), and the same two figures
// read off a computed pressure profile by a least-squares fit of p^2 = p0^2 (1 - r^2 / a^2).
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
  double a_error() const { return std::abs(a_fit / a_hertz - 1); }
  double p0_error() const { return std::abs(p0_fit / p0_hertz - 1); }
};

// vertical_force: the modelled part's contact force (its sign is ignored); in_contact: (r,
// p) of every slave node in contact, r its reference distance from the axis of symmetry, p
// the magnitude of its multiplier. Needs two nodes at different r.
HertzComparison compare_with_hertz(const HertzCase& c, double vertical_force,
                                   const std::vector<std::pair<double, double>>& in_contact);

}  // namespace stiction::harness
