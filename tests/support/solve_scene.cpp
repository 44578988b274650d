#include "support/solve_scene.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "builtin_scenes.hpp"
#include "registry.hpp"

namespace stiction::test {

namespace {
SolvedScene solve(std::unique_ptr<scene::Scene> s, const std::string& backend) {
  SolvedScene out;
  out.scene = std::move(s);
  auto solver = solvers::create_solver(backend, PETSC_COMM_WORLD);
  nonlinear::QuasiStaticSolver newton(PETSC_COMM_WORLD, out.scene->problem, out.scene->newton, *solver);
  out.steps = newton.run();
  out.u = newton.displacement();
  out.lambda = newton.multipliers();
  return out;
}
}  // namespace

SolvedScene solve_scene_text(const std::string& toml, int level, const std::string& backend) {
  return solve(scene::build_scene(toml, "test-scene", ".", level), backend);
}

SolvedScene solve_builtin(const std::string& name, int level, const std::string& backend,
                          const std::vector<std::string>& overrides) {
  return solve(harness::open_scene(name, level, overrides), backend);
}

std::vector<double> SolvedScene::displacement_near(const std::vector<double>& X) const {
  const auto& space = *scene->space;
  const auto nodal = space.nodal_values(u);
  int best = 0;
  double best_d = INFINITY, Y[3];
  for (int n = 0; n < space.n_nodes(); ++n) {
    space.node_position(n, Y);
    double d = 0;
    for (int k = 0; k < space.dim(); ++k) d += (X[k] - Y[k]) * (X[k] - Y[k]);
    if (d < best_d) best_d = d, best = n;
  }
  return {nodal.begin() + best * space.dim(), nodal.begin() + (best + 1) * space.dim()};
}

double SolvedScene::mean_krylov_per_newton_step() const {
  double krylov = 0, newton = 0;
  for (const auto& s : steps)
    for (const auto& it : s.iterations) krylov += it.linear.iterations, newton += 1;
  return newton > 0 ? krylov / newton : 0;
}

const char* minimal_bar_scene() {
  return R"(
[[material]]
name = "steel"
model = "linear"
E = 200.0
nu = 0.3

[[body]]
name = "bar"
material = "steel"
mesh = { generator = "structured-box", size = [4.0, 1.0], cells = [4, 1] }

[[dirichlet]]
boundary = "xmin"
components = ["x", "y"]
value = [0.0, 0.0]
)";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << "'" << from << "' not in the scene text";
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

}  // namespace stiction::test
