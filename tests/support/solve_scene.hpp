#pragma once
// Solves a scene given as TOML text (or a built-in name) with a backend, through the real
// builder and Newton driver, for verification tests.
#include <memory>
#include <string>
#include <vector>

#include "nonlinear/newton.hpp"
#include "scene/scene.hpp"

namespace stiction::test {

struct SolvedScene {
  std::unique_ptr<scene::Scene> scene;
  std::vector<double> u;
  std::vector<double> lambda;  // contact multipliers (empty without contact)
  std::vector<nonlinear::StepResult> steps;
  bool converged() const { return !steps.empty() && steps.back().converged(); }
  // Nodal displacement of the node nearest X (vertex or edge midpoint).
  std::vector<double> displacement_near(const std::vector<double>& X) const;
  double mean_krylov_per_newton_step() const;
};

SolvedScene solve_scene_text(const std::string& toml, int level, const std::string& backend);
// overrides: KEY=VALUE scene settings, as `stiction solve --set` takes them.
SolvedScene solve_builtin(const std::string& name, int level, const std::string& backend,
                          const std::vector<std::string>& overrides = {});

// The smallest scene that builds: a linear-elastic 4 x 1 bar of four cells, clamped at x = 0,
// with the default load (one step).
const char* minimal_bar_scene();

// Replaces the first occurrence of `from` by `to` (fails the test when absent).
std::string replaced(std::string text, const std::string& from, const std::string& to);

}  // namespace stiction::test
