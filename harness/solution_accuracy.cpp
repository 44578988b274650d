#include "solution_accuracy.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "checkpoint.hpp"
#include "common/error.hpp"
#include "csv_table.hpp"
#include "fem/error_norms.hpp"
#include "analytic_reference.hpp"

namespace stiction::harness {

namespace {

struct FinalState {
  std::vector<double> u;
  // Every slave node at the last step: its mesh vertex, state, normal multiplier and the
  // multiplier's magnitude.
  struct SlaveNode {
    int vertex = 0;
    std::string state;
    double lambda_n = 0, lambda_norm = 0;
  };
  std::vector<SlaveNode> slave_nodes;
  std::vector<double> contact_force;           // every pair's F3 components, in column order
  double peak_pressure = 0;                    // largest lambda_n at the last step
  std::map<std::string, std::string> states;   // "pair/node" -> state at the last step
};

FinalState read_final_state(const scene::Scene& scene, const std::string& dir) {
  const Checkpoint c = read_checkpoint(dir + "/checkpoint.bin");
  if (c.scene != scene.name || c.level != scene.level)
    throw Error(fmt::format("'{}' holds a run of scene '{}' level {}, not '{}' level {}", dir, c.scene, c.level,
                            scene.name, scene.level));
  if (c.state.step != scene.problem.n_steps())
    throw Error(fmt::format("the run in '{}' stopped after load step {} of {}", dir, c.state.step,
                            scene.problem.n_steps()));
  FinalState f;
  f.u = c.state.u;
  if (f.u.size() < static_cast<size_t>(scene.space->n_dofs()))
    throw Error(fmt::format("'{}' holds {} displacement unknowns, the scene {}", dir, f.u.size(), scene.space->n_dofs()));
  if (scene.contacts.empty()) return f;

  const CsvTable steps = read_csv(dir + "/steps.csv");
  const std::map<std::string, std::string>* last = nullptr;
  for (const auto& row : steps.rows)
    if (number(row, "converged") == 1) last = &row;
  if (!last) throw Error(fmt::format("'{}/steps.csv' has no converged load step", dir));
  for (const auto& column : steps.columns)
    if (column.rfind("contact_", 0) == 0 && column.find("_force_") != std::string::npos)
      f.contact_force.push_back(number(*last, column));

  const CsvTable contact = read_csv(dir + "/contact.csv");
  const std::string final_step = contact.rows.empty() ? "" : contact.rows.back().at("step");
  for (const auto& row : contact.rows) {
    if (row.at("step") != final_step) continue;
    f.peak_pressure = std::max(f.peak_pressure, number(row, "lambda_n"));
    f.states[row.at("pair") + "/" + row.at("node")] = row.at("state");
    double p2 = 0;
    for (const char* k : {"lambda_x", "lambda_y", "lambda_z"})
      if (row.count(k)) p2 += std::pow(number(row, k), 2);
    f.slave_nodes.push_back(
        {static_cast<int>(number(row, "vertex")), row.at("state"), number(row, "lambda_n"), std::sqrt(p2)});
  }
  return f;
}

double relative(double error, double reference) { return reference > 0 ? error / reference : error; }

// The norms of a discrete displacement: its error against zero.
fem::ErrorNorms norms_of(const scene::Scene& scene, const std::vector<double>& u) {
  const auto zero = [](const double*, double* out) { std::fill(out, out + 3, 0.0); };
  const auto zero_gradient = [](const double*, double* out) { std::fill(out, out + 9, 0.0); };
  return fem::compute_errors(*scene.space, u, zero, zero_gradient);
}

double force_difference(const std::vector<double>& f, const std::vector<double>& ref) {
  double error = 0, size = 0;
  for (size_t k = 0; k < ref.size() && k < f.size(); ++k) {
    error += std::pow(f[k] - ref[k], 2);
    size += std::pow(ref[k], 2);
  }
  return relative(std::sqrt(error), std::sqrt(size));
}

}  // namespace

SolutionAccuracy compare_to_reference(const scene::Scene& scene, const std::string& run_dir,
                                      const std::string& reference_dir) {
  const FinalState run = read_final_state(scene, run_dir), ref = read_final_state(scene, reference_dir);
  SolutionAccuracy a;
  std::vector<double> difference(ref.u.size());
  for (size_t i = 0; i < difference.size(); ++i) difference[i] = run.u[i] - ref.u[i];
  const fem::ErrorNorms error = norms_of(scene, difference), size = norms_of(scene, ref.u);
  a.displacement_l2 = relative(error.l2, size.l2);
  a.displacement_h1 = relative(error.h1_seminorm, size.h1_seminorm);
  a.contact = !scene.contacts.empty();
  if (!a.contact) return a;
  a.contact_force = force_difference(run.contact_force, ref.contact_force);
  a.peak_pressure = relative(std::abs(run.peak_pressure - ref.peak_pressure), ref.peak_pressure);
  for (const auto& [node, state] : ref.states) {
    const auto it = run.states.find(node);
    a.state_changes += it == run.states.end() || it->second != state;
  }
  return a;
}

LevelDifference compare_levels(const scene::Scene& coarse, const std::string& coarse_dir, const scene::Scene& fine,
                               const std::string& fine_dir) {
  const FinalState c = read_final_state(coarse, coarse_dir), f = read_final_state(fine, fine_dir);
  const fem::ErrorNorms nc = norms_of(coarse, c.u), nf = norms_of(fine, f.u);
  LevelDifference d;
  d.displacement_l2 = relative(std::abs(nc.l2 - nf.l2), nf.l2);
  d.displacement_h1 = relative(std::abs(nc.h1_seminorm - nf.h1_seminorm), nf.h1_seminorm);
  d.contact = !coarse.contacts.empty();
  if (d.contact) {
    d.contact_force = force_difference(c.contact_force, f.contact_force);
    d.peak_pressure = relative(std::abs(c.peak_pressure - f.peak_pressure), f.peak_pressure);
  }
  return d;
}

std::optional<AnalyticAccuracy> analytic_accuracy(const scene::Scene& scene, const std::string& run_dir) {
  const auto hertz = hertz_case(scene.name);
  const auto mindlin = mindlin_case(scene.name);
  const auto patch = patch_case(scene.name);
  if (!hertz && !mindlin && !patch) return std::nullopt;
  const FinalState f = read_final_state(scene, run_dir);
  AnalyticAccuracy a;
  if (hertz) {
    std::vector<std::pair<double, double>> profile;
    for (const auto& node : f.slave_nodes) {
      if (node.state == "inactive") continue;
      const double* X = scene.mesh.vertex(node.vertex);
      profile.emplace_back(hertz->dim == 2 ? X[0] : std::hypot(X[0], X[2]), node.lambda_norm);
    }
    if (profile.size() >= 2 && f.contact_force.size() >= 2) {
      const HertzComparison h = compare_with_hertz(*hertz, f.contact_force[1], profile);
      a.hertz_a = h.a_error();
      a.hertz_p0 = h.p0_error();
    }
  }
  if (mindlin && f.contact_force.size() >= 2) {
    std::vector<double> stick, slip;  // |x| of the reference positions, the contact point at x = 0
    for (const auto& node : f.slave_nodes) {
      const double x = std::abs(scene.mesh.vertex(node.vertex)[0]);
      if (node.state == "stick") stick.push_back(x);
      if (node.state == "slip") slip.push_back(x);
    }
    if (!stick.empty() && !slip.empty())
      a.stick_zone = compare_with_mindlin(*mindlin, f.contact_force[1], f.contact_force[0], stick, slip)
                         .stick_zone_error();
  }
  if (patch) {
    std::vector<double> normal;
    for (const auto& node : f.slave_nodes) normal.push_back(node.lambda_n);
    if (!normal.empty()) a.patch_pressure = patch_pressure_error(*patch, normal);
  }
  return a;
}

}  // namespace stiction::harness
