#include "hertz_reference.hpp"

#include <cmath>
#include <map>

#include "csv_table.hpp"

namespace stiction::harness {

const std::map<std::string, std::string>& embedded_reference();  // generated

std::optional<HertzCase> hertz_case(const std::string& scene_name) {
  for (const auto& row : parse_csv(embedded_reference().at("hertz-cases")).rows)
    if (row.at("scene") == scene_name)
      return HertzCase{scene_name, static_cast<int>(number(row, "dim")), number(row, "R_star"), number(row, "E_star"),
                       number(row, "force_factor")};
  return std::nullopt;
}

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

}  // namespace stiction::harness
