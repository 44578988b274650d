// Run under `mpirun -n 2` (ctest label `mpi`). Every process solves a scene twice: alone
// (PETSC_COMM_SELF, the one-process system, whose Jacobian the finite-difference tests
// verify) and with the other process (PETSC_COMM_WORLD, the system distributed by
// fem::DofLayout). At every Newton iteration the distributed matrix times a fixed vector,
// and the right side, brought back to stiction's own numbering, must equal the
// one-process ones: the exact Jacobian survives the distribution (each rank's rows
// assembled from the cells that reach them, contact rows on the slave node's rank,
// Dirichlet rows zeroed by their owner). The preconditioner parts the Schur backends read
// (the pressure mass, the multiplier block's Schur parts) are compared the same way, in
// their field's block numbering.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "builtin_scenes.hpp"
#include "common/error.hpp"
#include "common/petsc.hpp"
#include "fem/ghosted_vector.hpp"
#include "fem/mesh_partition.hpp"
#include "nonlinear/constraint_set.hpp"
#include "nonlinear/newton.hpp"
#include "multiplier_schur_parts.hpp"
#include "registry.hpp"
#include "scene/scene_part.hpp"
#include "support/test_names.hpp"

namespace {

using namespace stiction;

struct SystemProducts {
  std::vector<std::vector<double>> matrix_times_x, rhs;  // per Newton iteration, app order
  // Per Newton iteration: each preconditioner part times x's entries on its block.
  std::vector<std::vector<std::vector<double>>> parts_times_x;
  std::vector<int> newton_per_step;
  int tangents_beside_system = 0;  // systems solved while a tangent matrix was also alive
  int cells_held = 0;              // cells of the mesh this process's space is over
};

// x in app order: a fixed pseudo-random vector, the same on every process.
std::vector<double> probe(size_t n) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> d(-1, 1);
  std::vector<double> x(n);
  for (double& v : x) v = d(gen);
  return x;
}

// M, a matrix on the block of unknowns [first, last) of the layout's local index in its
// field's numbering (DofLayout::block_numbering), times x's entries there (x in app order);
// the product in the block's app order, NaN where this process holds no unknown (over a mesh
// part). The block's app indices are the last M-size ones before `app_end`.
std::vector<double> block_times(const fem::DofLayout& layout, Mat M, PetscInt first, PetscInt last, PetscInt app_end,
                                const std::vector<double>& x) {
  PetscInt m;
  STICTION_PETSC(MatGetSize(M, &m, nullptr));
  const PetscInt app_first = app_end - m;
  const std::vector<PetscInt> number = layout.block_numbering(first, last);
  PetscVec xv, yv, all;
  STICTION_PETSC(MatCreateVecs(M, xv.out(), yv.out()));
  for (PetscInt k = 0; k < last - first; ++k)
    if (layout.owns(first + k)) STICTION_PETSC(VecSetValue(xv, number[k], x[layout.app(first + k)], INSERT_VALUES));
  STICTION_PETSC(VecAssemblyBegin(xv));
  STICTION_PETSC(VecAssemblyEnd(xv));
  STICTION_PETSC(MatMult(M, xv, yv));
  VecScatter to_all;
  STICTION_PETSC(VecScatterCreateToAll(yv, &to_all, all.out()));
  STICTION_PETSC(VecScatterBegin(to_all, yv, all, INSERT_VALUES, SCATTER_FORWARD));
  STICTION_PETSC(VecScatterEnd(to_all, yv, all, INSERT_VALUES, SCATTER_FORWARD));
  STICTION_PETSC(VecScatterDestroy(&to_all));
  const PetscScalar* a;
  std::vector<double> y(static_cast<size_t>(m), std::nan(""));
  STICTION_PETSC(VecGetArrayRead(all, &a));
  for (PetscInt k = 0; k < last - first; ++k) y[layout.app(first + k) - app_first] = a[number[k]];
  STICTION_PETSC(VecRestoreArrayRead(all, &a));
  return y;
}

// on_parts: each process holds its part of the mesh (scene::divide_scene), not the whole.
SystemProducts solve_recording(MPI_Comm comm, const std::string& name, const std::string& backend,
                               bool on_parts = false) {
  auto scene = harness::open_scene(name, 0, {});
  auto solver = solvers::create_solver(backend, comm);
  const auto parts = on_parts ? scene::divide_scene(comm, *scene) : nullptr;
  const nonlinear::ElasticityProblem& problem = parts ? parts->problem : scene->problem;
  nonlinear::QuasiStaticSolver newton = parts ? nonlinear::QuasiStaticSolver(comm, problem, parts->part, parts->ownership,
                                                                              scene->newton, *solver)
                                              : nonlinear::QuasiStaticSolver(comm, problem, scene->newton, *solver);
  const fem::DofLayout& layout = newton.layout();
  const std::vector<double> x = probe(layout.n_total());
  SystemProducts out;
  out.cells_held = problem.space->mesh().n_cells();
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
    std::vector<std::vector<double>> parts;
    const fem::FieldSpace& space = *problem.space;
    const PetscInt n_multipliers = layout.n_held() - space.n_dofs();
    if (sys.pressure_mass)
      parts.push_back(block_times(layout, sys.pressure_mass, space.pressure_block().first, space.pressure_block().second,
                                  layout.n_total() - n_multipliers, x));
    if (sys.multiplier_surface.mass) {  // the Schur parts as the contact preconditioner forms them
      const solvers::MultiplierSchurParts schur = solvers::form_multiplier_schur_parts(sys.multiplier_surface);
      for (Mat part : {schur.mass.get(), schur.laplacian.get(), schur.slip_coupling.get()})
        parts.push_back(block_times(layout, part, space.n_dofs(), layout.n_held(), layout.n_total(), x));
    }
    out.parts_times_x.push_back(parts);
    if (newton.tangent_beside_system()) ++out.tangents_beside_system;
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

// Over the entries b has (not NaN: a block product over a mesh part holds only the part's).
double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double diff = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (!std::isnan(b[i])) diff = std::max(diff, std::abs(a[i] - b[i]));
  return diff;
}

struct Case {
  const char* scene;
  const char* backend;
  // 1: the pressure mass; 3: the multiplier block's Schur parts (no scene here has both)
  size_t preconditioner_parts;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.scene << " with " << c.backend; }

class DistributedSystem : public ::testing::TestWithParam<Case> {};

// The distributed run's systems against the one-process run's, at every Newton iteration.
void expect_same_systems(const SystemProducts& alone, const SystemProducts& together, size_t preconditioner_parts) {
  EXPECT_EQ(alone.newton_per_step, together.newton_per_step);
  // With contact the augmented matrix holds the tangent's rows, and the tangent is dropped
  // before the solve (one process: merged in place; several: copied, then released).
  EXPECT_EQ(alone.tangents_beside_system, 0);
  EXPECT_EQ(together.tangents_beside_system, 0);
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
    ASSERT_EQ(alone.parts_times_x[k].size(), preconditioner_parts) << "system " << k;
    ASSERT_EQ(together.parts_times_x[k].size(), preconditioner_parts) << "system " << k;
    // The multiplier block's parts are summed into one Schur approximation (same units);
    // the slip coupling vanishes up to round-off where nothing slips: each part is compared
    // on the scale of the largest.
    double parts_scale = 0;
    for (const auto& part : alone.parts_times_x[k]) parts_scale = std::max(parts_scale, max_abs(part));
    for (size_t p = 0; p < preconditioner_parts; ++p) {
      const auto& held = together.parts_times_x[k][p];
      EXPECT_GT(std::count_if(held.begin(), held.end(), [](double v) { return !std::isnan(v); }), 0);
      EXPECT_LE(max_difference(alone.parts_times_x[k][p], held), kTolerance * parts_scale)
          << "system " << k << ", preconditioner part " << p;
    }
  }
}

TEST_P(DistributedSystem, EqualsTheOneProcessSystemAtEveryNewtonIteration) {
  int processes = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &processes);
  ASSERT_EQ(processes, 2) << "run under mpirun -n 2";
  const SystemProducts alone = solve_recording(PETSC_COMM_SELF, GetParam().scene, GetParam().backend);
  const SystemProducts together = solve_recording(PETSC_COMM_WORLD, GetParam().scene, GetParam().backend);
  expect_same_systems(alone, together, GetParam().preconditioner_parts);
}

// The same on mesh parts (with contact, each part holding the contact surfaces whole): the
// exact Jacobian of the one-process system, whose entries each part assembles from its own
// cells and its pairs rebuilt over its space.
TEST_P(DistributedSystem, OnMeshPartsEqualsTheOneProcessSystemAtEveryNewtonIteration) {
  int processes = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &processes);
  ASSERT_EQ(processes, 2) << "run under mpirun -n 2";
  const SystemProducts alone = solve_recording(PETSC_COMM_SELF, GetParam().scene, GetParam().backend);
  const SystemProducts on_parts = solve_recording(PETSC_COMM_WORLD, GetParam().scene, GetParam().backend, true);
  EXPECT_LT(on_parts.cells_held, alone.cells_held) << "not a part of the mesh";
  expect_same_systems(alone, on_parts, GetParam().preconditioner_parts);
}

// Displacement only, mixed u-p, frictionless and frictional contact, 2D and 3D, self-contact.
INSTANTIATE_TEST_SUITE_P(Scenes, DistributedSystem,
                         ::testing::Values(Case{"cantilever-2d", "lu-mumps", 0}, Case{"cook-membrane-2d", "lu-mumps", 1},
                                           Case{"hertz-cylinder-2d", "lu-mumps", 3},
                                           Case{"sliding-block-2d", "lu-mumps", 3},
                                           Case{"self-contact-2d", "lu-mumps", 3},
                                           Case{"hertz-sphere-3d", "lu-mumps", 3},
                                           Case{"cook-membrane-3d", "lu-mumps", 1}),
                         [](const auto& info) { return test::identifier(info.param.scene); });

// Distributed, each process evaluates the contact of its own slave nodes: the Jacobian
// entries the processes compute together are the one-process entries, each computed once
// (summed over the processes, |entries| equals the one-process sum; were every process to
// evaluate everything, it would be twice that), every process gets the whole constraint
// rows, and the processes' shares of the forces sum to the whole. At the converged state of the scene's short run, where nodes press and slip.
class DistributedContact : public ::testing::TestWithParam<const char*> {};

double abs_sum(const nonlinear::SparseEntries& e) {
  double s = 0;
  for (double v : e.values) s += std::abs(v);
  return s;
}

TEST_P(DistributedContact, EachProcessComputesItsShareOnce) {
  int processes = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &processes);
  ASSERT_EQ(processes, 2) << "run under mpirun -n 2";
  auto scene = harness::open_scene(GetParam(), 0, {});
  auto solver = solvers::create_solver("lu-mumps", PETSC_COMM_WORLD);
  nonlinear::QuasiStaticSolver newton(PETSC_COMM_WORLD, scene->problem, scene->newton, *solver);
  const auto steps = newton.run({}, 1, scene->problem.step_reaching(scene->quick_until));
  ASSERT_FALSE(steps.empty());
  ASSERT_TRUE(steps.back().converged());
  nonlinear::ConstraintSet constraints(scene->problem.constraints);
  ASSERT_FALSE(constraints.all_free()) << "no node in contact at the end of the short run";
  const PetscInt n_u = scene->problem.space->n_dofs();
  const double t = steps.back().time;
  const std::vector<double> u = newton.displacement();
  const std::vector<double>& lambda = newton.multipliers();

  auto evaluate = [&](nonlinear::SparseEntries& jacobian, std::vector<double>& r_u, std::vector<double>& r_c) {
    r_u.assign(static_cast<size_t>(n_u), 0.0);
    constraints.evaluate(t, u, lambda, r_u, r_c, &jacobian, n_u);
  };
  nonlinear::SparseEntries share, whole;
  std::vector<double> r_u_shared, r_c_shared, r_u_alone, r_c_alone;
  evaluate(share, r_u_shared, r_c_shared);
  for (auto* c : scene->problem.constraints) c->distribute(PETSC_COMM_SELF, {});
  evaluate(whole, r_u_alone, r_c_alone);

  double shared_sum = abs_sum(share);
  MPI_Allreduce(MPI_IN_PLACE, &shared_sum, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  EXPECT_NEAR(shared_sum, abs_sum(whole), 1e-10 * abs_sum(whole));
  long long shared_entries = static_cast<long long>(share.size());
  MPI_Allreduce(MPI_IN_PLACE, &shared_entries, 1, MPI_LONG_LONG, MPI_SUM, PETSC_COMM_WORLD);
  EXPECT_LE(shared_entries, static_cast<long long>(whole.size()));
  // Each process adds its share of the forces; the shares sum to the whole.
  MPI_Allreduce(MPI_IN_PLACE, r_u_shared.data(), static_cast<int>(n_u), MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  EXPECT_LT(max_difference(r_u_shared, r_u_alone), 1e-12 * max_abs(r_u_alone));
  EXPECT_LT(max_difference(r_c_shared, r_c_alone), 1e-12 * std::max(max_abs(r_c_alone), 1e-300));
}

// A contact scene after its first load step, solved on both processes.
class DistributedState : public DistributedContact {
protected:
  void SetUp() override {
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank_);
    scene_ = harness::open_scene(GetParam(), 0, {});
    solver_ = solvers::create_solver("lu-mumps", PETSC_COMM_WORLD);
    newton_ = std::make_unique<nonlinear::QuasiStaticSolver>(PETSC_COMM_WORLD, scene_->problem, scene_->newton,
                                                             *solver_);
    const auto steps = newton_->run({}, 1, 1);
    ASSERT_FALSE(steps.empty());
    ASSERT_TRUE(steps.back().converged());
  }
  int rank_ = 0;
  std::unique_ptr<scene::Scene> scene_;
  std::unique_ptr<nonlinear::LinearSolver> solver_;
  std::unique_ptr<nonlinear::QuasiStaticSolver> newton_;
};

// What each process writes its output from without a gather: the state it holds covers the
// nodes of its own cells (its VTU piece) and the contact surfaces (contact.csv, written by
// rank 0), with the gathered state's values; the checkpoint's state is whole on rank 0 only.
// (An own cell whose nodes all lie in cells without a node of this process would be covered
// by neither its row cells nor the surfaces; the built-in partitions have none.)
TEST_P(DistributedState, HeldStateCoversOwnCellsAndContactSurfaces) {
  const int rank = rank_;
  const auto& scene = scene_;
  const nonlinear::QuasiStaticSolver& newton = *newton_;
  const fem::FieldSpace& space = *scene->problem.space;
  const std::vector<double> whole = newton.displacement();
  const fem::StateView held = newton.held_displacement();
  std::vector<int> tags;
  for (const auto* c : scene->problem.constraints)
    for (const auto& [role, tag] : c->surfaces()) tags.push_back(tag);
  std::vector<PetscInt> needed = fem::unknowns_of_cells(space, newton.partition().owned_cells);
  const std::vector<PetscInt> surfaces = fem::unknowns_of_facets(space, tags);
  ASSERT_FALSE(surfaces.empty());
  needed.insert(needed.end(), surfaces.begin(), surfaces.end());
  for (PetscInt a : needed) {  // no ASSERT: state() below is collective
    if (!held.holds(static_cast<size_t>(a))) {
      ADD_FAILURE() << "unknown " << a << " is not held on process " << rank;
      break;
    }
    EXPECT_EQ(held[static_cast<size_t>(a)], whole[static_cast<size_t>(a)]) << "unknown " << a;
  }
  EXPECT_LT(held.storage().size(), whole.size()) << "process " << rank << " holds the whole state";

  const auto state = newton.state();
  if (rank == 0) EXPECT_EQ(state.u, whole);
  else EXPECT_TRUE(state.u.empty()) << "process " << rank << " holds a whole copy for the checkpoint";
}

// A checkpoint's state holds u on process 0 alone; restored, each process takes its part
// (owned unknowns and ghosts) and every process the multipliers and contact states: a fresh
// solver then holds the state of the one that saved it. A u of the wrong size, known to
// process 0 alone, is refused on every process.
TEST_P(DistributedState, StateRestoresFromProcessZeroAlone) {
  const int rank = rank_;
  const auto& scene = scene_;
  const nonlinear::QuasiStaticSolver& newton = *newton_;
  const auto saved = newton.state();
  EXPECT_EQ(saved.u.empty(), rank != 0);  // EXPECT: a check of one process must not skip the collectives below

  auto other_solver = solvers::create_solver("lu-mumps", PETSC_COMM_WORLD);
  nonlinear::QuasiStaticSolver restored(PETSC_COMM_WORLD, scene->problem, scene->newton, *other_solver);
  restored.restore(saved);
  const std::vector<double> u = newton.displacement();
  EXPECT_GT(max_abs(u), 0);
  EXPECT_EQ(restored.displacement(), u);
  // Every displacement (and pressure) unknown held, ghosts included.
  const fem::StateView a = newton.held_displacement(), b = restored.held_displacement();
  EXPECT_EQ(a.storage().size(), b.storage().size());
  int held = 0;
  for (size_t k = 0; k < u.size(); ++k) {
    if (a.holds(k) != b.holds(k)) {
      ADD_FAILURE() << "unknown " << k << " is held by one solver only";
      break;
    }
    if (!a.holds(k)) continue;
    EXPECT_EQ(b[k], a[k]) << "unknown " << k << " on process " << rank;
    ++held;
  }
  EXPECT_LT(held, static_cast<int>(u.size()));
  EXPECT_EQ(restored.multipliers(), newton.multipliers());

  auto damaged = saved;
  if (rank == 0) damaged.u.pop_back();
  EXPECT_THROW(restored.restore(damaged), Error);
}

// Deformable master in 2D and 3D (self-contact), rigid plane with friction.
const char* const kContactScenes[] = {"self-contact-2d", "hertz-spheres-3d", "sliding-block-2d"};
std::string scene_test_name(const ::testing::TestParamInfo<const char*>& info) { return test::identifier(info.param); }
INSTANTIATE_TEST_SUITE_P(Scenes, DistributedContact, ::testing::ValuesIn(kContactScenes), scene_test_name);
INSTANTIATE_TEST_SUITE_P(Scenes, DistributedState, ::testing::ValuesIn(kContactScenes), scene_test_name);

// PT-Scotch splits the cells the same way every time: on several threads (Scotch 7's
// default) their race changed the partition, and so every Krylov count of a distributed
// run, from one call to the next.
TEST(MeshPartition, IsTheSameEveryTime) {
  int processes = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &processes);
  ASSERT_EQ(processes, 2) << "run under mpirun -n 2";
  auto scene = harness::open_scene("block-strips", 0, {});
  const mesh::Mesh& mesh = scene->problem.space->mesh();
  const fem::MeshPartition first = fem::partition_cells(PETSC_COMM_WORLD, mesh);
  ASSERT_EQ(first.partitioner, "ptscotch");
  for (int k = 2; k <= 5; ++k)
    EXPECT_EQ(fem::partition_cells(PETSC_COMM_WORLD, mesh).cell_owner, first.cell_owner) << "partition " << k;
}

}  // namespace
