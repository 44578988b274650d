// Run under `mpirun -n 2` (ctest label `mpi`). Every process solves a scene twice: alone
// (PETSC_COMM_SELF, the one-process system, whose Jacobian the finite-difference tests
// verify) and with the other process (PETSC_COMM_WORLD, the system distributed by
// fem::DofLayout). At every Newton iteration the distributed matrix times a fixed vector,
// and the right side, brought back to stiction's own numbering, must equal the
// one-process ones: the exact Jacobian survives the distribution (cells assembled by
// their own rank, rows sent to their owner, contact rows on the slave node's rank,
// Dirichlet rows zeroed by their owner).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "builtin_scenes.hpp"
#include "common/petsc.hpp"
#include "nonlinear/newton.hpp"
#include "registry.hpp"

namespace {

using namespace stiction;

struct SystemProducts {
  std::vector<std::vector<double>> matrix_times_x, rhs;  // per Newton iteration, app order
  std::vector<int> newton_per_step;
};

// x in app order: a fixed pseudo-random vector, the same on every process.
std::vector<double> probe(size_t n) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> d(-1, 1);
  std::vector<double> x(n);
  for (double& v : x) v = d(gen);
  return x;
}

SystemProducts solve_recording(MPI_Comm comm, const std::string& name, const std::string& backend) {
  auto scene = harness::open_scene(name, 0, {});
  auto solver = solvers::create_solver(backend, comm);
  nonlinear::QuasiStaticSolver newton(comm, scene->problem, scene->newton, *solver);
  const fem::DofLayout& layout = newton.layout();
  const std::vector<double> x = probe(layout.n_total());
  SystemProducts out;
  newton.set_system_observer([&](const nonlinear::NewtonSystem& sys, Vec, const nonlinear::LinearSolveStats&, int, int) {
    PetscVec xv, yv;
    *xv.out() = layout.create_vector();
    *yv.out() = layout.create_vector();
    layout.scatter(x, xv);
    STICTION_PETSC(MatMult(sys.matrix, xv, yv));
    std::vector<double> y, b;
    layout.gather(yv, y);
    layout.gather(sys.rhs, b);
    out.matrix_times_x.push_back(y);
    out.rhs.push_back(b);
  });
  const auto steps = newton.run({}, 1, scene->problem.step_reaching(scene->quick_until));
  for (const auto& s : steps) out.newton_per_step.push_back(static_cast<int>(s.iterations.size()));
  return out;
}

double max_abs(const std::vector<double>& a) {
  double m = 0;
  for (double v : a) m = std::max(m, std::abs(v));
  return m;
}

double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double diff = 0;
  for (size_t i = 0; i < a.size(); ++i) diff = std::max(diff, std::abs(a[i] - b[i]));
  return diff;
}

struct Case {
  const char* scene;
  const char* backend;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.scene << " with " << c.backend; }

class DistributedSystem : public ::testing::TestWithParam<Case> {};

TEST_P(DistributedSystem, EqualsTheOneProcessSystemAtEveryNewtonIteration) {
  int processes = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &processes);
  ASSERT_EQ(processes, 2) << "run under mpirun -n 2";
  const SystemProducts alone = solve_recording(PETSC_COMM_SELF, GetParam().scene, GetParam().backend);
  const SystemProducts together = solve_recording(PETSC_COMM_WORLD, GetParam().scene, GetParam().backend);
  EXPECT_EQ(alone.newton_per_step, together.newton_per_step);
  ASSERT_EQ(alone.matrix_times_x.size(), together.matrix_times_x.size());
  ASSERT_FALSE(alone.matrix_times_x.empty());
  // Both runs follow one Newton path up to round-off (the sums run in another order), so
  // the states differ by about 1e-12 relative; a missing or misplaced entry is O(1). The
  // right sides shrink to round-off as Newton converges: they are compared on the scale
  // of the largest (a load step's first).
  constexpr double kTolerance = 1e-8;
  double rhs_scale = 0;
  for (const auto& b : alone.rhs) rhs_scale = std::max(rhs_scale, max_abs(b));
  for (size_t k = 0; k < alone.matrix_times_x.size(); ++k) {
    EXPECT_LT(max_difference(alone.matrix_times_x[k], together.matrix_times_x[k]),
              kTolerance * max_abs(alone.matrix_times_x[k]))
        << "system " << k;
    EXPECT_LT(max_difference(alone.rhs[k], together.rhs[k]), kTolerance * rhs_scale) << "system " << k;
  }
}

// Displacement only, mixed u-p, frictionless and frictional contact, 2D and 3D, self-contact.
INSTANTIATE_TEST_SUITE_P(Scenes, DistributedSystem,
                         ::testing::Values(Case{"cantilever-2d", "lu-mumps"}, Case{"cook-membrane-2d", "lu-mumps"},
                                           Case{"hertz-cylinder-2d", "lu-mumps"}, Case{"sliding-block-2d", "lu-mumps"},
                                           Case{"self-contact-2d", "lu-mumps"}, Case{"hertz-sphere-3d", "lu-mumps"},
                                           Case{"cook-membrane-3d", "lu-mumps"}),
                         [](const auto& info) {
                           std::string n = info.param.scene;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

}  // namespace
