#include "analytic_reference.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "csv_table.hpp"

namespace stiction::harness {

const std::map<std::string, std::string>& embedded_reference();  // generated

namespace {

// The row of reference table `table` (an embedded CSV's stem) for the scene, if any.
std::optional<std::map<std::string, std::string>> case_row(const std::string& table, const std::string& scene_name) {
  for (const auto& row : parse_csv(embedded_reference().at(table)).rows)
    if (row.at("scene") == scene_name) return row;
  return std::nullopt;
}

}  // namespace

std::optional<HertzCase> hertz_case(const std::string& scene_name) {
  const auto row = case_row("hertz-cases", scene_name);
  if (!row) return std::nullopt;
  return HertzCase{scene_name, static_cast<int>(number(*row, "dim")), number(*row, "R_star"), number(*row, "E_star"),
                   number(*row, "force_factor")};
}

double HertzComparison::a_error() const { return std::abs(a_fit / a_hertz - 1); }
double HertzComparison::p0_error() const { return std::abs(p0_fit / p0_hertz - 1); }

HertzComparison compare_with_hertz(const HertzCase& c, double vertical_force,
                                   const std::vector<std::pair<double, double>>& in_contact) {
  HertzComparison h;
  const double P = c.force_factor * std::abs(vertical_force);
  if (c.dim == 2) {
    h.a_hertz = std::sqrt(4 * P * c.R_star / (M_PI * c.E_star));
    h.p0_hertz = 2 * P / (M_PI * h.a_hertz);
  } else {
    h.a_hertz = std::cbrt(3 * P * c.R_star / (4 * c.E_star));
    h.p0_hertz = 3 * P / (2 * M_PI * h.a_hertz * h.a_hertz);
  }
  // p^2 = alpha + beta r^2 by least squares: p0^2 = alpha, a^2 = -alpha / beta.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(in_contact.size());
  for (const auto& [r, p] : in_contact) {
    const double x = r * r, y = p * p;
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double beta = (n * sxy - sx * sy) / (n * sxx - sx * sx), alpha = (sy - beta * sx) / n;
  h.a_fit = std::sqrt(-alpha / beta);
  h.p0_fit = std::sqrt(alpha);
  return h;
}

std::optional<MindlinCase> mindlin_case(const std::string& scene_name) {
  const auto row = case_row("cattaneo-mindlin-cases", scene_name);
  if (!row) return std::nullopt;
  return MindlinCase{scene_name, number(*row, "R_star"), number(*row, "E_star"), number(*row, "mu")};
}

double MindlinComparison::stick_zone_error() const { return std::abs(c_computed - c) / a; }

MindlinComparison compare_with_mindlin(const MindlinCase& m, double P, double Q, const std::vector<double>& stick,
                                       const std::vector<double>& slip) {
  MindlinComparison r;
  P = std::abs(P), Q = std::abs(Q);
  r.a = std::sqrt(4 * P * m.R_star / (M_PI * m.E_star));
  r.c = r.a * std::sqrt(std::max(0.0, 1 - Q / (m.mu * P)));
  // Both sides of the zone folded onto |x|: the computed edge lies between the outermost
  // sticking and the innermost slipping node.
  const double outer_stick = *std::max_element(stick.begin(), stick.end());
  const double inner_slip = *std::min_element(slip.begin(), slip.end());
  r.c_computed = 0.5 * (outer_stick + inner_slip);
  return r;
}

double PatchCase::pressure() const {
  const auto M = [this](double E) { return E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)); };
  return delta / (H1 / M(E1) + H2 / M(E2));
}

std::optional<PatchCase> patch_case(const std::string& scene_name) {
  const auto row = case_row("patch-cases", scene_name);
  if (!row) return std::nullopt;
  return PatchCase{scene_name,         number(*row, "delta"), number(*row, "H1"), number(*row, "E1"),
                   number(*row, "H2"), number(*row, "E2"),    number(*row, "nu")};
}

double patch_pressure_error(const PatchCase& c, const std::vector<double>& normal_multipliers) {
  const double p = c.pressure();
  double worst = 0;
  for (double p_i : normal_multipliers) worst = std::max(worst, std::abs(p_i / p - 1));
  return worst;
}

}  // namespace stiction::harness
