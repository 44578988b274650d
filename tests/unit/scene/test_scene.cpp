// Scene schema: defaults, validation messages, and that only named objects are built.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "common/error.hpp"
#include "mesh/mesh.hpp"
#include "registry.hpp"
#include "scene/scene.hpp"
#include "scene/scene_part.hpp"
#include "builtin_scenes.hpp"
#include "support/solve_scene.hpp"

namespace stiction::scene {
namespace {

const std::string kMinimal = test::minimal_bar_scene();

std::string error_of(const std::string& text) {
  try {
    build_scene(text, "test.toml", ".");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Scene, DefaultsComeFromTheSchema) {
  auto s = build_scene(kMinimal, "test.toml", ".");
  EXPECT_EQ(s->name, "test");
  EXPECT_EQ(s->level, 0);
  EXPECT_EQ(s->problem.n_steps(), 1);
  EXPECT_EQ(s->newton.max_iterations, 25);
  EXPECT_DOUBLE_EQ(s->newton.rtol, 1e-6);
  EXPECT_EQ(s->space->kind(), fem::BasisKind::P2Hierarchical);
  EXPECT_EQ(s->problem.dirichlet.size(), 1u);
  EXPECT_TRUE(s->problem.tractions.empty());  // nothing the scene does not name
  EXPECT_FALSE(s->problem.body_force);
  EXPECT_EQ(s->mesh.n_cells(), 8);
}

// newton.krylov_restart: 0 (the backend's) unless the scene sets it; a negative one is bad input.
TEST(Scene, KrylovRestartIsTheBackendsUnlessTheSceneSetsIt) {
  EXPECT_EQ(build_scene(kMinimal, "test.toml", ".")->newton.krylov_restart, 0);
  EXPECT_EQ(build_scene(kMinimal + "\n[newton]\nkrylov_restart = 30\n", "test.toml", ".")->newton.krylov_restart, 30);
  EXPECT_NE(error_of(kMinimal + "\n[newton]\nkrylov_restart = -1\n").find("krylov_restart must be >= 0"),
            std::string::npos);
  EXPECT_EQ(harness::open_scene("block-strips", 0, {})->newton.krylov_restart, 50);
}

// contact.tangential_penalty_floor: 0 and 1 are accepted; outside [0, 1] is bad input.
TEST(Scene, TangentialPenaltyFloorIsValidated) {
  const std::string text = harness::builtin_scenes().at("sliding-block-2d");
  auto with_floor = [&](const std::string& value) {
    return test::replaced(text, "[[contact]]\n", "[[contact]]\ntangential_penalty_floor = " + value + "\n");
  };
  EXPECT_EQ(error_of(with_floor("0.0")), "");
  EXPECT_EQ(error_of(with_floor("1.0")), "");
  for (const char* bad : {"-0.1", "1.5"})
    EXPECT_NE(error_of(with_floor(bad)).find("tangential_penalty_floor in [0, 1]"), std::string::npos) << bad;
}

TEST(Scene, LevelRefines) {
  auto s = build_scene(kMinimal, "test.toml", ".", 2);
  EXPECT_EQ(s->mesh.n_cells(), 8 * 16);
}

// A body meshed from a .geo script (a disk, its rim named "rim"): each level is a new Gmsh
// mesh at sizes / 2^level, so the refined rim stays on the circle (uniform refinement would
// leave its new vertices on the coarse chords, inside it).
TEST(Scene, GeoScriptLevelsRemeshTheGeometry) {
  const std::string dir = ::testing::TempDir();
  {
    std::FILE* f = std::fopen((dir + "/disk.geo").c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("SetFactory(\"OpenCASCADE\");\nDisk(1) = {0, 0, 0, 1};\nPhysical Surface(\"body\") = {1};\n"
               "Physical Curve(\"rim\") = {1};\nMesh.MeshSizeMax = 0.25;\n", f);
    std::fclose(f);
  }
  std::string text = test::replaced(kMinimal, R"(mesh = { generator = "structured-box", size = [4.0, 1.0], cells = [4, 1] })",
                                    R"(mesh = { file = "disk.geo" })");
  text = test::replaced(text, R"(boundary = "xmin")", R"(boundary = "rim")");
  const auto coarse = build_scene(text, "disk.toml", dir, 0), fine = build_scene(text, "disk.toml", dir, 1);
  EXPECT_GT(fine->mesh.n_cells(), 3 * coarse->mesh.n_cells());
  const int rim = fine->mesh.facet_tag_names.at("bar/rim");
  int on_rim = 0;
  for (int f = 0; f < fine->mesh.n_facets(); ++f) {
    if (fine->mesh.facet_tags[f] != rim) continue;
    const double* x = fine->mesh.vertex(fine->mesh.facet(f)[0]);
    EXPECT_NEAR(std::hypot(x[0], x[1]), 1.0, 1e-9);
    ++on_rim;
  }
  EXPECT_GT(on_rim, 40);
}

// The paper's block with strips through a scene: the generator's defaults (no keys but the
// generator), level 1 as a uniform refinement (8x the tetrahedra, as in Table 1), the keys
// reaching the geometry (its volume), and the generator's errors naming file and body.
TEST(Scene, GroovedBlockGenerator) {
  std::string text = test::replaced(kMinimal, R"(mesh = { generator = "structured-box", size = [4.0, 1.0], cells = [4, 1] })",
                                    R"(mesh = { generator = "grooved-block" })");
  text = test::replaced(text, R"(boundary = "xmin")", R"(boundary = "top")");
  text = test::replaced(text, R"(components = ["x", "y"])", R"(components = ["x", "y", "z"])");
  text = test::replaced(text, "value = [0.0, 0.0]", "value = [0.0, 0.0, 0.0]");
  const auto level0 = build_scene(text, "block.toml", ".", 0), level1 = build_scene(text, "block.toml", ".", 1);
  EXPECT_EQ(level0->mesh.dim, 3);
  EXPECT_EQ(level1->mesh.n_cells(), 8 * level0->mesh.n_cells());
  for (const char* name : {"top", "strip-bottom", "groove-wall-left", "groove-wall-right", "groove-floor", "xmin", "xmax",
                           "ymin", "ymax"})
    EXPECT_TRUE(level1->mesh.facet_tag_names.count(std::string("bar/") + name)) << name;

  const std::string custom = test::replaced(
      text, R"(mesh = { generator = "grooved-block" })",
      R"(mesh = { generator = "grooved-block", size = [30.0, 20.0, 10.0], grooves = 3, groove_width = 1.5, groove_depth = 4.0, h = 3.0, contact_size = 1.5 })");
  const auto s = build_scene(custom, "block.toml", ".");
  double volume = 0;
  for (int c = 0; c < s->mesh.n_cells(); ++c) volume += mesh::signed_measure(s->mesh, c);
  EXPECT_NEAR(volume, 30.0 * 20 * 10 - 3 * 1.5 * 4 * 20, 1e-9 * 6000);

  const std::string deep = error_of(test::replaced(custom, "groove_depth = 4.0", "groove_depth = 12.0"));
  EXPECT_NE(deep.find("test.toml: body 'bar': grooved-block generator: groove_depth = 12"), std::string::npos) << deep;
  const std::string wide = error_of(test::replaced(custom, "groove_width = 1.5", "groove_width = 10.0"));
  EXPECT_NE(wide.find("3 grooves 10 wide do not fit in lx = 30"), std::string::npos) << wide;
  const std::string flat = error_of(test::replaced(custom, "size = [30.0, 20.0, 10.0]", "size = [30.0, 20.0]"));
  EXPECT_NE(flat.find("'grooved-block' needs mesh.size = [lx, ly, lz]"), std::string::npos) << flat;
}

TEST(Scene, UnknownKeyNamesFileKeyAndAccepted) {
  const std::string msg = error_of(std::string(kMinimal) + "\n[newton]\nrtool = 1e-6\n");
  EXPECT_NE(msg.find("test.toml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'newton.rtool'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("rtol"), std::string::npos) << msg;  // the accepted keys
}

TEST(Scene, WrongTypeAndBadChoice) {
  EXPECT_NE(error_of(std::string(kMinimal) + "\n[load]\nsteps = \"four\"\n").find("must be a integer"), std::string::npos);
  std::string bad = kMinimal;
  bad.replace(bad.find("\"linear\""), 8, "\"rubbery\"");
  const std::string msg = error_of(bad);
  EXPECT_NE(msg.find("'rubbery'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("neo-hookean"), std::string::npos) << msg;
}

// master_point picks the 3D master point; 2D surfaces and rigid planes have one rule only.
TEST(Scene, MasterPointIsA3DSurfaceKey) {
  const std::string cylinders = harness::builtin_scenes().at("hertz-cylinders-2d");
  const std::string crossing_2d =
      error_of(test::replaced(cylinders, "friction = 0.0", "friction = 0.0\nmaster_point = \"normal-crossing\""));
  EXPECT_NE(crossing_2d.find("master_point 'normal-crossing' is 3D only"), std::string::npos) << crossing_2d;
  EXPECT_EQ(error_of(test::replaced(cylinders, "friction = 0.0", "friction = 0.0\nmaster_point = \"closest\"")), "");
  const std::string on_plane = error_of(test::replaced(harness::builtin_scenes().at("hertz-cylinder-2d"),
                                                       "friction = 0.0", "friction = 0.0\nmaster_point = \"closest\""));
  EXPECT_NE(on_plane.find("key 'master_point' does not apply to master 'plane'"), std::string::npos) << on_plane;
  const std::string unknown = error_of(test::replaced(harness::builtin_scenes().at("hertz-spheres-3d"),
                                                      "friction = 0.0", "friction = 0.0\nmaster_point = \"nearest\""));
  EXPECT_NE(unknown.find("'nearest'"), std::string::npos) << unknown;
}

TEST(Scene, MissingRequiredKey) {
  std::string bad = kMinimal;
  bad.erase(bad.find("material = \"steel\""), 18);
  EXPECT_NE(error_of(bad).find("missing required key 'body[0].material'"), std::string::npos) << error_of(bad);
}

TEST(Scene, MaterialKeysFollowTheModel) {
  std::string missing = kMinimal;
  missing.erase(missing.find("nu = 0.3"), 8);
  EXPECT_NE(error_of(missing).find("model 'linear' needs key 'nu'"), std::string::npos) << error_of(missing);
  std::string foreign = kMinimal;
  foreign.replace(foreign.find("nu = 0.3"), 8, "nu = 0.3\nkappa = 10.0");
  EXPECT_NE(error_of(foreign).find("key 'kappa' does not apply to model 'linear'"), std::string::npos)
      << error_of(foreign);
}

TEST(Scene, MixedLawBuildsAPressureFieldOnlyOnItsBody) {
  const std::string text = std::string(kMinimal) + R"(
[[material]]
name = "rubber"
model = "mooney-rivlin"
mu10 = 1.0
mu01 = 0.1
kappa = 100.0

[[body]]
name = "pad"
material = "rubber"
mesh = { generator = "structured-box", size = [1.0, 1.0], cells = [2, 2] }
)";
  auto s = build_scene(std::string(text).replace(text.find("boundary = \"xmin\""), 17,
                                                 "body = \"bar\"\nboundary = \"xmin\""),
                       "test.toml", ".");
  ASSERT_TRUE(s->space->has_pressure());
  EXPECT_EQ(s->space->n_pressure_dofs(), 9);  // the pad's 3 x 3 vertices only
  EXPECT_FALSE(build_scene(kMinimal, "test.toml", ".")->space->has_pressure());
}

TEST(Scene, ScheduleLengthMustMatchSteps) {
  const std::string msg = error_of(std::string(kMinimal) + "\n[load]\nsteps = 3\n[[traction]]\nboundary = \"xmax\"\n"
                                                           "value = [1.0, 0.0]\nschedule = [0.5, 1.0]\n");
  EXPECT_NE(msg.find("schedule has 2 entries for 3 load steps"), std::string::npos) << msg;
}

// Load phases give the steps' pseudo-times; a table gives a load as a function of them.
TEST(Scene, PhasesAndTablesDefineLoadsInPseudoTime) {
  const std::string text = std::string(kMinimal) +
                           "\n[load]\nphases = [{ until = 1.0, steps = 2 }, { until = 3.0, steps = 4 }]\nquick_until = 1.5\n"
                           "[[traction]]\nboundary = \"xmax\"\ntable = [[0.0, 0.0, 0.0], [1.0, 2.0, 0.0], [3.0, 2.0, -4.0]]\n";
  auto s = build_scene(text, "test.toml", ".");
  const std::vector<double> expected{0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0};
  ASSERT_EQ(s->problem.step_times.size(), expected.size());
  for (size_t k = 0; k < expected.size(); ++k) EXPECT_DOUBLE_EQ(s->problem.step_times[k], expected[k]);
  EXPECT_DOUBLE_EQ(s->quick_until, 1.5);
  double t[2];
  s->problem.tractions.at(0).value(nullptr, 0.5, t);
  EXPECT_DOUBLE_EQ(t[0], 1.0);
  s->problem.tractions.at(0).value(nullptr, 2.0, t);
  EXPECT_DOUBLE_EQ(t[0], 2.0);
  EXPECT_DOUBLE_EQ(t[1], -2.0);
  // A per-step schedule is a table on the steps' pseudo-times (linear in between).
  auto u = build_scene(std::string(kMinimal) + "\n[load]\nsteps = 2\n[[traction]]\nboundary = \"xmax\"\n"
                                               "value = [1.0, 0.0]\nschedule = [1.0, 0.0]\n",
                       "test.toml", ".");
  u->problem.tractions.at(0).value(nullptr, 0.25, t);
  EXPECT_DOUBLE_EQ(t[0], 0.5);
  u->problem.tractions.at(0).value(nullptr, 0.75, t);
  EXPECT_DOUBLE_EQ(t[0], 0.5);
}

TEST(Scene, LoadTablesAndPhasesAreChecked) {
  const std::string traction = "\n[[traction]]\nboundary = \"xmax\"\n";
  EXPECT_NE(error_of(std::string(kMinimal) + traction + "value = [1.0, 0.0]\ntable = [[0.0, 0.0, 0.0]]\n")
                .find("give exactly one of 'value'"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + traction + "table = [[0.0, 0.0], [1.0, 1.0]]\n").find("needs 3 numbers"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + traction + "table = [[1.0, 0.0, 0.0], [0.5, 1.0, 0.0]]\n")
                .find("pseudo-times must increase"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "\n[load]\nsteps = 2\nphases = [{ until = 1.0, steps = 2 }]\n")
                .find("not both"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "\n[load]\nphases = [{ until = 1.0, steps = 2 }, { until = 0.5, steps = 1 }]\n")
                .find("until > 1"),
            std::string::npos);
}

TEST(Scene, SchemaDocumentsEveryKey) {
  const std::string doc = document(scene_schema());
  for (const char* key : {"material", "body", "dirichlet", "traction", "schedule", "max_iterations", "basis"})
    EXPECT_NE(doc.find(key), std::string::npos) << key;
}

}  // namespace
}  // namespace stiction::scene

namespace stiction {
namespace {

// A scene knows whether its levels are uniform refinements of level 0 (what dividing level 0
// and refining the parts relies on): not when a body is re-meshed per level (curved polygon
// sides, spheres, tubes). It keeps the level its file asks for beside the one built.
TEST(Scene, KnowsWhetherItsLevelsAreRefinementsOfLevelZero) {
  EXPECT_TRUE(harness::open_scene("cook-membrane-2d", 0, {})->levels_by_refinement);
  EXPECT_TRUE(harness::open_scene("block-compression", 0, {})->levels_by_refinement);
  EXPECT_FALSE(harness::open_scene("hertz-cylinder-2d", 0, {})->levels_by_refinement);  // arc sides
  EXPECT_FALSE(harness::open_scene("hertz-spheres-3d", 0, {})->levels_by_refinement);   // sphere octants
  const auto s = scene::build_scene(std::string("[scene]\nlevel = 1\n") + test::minimal_bar_scene(), "test.toml", ".", 0);
  EXPECT_EQ(s->file_level, 1);
  EXPECT_EQ(s->level, 0);
}

// On one process a scene's part is the whole scene (refined in parts: the whole finer
// level), and solving on it is the whole-mesh run, bit for bit.
TEST(ScenePart, OnOneProcessSolvesAsTheWholeScene) {
  const test::SolvedScene fine = test::solve_builtin("cook-membrane-2d", 1, "lu-mumps");
  ASSERT_TRUE(fine.converged());
  const auto coarse = harness::open_scene("cook-membrane-2d", 0, {});
  const auto parts = scene::divide_scene(PETSC_COMM_WORLD, *coarse, 1);
  EXPECT_EQ(parts->part.mesh.n_cells(), fine.scene->mesh.n_cells());
  EXPECT_EQ(parts->part.mesh.coords, fine.scene->mesh.coords);
  auto solver = solvers::create_solver("lu-mumps", PETSC_COMM_WORLD);
  nonlinear::QuasiStaticSolver newton(PETSC_COMM_WORLD, parts->problem, parts->part, parts->ownership,
                                      fine.scene->newton, *solver);
  const auto steps = newton.run();
  ASSERT_EQ(steps.size(), fine.steps.size());
  for (size_t k = 0; k < steps.size(); ++k) EXPECT_EQ(steps[k].iterations.size(), fine.steps[k].iterations.size());
  EXPECT_EQ(newton.displacement(), fine.u);
}

}  // namespace
}  // namespace stiction

namespace stiction {
namespace {

// Refined in parts, each cell keeps the law of its body: two bodies of different laws, as
// the whole scene refined gives them cell by cell.
TEST(ScenePart, RefinedCellsKeepTheirBodysLaw) {
  const std::string text = R"(
[[material]]
name = "stiff"
model = "linear"
E = 200.0
nu = 0.3

[[material]]
name = "soft"
model = "neo-hookean"
E = 2.0
nu = 0.3

[[body]]
name = "left"
material = "stiff"
mesh = { generator = "polygon", points = [0.0, 0.0, 2.0, 0.0, 2.0, 1.0, 0.0, 1.0], sides = ["base", "right", "top", "side"], h = 0.5 }

[[body]]
name = "right"
material = "soft"
mesh = { generator = "polygon", points = [3.0, 0.0, 5.0, 0.0, 5.0, 1.0, 3.0, 1.0], sides = ["base", "right", "top", "side"], h = 0.4 }

[[dirichlet]]
body = "left"
boundary = "base"
components = ["x", "y"]
value = [0.0, 0.0]

[[dirichlet]]
body = "right"
boundary = "base"
components = ["x", "y"]
value = [0.0, 0.0]
)";
  const auto coarse = scene::build_scene(text, "two-bodies", ".", 0);
  const auto fine = scene::build_scene(text, "two-bodies", ".", 2);
  const auto parts = scene::divide_scene(PETSC_COMM_WORLD, *coarse, 2);
  ASSERT_EQ(parts->problem.cell_material.size(), fine->problem.cell_material.size());
  int wrong = 0, soft = 0;
  for (size_t c = 0; c < fine->problem.cell_material.size(); ++c) {
    const std::string law = parts->problem.cell_material[c]->describe();
    wrong += law != fine->problem.cell_material[c]->describe();
    soft += law == fine->materials[1]->describe();
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(soft, 0);
  EXPECT_LT(soft, static_cast<int>(fine->problem.cell_material.size()));
}

}  // namespace
}  // namespace stiction
