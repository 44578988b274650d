// Run under `mpirun -n 2` with the other distributed tests. A scene solved on mesh parts
// (scene::divide_scene: each process holds its cells, the layer around them and its own
// space, not the whole mesh; with contact, the contact surfaces whole besides and the pairs
// over its space) takes the whole-mesh distributed run's Newton path: the same
// Newton iterations per load step, the same Krylov iterations, and the same converged
// state and forces, to 1e-8 relative; and one whose coarse mesh alone was whole, refined in
// parts (with contact, its surfaces whole on every part), solves the finer level as the
// whole mesh does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "builtin_scenes.hpp"
#include "nonlinear/newton.hpp"
#include "registry.hpp"
#include "scene/scene_part.hpp"
#include "support/test_names.hpp"

namespace {

using namespace stiction;

struct Case {
  const char* scene;
  const char* backend;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.scene << " with " << c.backend; }

struct NewtonPath {
  std::vector<int> newton, krylov;          // per increment, per Newton iteration
  std::vector<std::array<double, 3>> forces;  // every surface force and reaction of the last increment
  std::vector<double> displacement;         // whole, app order
};

NewtonPath record(nonlinear::QuasiStaticSolver& newton, int last_step) {
  NewtonPath out;
  const auto steps = newton.run({}, 1, last_step);
  for (const auto& s : steps) {
    out.newton.push_back(static_cast<int>(s.iterations.size()));
    for (const auto& it : s.iterations) out.krylov.push_back(it.linear.iterations);
  }
  if (!steps.empty()) {
    for (const auto& [name, f] : steps.back().surface_forces) out.forces.push_back(f);
    for (const auto& [name, f] : steps.back().reactions) out.forces.push_back(f);
  }
  out.displacement = newton.displacement();
  return out;
}

double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double scale = 0, diff = 0;
  for (size_t i = 0; i < a.size(); ++i) scale = std::max(scale, std::abs(a[i])), diff = std::max(diff, std::abs(a[i] - b[i]));
  return diff / scale;
}

// The same converged forces and state, to 1e-8 relative.
void expect_same_state(const NewtonPath& run, const NewtonPath& whole) {
  ASSERT_EQ(run.forces.size(), whole.forces.size());
  EXPECT_FALSE(whole.forces.empty());
  for (size_t k = 0; k < whole.forces.size(); ++k) {
    const std::vector<double> a(whole.forces[k].begin(), whole.forces[k].end()), b(run.forces[k].begin(), run.forces[k].end());
    EXPECT_LT(relative_difference(a, b), 1e-8) << "force " << k;
  }
  ASSERT_EQ(run.displacement.size(), whole.displacement.size());
  EXPECT_LT(relative_difference(whole.displacement, run.displacement), 1e-8);
}

class SolveInParts : public ::testing::TestWithParam<Case> {};

TEST_P(SolveInParts, FollowsTheWholeMeshNewtonPath) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  auto scene = harness::open_scene(GetParam().scene, 0, {});
  const int last = scene->problem.step_reaching(scene->quick_until);

  auto whole_solver = solvers::create_solver(GetParam().backend, comm);
  nonlinear::QuasiStaticSolver whole_newton(comm, scene->problem, scene->newton, *whole_solver);
  const NewtonPath whole = record(whole_newton, last);

  const auto parts = scene::divide_scene(comm, *scene);
  auto solver = solvers::create_solver(GetParam().backend, comm);
  nonlinear::QuasiStaticSolver newton(comm, parts->problem, parts->part, parts->ownership, scene->newton, *solver);
  EXPECT_LT(parts->part.mesh.n_cells(), scene->mesh.n_cells());  // a part, not the whole mesh
  const NewtonPath run = record(newton, last);

  EXPECT_EQ(run.newton, whole.newton);
  EXPECT_EQ(run.krylov, whole.krylov);
  expect_same_state(run, whole);
}

INSTANTIATE_TEST_SUITE_P(Scenes, SolveInParts,
                         ::testing::Values(Case{"cook-membrane-2d", "lu-mumps"}, Case{"block-compression", "schur-amg"},
                                           Case{"mooney-rivlin-block", "schur-amg"},
                                           Case{"hertz-cylinder-2d", "lu-mumps"}, Case{"sliding-block-2d", "lu-mumps"},
                                           Case{"self-contact-2d", "lu-mumps"}, Case{"hertz-spheres-3d", "schur-amg"}),
                         [](const auto& info) {
                           return test::identifier(std::string(info.param.scene) + "_" + info.param.backend);
                         });

// Only the coarse mesh whole: a scene's level 0 divided, then refined in parts, is solved as
// the whole level-1 run solves it (the same mesh and numbering, another split of the cells,
// so a direct solver's path: the same Newton iterations and state to 1e-8).
class SolveRefinedInParts : public ::testing::TestWithParam<const char*> {};

TEST_P(SolveRefinedInParts, FollowsTheWholeFinerLevel) {
  const MPI_Comm comm = PETSC_COMM_WORLD;
  auto coarse = harness::open_scene(GetParam(), 0, {});
  auto fine = harness::open_scene(GetParam(), 1, {});
  const int last = fine->problem.step_reaching(fine->quick_until);
  auto whole_solver = solvers::create_solver("lu-mumps", comm);
  nonlinear::QuasiStaticSolver whole_newton(comm, fine->problem, fine->newton, *whole_solver);
  const NewtonPath whole = record(whole_newton, last);

  const auto parts = scene::divide_scene(comm, *coarse, 1);
  EXPECT_EQ(parts->part.n_global_cells, fine->mesh.n_cells());
  auto solver = solvers::create_solver("lu-mumps", comm);
  nonlinear::QuasiStaticSolver newton(comm, parts->problem, parts->part, parts->ownership, fine->newton, *solver);
  const NewtonPath run = record(newton, last);

  EXPECT_EQ(run.newton, whole.newton);
  expect_same_state(run, whole);
}

// With contact the parts hold the refined contact surfaces whole (sliding-block-2d: friction
// on a deformable master; self-contact-2d).
INSTANTIATE_TEST_SUITE_P(Scenes, SolveRefinedInParts,
                         ::testing::Values("cook-membrane-2d", "cook-membrane-3d", "sliding-block-2d", "self-contact-2d"),
                         [](const auto& info) { return test::identifier(info.param); });

}  // namespace
