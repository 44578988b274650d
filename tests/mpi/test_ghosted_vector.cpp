// Run under `mpirun -n 2` with the other distributed tests. The Newton state held as each
// process's owned unknowns and ghosts (fem::GhostedVector): ghosts take their owners'
// values, owners add their ghosts' values, and the internal forces assembled over a
// process's row cells through its ghosted state are its owned rows of the residual the
// whole vector gives, bit for bit.
#include <gtest/gtest.h>

#include <random>
#include <utility>
#include <vector>

#include "builtin_scenes.hpp"
#include "fem/dof_layout.hpp"
#include "fem/elasticity_assembly.hpp"
#include "fem/ghosted_vector.hpp"
#include "fem/mesh_partition.hpp"
#include "scene/scene.hpp"

namespace {

using namespace stiction;

struct Distributed {
  std::unique_ptr<scene::Scene> scene;
  fem::MeshPartition partition;
  std::unique_ptr<fem::DofLayout> layout;
  std::shared_ptr<const fem::GhostPattern> pattern;
  explicit Distributed(const std::string& name) {
    scene = scene::build_scene(harness::builtin_scenes().at(name), name, ".", 0);
    partition = fem::partition_cells(PETSC_COMM_WORLD, scene->mesh);
    layout = std::make_unique<fem::DofLayout>(PETSC_COMM_WORLD, *scene->space, partition, std::vector<int>{});
    pattern = std::make_shared<fem::GhostPattern>(*layout, fem::unknowns_of_cells(*scene->space, layout->row_cells()));
  }
};

// The same pseudo-random vector on every process.
std::vector<double> random_vector(size_t n, double amplitude) {
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> d(-amplitude, amplitude);
  std::vector<double> x(n);
  for (double& v : x) v = d(gen);
  return x;
}

TEST(GhostedVector, GhostsFollowTheirOwnersAndAddBackIntoThem) {
  Distributed d("mooney-rivlin-block");
  const fem::DofLayout& layout = *d.layout;
  ASSERT_FALSE(layout.identity()) << "run under mpirun -n 2";
  ASSERT_GT(d.pattern->n_ghosts(), 0);
  const PetscInt n = layout.n_total();
  const std::vector<double> whole = random_vector(static_cast<size_t>(n), 1.0);

  fem::GhostedVector x(d.pattern);
  fem::ResidualView xv = x.view();
  for (PetscInt a = 0; a < n; ++a)
    if (layout.owns(a)) xv[a] = whole[a];
  x.update_ghosts();
  int held = 0;
  for (PetscInt a = 0; a < n; ++a)
    if (d.pattern->holds(a)) {
      EXPECT_EQ(xv[a], whole[a]) << "unknown " << a;
      ++held;
    }
  EXPECT_EQ(held, d.pattern->n_stored());
  EXPECT_EQ(x.whole(), whole);

  // Every held entry 1, then each owner adds its ghosts: the number of processes holding it.
  std::vector<int> holders(static_cast<size_t>(n), 0);
  for (PetscInt a = 0; a < n; ++a) holders[a] = d.pattern->holds(a) ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, holders.data(), static_cast<int>(n), MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
  x.fill(1.0);
  x.add_ghosts_to_owners();
  int shared = 0;
  for (PetscInt a = 0; a < n; ++a)
    if (layout.owns(a)) {
      EXPECT_EQ(xv[a], holders[a]) << "unknown " << a;
      shared += holders[a] > 1;
    }
  EXPECT_GT(shared, 0);
}

// A mixed u-p Mooney-Rivlin block, so the ghosts include pressures.
TEST(GhostedVector, RowCellsThroughTheGhostedStateGiveTheOwnedRows) {
  Distributed d("mooney-rivlin-block");
  const fem::DofLayout& layout = *d.layout;
  ASSERT_FALSE(layout.identity()) << "run under mpirun -n 2";
  const fem::FieldSpace& space = *d.scene->space;
  const auto& materials = d.scene->problem.cell_material;
  const std::vector<double> u = random_vector(static_cast<size_t>(space.n_dofs()), 0.05);
  std::vector<double> r_whole(u.size(), 0.0);
  ASSERT_EQ(fem::assemble_internal(space, materials, u, r_whole, nullptr).inverted_cell, -1);

  fem::GhostedVector state(d.pattern), residual(d.pattern);
  fem::ResidualView sv = state.view();
  for (PetscInt a = 0; a < layout.n_total(); ++a)
    if (layout.owns(a)) sv[a] = u[a];
  state.update_ghosts();
  fem::assemble_internal(space, materials, state.view(), residual.view(), nullptr, &layout.row_cells());
  const fem::StateView rv = std::as_const(residual).view();
  int owned = 0;
  for (PetscInt a = 0; a < layout.n_total(); ++a)
    if (layout.owns(a)) {
      EXPECT_EQ(rv[a], r_whole[a]) << "unknown " << a;
      ++owned;
    }
  EXPECT_EQ(owned, layout.n_owned());
  EXPECT_LT(d.pattern->n_stored(), layout.n_total());  // no process holds everything
}

}  // namespace
