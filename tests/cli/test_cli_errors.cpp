// Bad input to the `stiction` CLI must end with exactly one `stiction: error: <message>`
// line on stderr and the documented exit code (2 bad input, 3 numerical failure), never a
// crash; a valid run must exit 0 and write its output files.
//
// The binary is run as a child process (std::system) from a fresh temporary directory; the
// scene variants are written there at test time from a copy of the cantilever-2d scene.
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "builtin_scenes.hpp"
#include "cli_run.hpp"
#include "cli_scenes.hpp"
#include "checkpoint.hpp"
#include "csv_table.hpp"
#include "run_info.hpp"
#include "run_settings.hpp"
#include "vtu_reader.hpp"

namespace {

namespace fs = std::filesystem;
using stiction::test::CliRun;
using stiction::test::read_file;
using stiction::test::shell_quote;
using stiction::test::without_mpi_environment;

#ifdef STICTION_TEST_DATA_DIR
const fs::path data_dir = STICTION_TEST_DATA_DIR;
#else
const fs::path data_dir = fs::path(__FILE__).parent_path().parent_path() / "data";
#endif

using stiction::test::SceneVariant;

class StictionCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = stiction::test::make_temporary_directory("stiction-cli");
    ASSERT_FALSE(dir_.empty()) << "cannot create a temporary directory";
  }

  void TearDown() override {
    std::error_code ignored;
    if (!dir_.empty()) fs::remove_all(dir_, ignored);
  }

  // `stiction solve SCENE --quiet --out DIR/out EXTRA...`
  CliRun solve(const std::string& scene, const std::vector<std::string>& extra = {}) const {
    std::vector<std::string> args = {"solve", scene, "--quiet", "--out", (dir_ / "out").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return CliRun::of(args, dir_);
  }

  // Writes `scene` as DIR/file_name and solves it.
  CliRun solve_variant(const SceneVariant& scene, const std::string& file_name) const {
    return solve(scene.write(dir_, file_name).string());
  }

  fs::path dir_;
};

// The run ended with exit `code` and one clean error line containing every needle.
void expect_error(const CliRun& run, int code, const std::vector<std::string>& needles) {
  SCOPED_TRACE("stderr:\n" + run.err);
  EXPECT_EQ(run.exit_code, code) << "(124: timed out; above 128: killed by signal)";
  const auto lines = run.error_lines();
  ASSERT_EQ(lines.size(), 1u) << "expected exactly one 'stiction: error:' line";
  std::string last_line = run.err.substr(0, run.err.find_last_not_of('\n') + 1);
  last_line = last_line.substr(last_line.find_last_of('\n') + 1);
  EXPECT_EQ(last_line, lines.front()) << "the error line must end stderr";
  for (const char* crash : {"terminate", "Segmentation", "Abort", "core dumped"})
    EXPECT_EQ(run.err.find(crash), std::string::npos) << "crash marker '" << crash << "'";
  EXPECT_FALSE(std::regex_search(run.err, std::regex(R"(\bnan\b)", std::regex::icase)))
      << "NaN in the output";
  for (const auto& needle : needles)
    EXPECT_NE(lines.front().find(needle), std::string::npos) << "message lacks '" << needle << "'";
}

TEST_F(StictionCli, MalformedTomlNamesTheLine) {
  const auto scene = SceneVariant().replace("E = 1000.0", "E = = 1000.0");
  const int line = scene.line_of("E = = 1000.0");
  expect_error(solve_variant(scene, "malformed.toml"), 2,
               {"malformed.toml", "malformed TOML", "line " + std::to_string(line)});
}

TEST_F(StictionCli, UnknownKeyNamesFileKeyPathAndAcceptedKeys) {
  const auto scene = SceneVariant().replace("material = \"soft\"", "matreial = \"soft\"");
  expect_error(solve_variant(scene, "unknown-key.toml"), 2,
               {"unknown-key.toml", "body[0].matreial", "accepted", "name", "material", "mesh"});
}

TEST_F(StictionCli, WrongTypeSaysMustBeANumber) {
  const auto scene = SceneVariant().replace("E = 1000.0", "E = \"soft\"");
  expect_error(solve_variant(scene, "wrong-type.toml"), 2,
               {"wrong-type.toml", "material[0].E", "must be a number"});
}

TEST_F(StictionCli, MissingMeshFileIsNotFound) {
  const auto scene = SceneVariant().replace(
      "mesh = { generator = \"box\", size = [10.0, 1.0], h = 0.25 }",
      "mesh = { file = \"no-such-mesh.msh\" }");
  expect_error(solve_variant(scene, "missing-mesh.toml"), 2, {"no-such-mesh.msh", "not found"});
}

// tests/data/inverted-2d.msh: the 2 x 1 rectangle in four triangles with physical curves
// "left" and "right"; its last triangle (cell 3, vertices (1,0) (1,1) (2,1)) is clockwise.
TEST_F(StictionCli, InvertedElementNamesIndexAndCoordinates) {
  fs::copy_file(data_dir / "inverted-2d.msh", dir_ / "inverted.msh");
  const auto scene = SceneVariant()
                         .replace("mesh = { generator = \"box\", size = [10.0, 1.0], h = 0.25 }",
                                  "mesh = { file = \"inverted.msh\" }")
                         .replace("\"xmin\"", "\"left\"")
                         .replace("\"xmax\"", "\"right\"");
  expect_error(solve_variant(scene, "inverted.toml"), 2,
               {"beam", "inverted element 3", "(1, 0) (1, 1) (2, 1)"});
}

TEST_F(StictionCli, UnknownSolverListsValidBackends) {
  expect_error(solve("cantilever-2d", {"--solver", "nosuch"}), 2, {"nosuch", "lu-mumps"});
}

TEST_F(StictionCli, NewtonFailureIsNumericalError) {
  const auto scene =
      SceneVariant().append("\n[newton]\nmax_iterations = 1\nrtol = 1e-30\natol = 1e-30\n");
  expect_error(solve_variant(scene, "newton-fails.toml"), 3,
               {"did not converge", "DIVERGED_MAX_ITERATIONS"});
}

TEST_F(StictionCli, UnknownSceneNameListsBuiltIns) {
  expect_error(solve("no-such-scene"), 2,
               {"no-such-scene", "block-compression", "cantilever-2d"});
}

TEST_F(StictionCli, UnusedPetscOptionIsReported) {
  expect_error(solve("cantilever-2d", {"-lu_mumps_no_such_option", "3"}), 2,
               {"-lu_mumps_no_such_option", "not used"});
}

// The contact level's own option values (solvers/contact_pc.hpp) are checked when it is set
// up: a value it does not know ends the run with one message naming the option.
TEST_F(StictionCli, BadContactSchurOptionValueNamesTheOption) {
  const std::vector<std::string> schur_amg = {"--solver", "schur-amg", "--no-vtu"};
  auto with = [&](std::initializer_list<std::string> option) {
    std::vector<std::string> args = schur_amg;
    args.insert(args.end(), option);
    return solve("hertz-cylinder-2d", args);
  };
  expect_error(with({"-schur_amg_contact_fractional_form", "sparse"}), 2,
               {"-schur_amg_contact_fractional_form", "'sparse'", "auto, dense or rational"});
  expect_error(with({"-schur_amg_contact_fractional_form", "rational", "-schur_amg_contact_fractional_tol", "0"}), 2,
               {"-schur_amg_contact_fractional_tol", "not in (0, 0.5)"});
  expect_error(with({"-schur_amg_contact_schur", "exact"}), 2, {"-schur_amg_contact_schur", "'exact'"});
}

TEST_F(StictionCli, UnknownBoundaryListsTheBodysBoundaries) {
  const auto scene = SceneVariant().replace("\"xmin\"", "\"nosuch\"");
  expect_error(solve_variant(scene, "unknown-boundary.toml"), 2,
               {"unknown-boundary.toml", "dirichlet[0]", "nosuch", "xmin", "xmax", "ymin", "ymax"});
}

TEST_F(StictionCli, ContactPairKeysAreCheckedAgainstTheMaster) {
  const std::string pair = "\n[[contact]]\nboundary = \"ymin\"\nmaster = \"surface\"\n";
  expect_error(solve_variant(SceneVariant().append(pair), "no-master-boundary.toml"), 2,
               {"no-master-boundary.toml", "contact[0]", "master_boundary"});
  expect_error(solve_variant(SceneVariant().append(pair + "master_boundary = \"ymax\"\npoint = [0.0, 0.0]\n"),
                             "plane-key.toml"),
               2, {"plane-key.toml", "contact[0]", "'point'", "does not apply"});
}

TEST_F(StictionCli, ValidRunWritesOutput) {
  const CliRun run = solve("cantilever-2d");
  EXPECT_EQ(run.exit_code, 0) << "stderr:\n" << run.err;
  EXPECT_TRUE(run.error_lines().empty()) << run.err;
  for (const char* file : {"steps.csv", "solution.pvd", "step-004.vtu"})
    EXPECT_TRUE(fs::is_regular_file(dir_ / "out" / file)) << file << " not written";
}

// A run stopped after two of its four load steps (--until) and restarted from its checkpoint
// ends where an uninterrupted run ends, with the rows of both parts in one steps.csv.
TEST_F(StictionCli, RestartContinuesFromTheLastCompletedStep) {
  const CliRun whole = CliRun::of({"solve", "cantilever-2d", "--quiet", "--no-vtu", "--out", (dir_ / "whole").string()},
                                  dir_);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const CliRun first = solve("cantilever-2d", {"--no-vtu", "--until", "0.5"});
  ASSERT_EQ(first.exit_code, 0) << first.err;
  ASSERT_EQ(stiction::harness::read_csv((dir_ / "out" / "steps.csv").string()).rows.size(), 2u);
  const CliRun rest = solve("cantilever-2d", {"--no-vtu", "--restart", (dir_ / "out").string()});
  ASSERT_EQ(rest.exit_code, 0) << rest.err;
  const auto parts = stiction::harness::read_csv((dir_ / "out" / "steps.csv").string()).rows;
  const auto straight = stiction::harness::read_csv((dir_ / "whole" / "steps.csv").string()).rows;
  ASSERT_EQ(parts.size(), 4u);
  ASSERT_EQ(straight.size(), 4u);
  EXPECT_EQ(parts.back().at("step"), "4");
  for (const char* column : {"reaction_beam/xmin_x", "reaction_beam/xmin_y", "min_det_f"}) {
    const double a = std::stod(parts.back().at(column)), b = std::stod(straight.back().at(column));
    EXPECT_NEAR(a, b, 1e-8 * std::abs(b)) << column;
  }
  expect_error(solve("sliding-block-2d", {"--no-vtu", "--restart", (dir_ / "out").string()}), 2,
               {"checkpoint", "cantilever-2d", "sliding-block-2d"});
  expect_error(solve("cantilever-2d", {"--restart", (dir_ / "nowhere").string()}), 2, {"no checkpoint", "nowhere"});
}

// A checkpoint carries the run's tally of linear solves (a restart then retries failed
// solves as the uninterrupted run would) and the cut-back's state (it then takes the same
// increments); one of format 2, written before the cut-back's state, reads with none, and
// one of format 1, written before the tally, with a zero tally too.
TEST_F(StictionCli, CheckpointCarriesTheLinearSolveTallyAndTheCutBack) {
  using stiction::harness::Checkpoint;
  Checkpoint c;
  c.scene = "ironing-2d";
  c.level = 1;
  c.state.step = 7;
  c.state.time = 1.25;
  c.state.u = {1.0, -2.0, 3.5};
  c.state.lambda = {0.25};
  c.state.constraints = {{1.0, 2.0}};
  c.tally = {1234, 5};
  c.cut_back.cut = 2;
  c.cut_back.converged_at_cut = 1;
  c.cut_back.wait = {2, 2, 4, 8};
  c.cut_back.probing = true;
  const std::string path = (dir_ / "checkpoint.bin").string();
  stiction::harness::write_checkpoint(path, c);
  const Checkpoint back = stiction::harness::read_checkpoint(path);
  EXPECT_EQ(back.tally.solves, 1234);
  EXPECT_EQ(back.tally.failures, 5);
  EXPECT_EQ(back.cut_back.cut, 2);
  EXPECT_EQ(back.cut_back.converged_at_cut, 1);
  EXPECT_EQ(back.cut_back.wait, c.cut_back.wait);
  EXPECT_TRUE(back.cut_back.probing);
  EXPECT_EQ(back.state.u, c.state.u);
  EXPECT_EQ(back.state.constraints, c.state.constraints);

  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  auto rewrite = [&](char format, size_t trailing_bytes) {
    bytes[7] = format;
    bytes.resize(bytes.size() - trailing_bytes);
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << bytes;
  };
  ASSERT_EQ(bytes[7], '3');
  rewrite('2', 8 * (4 + c.cut_back.wait.size()));  // the cut-back's counts, flag and waits
  const Checkpoint format2 = stiction::harness::read_checkpoint(path);
  EXPECT_EQ(format2.tally.solves, 1234);
  EXPECT_EQ(format2.cut_back.cut, 0);
  EXPECT_TRUE(format2.cut_back.wait.empty());
  EXPECT_EQ(format2.state.u, c.state.u);
  rewrite('1', 16);  // the two tally counts
  const Checkpoint old = stiction::harness::read_checkpoint(path);
  EXPECT_EQ(old.tally.solves, 0);
  EXPECT_EQ(old.tally.failures, 0);
  EXPECT_EQ(old.state.u, c.state.u);
  EXPECT_EQ(old.state.time, 1.25);
}

// A run whose steps are cut carries the reduced increment into the next load step; restarted
// from the checkpoint after load step 1, it takes the same increments as the uninterrupted
// run (cantilever-2d with at most 3 Newton iterations: load step 1 ends in sixteenths of a
// step, and step 2 starts in them).
TEST_F(StictionCli, RestartTakesTheIncrementsOfTheUninterruptedRun) {
  const std::vector<std::string> cut = {"--no-vtu", "--set", "newton.max_iterations=3"};
  auto with = [&](std::vector<std::string> args) {
    args.insert(args.end(), cut.begin(), cut.end());
    return args;
  };
  const fs::path whole_dir = dir_ / "whole";
  std::vector<std::string> whole_args = with({"solve", "cantilever-2d", "--quiet", "--out", whole_dir.string()});
  const CliRun whole = CliRun::of(whole_args, dir_);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const CliRun first = solve("cantilever-2d", with({"--until", "0.25"}));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const CliRun rest = solve("cantilever-2d", with({"--restart", (dir_ / "out").string()}));
  ASSERT_EQ(rest.exit_code, 0) << rest.err;
  auto increments_after_step_1 = [](const fs::path& file) {
    std::vector<std::string> rows;
    for (const auto& row : stiction::harness::read_csv(file.string()).rows)
      if (row.at("step") != "1") rows.push_back(row.at("time") + " cut " + row.at("cut") + " " + row.at("reason"));
    return rows;
  };
  const auto straight = increments_after_step_1(whole_dir / "steps.csv");
  ASSERT_FALSE(straight.empty());
  EXPECT_NE(straight.front().find(" cut 4 "), std::string::npos) << "step 2 starts in the sixteenths step 1 ended in";
  EXPECT_EQ(increments_after_step_1(dir_ / "out" / "steps.csv"), straight);
}

// With contact, a restart follows the uninterrupted run's Newton path: the same residual at
// every iteration of the steps after the checkpoint (the contact states come from the
// checkpoint, everything else a contact pair tracks restarts with each increment).
TEST_F(StictionCli, RestartWithContactFollowsTheUninterruptedNewtonPath) {
  const fs::path whole_dir = dir_ / "whole";
  // Curved deformable contact over two steps: the normals' terms enter the Jacobian.
  const CliRun whole = CliRun::of({"solve", "hertz-cylinders-2d", "--quiet", "--no-vtu", "--out", whole_dir.string()},
                                  dir_);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const CliRun first = solve("hertz-cylinders-2d", {"--no-vtu", "--until", "0.5"});
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const CliRun rest = solve("hertz-cylinders-2d", {"--no-vtu", "--restart", (dir_ / "out").string()});
  ASSERT_EQ(rest.exit_code, 0) << rest.err;
  auto last_step_rows = [](const fs::path& file) {
    std::vector<std::map<std::string, std::string>> rows;
    for (const auto& row : stiction::harness::read_csv(file.string()).rows)
      if (row.at("step") == "2") rows.push_back(row);
    return rows;
  };
  const auto restarted = last_step_rows(dir_ / "out" / "iterations.csv");
  const auto straight = last_step_rows(whole_dir / "iterations.csv");
  ASSERT_GE(straight.size(), 2u) << "the last step takes Newton iterations to compare";
  ASSERT_EQ(restarted.size(), straight.size());
  for (size_t i = 0; i < straight.size(); ++i) {
    const double a = std::stod(restarted[i].at("residual")), b = std::stod(straight[i].at("residual"));
    EXPECT_NEAR(a, b, 1e-6 * std::abs(b) + 1e-14) << "iteration " << i + 1;
  }
}

// With contact, contact.csv holds a row per multiplier node and load step, and the VTU the
// contact fields; two conditions on one boundary get two sets of reaction columns.
TEST_F(StictionCli, ContactRunWritesContactNodesAndFields) {
  const CliRun run = solve("sliding-block-2d");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto nodes = stiction::harness::read_csv((dir_ / "out" / "contact.csv").string());
  ASSERT_EQ(nodes.rows.size(), 3u * 11u) << "three load steps, eleven slave nodes";
  for (const char* column : {"x", "y", "gap", "lambda_n", "lambda_t_x", "state"})
    EXPECT_TRUE(nodes.rows.front().count(column)) << column;
  int slipping = 0;
  for (const auto& row : nodes.rows)
    if (row.at("step") == "3") slipping += row.at("state") == "slip";
  EXPECT_EQ(slipping, 11) << "the whole contact slides in the last step";
  const std::string vtu = read_file(dir_ / "out" / "step-003.vtu");
  for (const char* field : {"contact_multiplier", "contact_pressure", "contact_state"})
    EXPECT_NE(vtu.find(field), std::string::npos) << field;
  const auto steps = stiction::harness::read_csv((dir_ / "out" / "steps.csv").string());
  EXPECT_TRUE(steps.rows.front().count("reaction_block/ymax_y"));
  EXPECT_TRUE(steps.rows.front().count("reaction_block/ymax:x_x")) << "the second condition on ymax";
}

TEST_F(StictionCli, TraceContactPrintsEveryStateChangeOfTheRun) {
  // Replaying the traced transitions from "all inactive" must end at the states contact.csv
  // holds for the last step; without the flag nothing is traced.
  const CliRun quiet = solve("sliding-block-2d");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err.find(" -> "), std::string::npos) << quiet.err;

  const CliRun run = solve("sliding-block-2d", {"--trace-contact"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::regex line(R"(step (\d+) iteration (\d+): (\S+) node (\d+) \(vertex \d+\) (\w+) -> (\w+), gap \S+, )"
                        R"(lambda_n \S+, \|lambda_t\| \S+, x \()");
  std::map<std::string, std::string> traced;  // node -> state after its last traced change
  int changes = 0;
  std::istringstream in(run.err);
  for (std::string text; std::getline(in, text);) {
    std::smatch m;
    if (!std::regex_search(text, m, line)) continue;
    ++changes;
    const std::string node = m[4], before = m[5], after = m[6];
    EXPECT_EQ(traced.count(node) ? traced[node] : "inactive", before) << text;
    EXPECT_NE(before, after) << text;
    traced[node] = after;
  }
  EXPECT_GE(changes, 11) << "every slave node enters contact at least once\n" << run.err;
  const auto nodes = stiction::harness::read_csv((dir_ / "out" / "contact.csv").string());
  int compared = 0;
  for (const auto& row : nodes.rows) {
    if (row.at("step") != "3") continue;
    const std::string node = row.at("node");
    EXPECT_EQ(traced.count(node) ? traced[node] : "inactive", row.at("state")) << "node " << node;
    ++compared;
  }
  EXPECT_EQ(compared, 11);
}

// boomeramg's set-up fails on the contact system (hypre error 12) at the increment's second
// solve: the increment is retried over half of it, fails the same way, and the run ends
// with one message (PETSc's hypre PC, reset after the failed set-up, once freed its vectors
// twice and the run aborted).
TEST_F(StictionCli, FailedAmgSetUpRetriedOnceEndsWithOneMessage) {
  const CliRun run = solve("sliding-block-2d", {"--solver", "boomeramg", "--quick", "--no-vtu"});
  expect_error(run, 3, {"load step 1", "PC_SETUP_FAILED"});
  const auto steps = stiction::harness::read_csv((dir_ / "out" / "steps.csv").string()).rows;
  ASSERT_EQ(steps.size(), 2u) << "the whole increment, then its half";
  EXPECT_EQ(steps[0].at("retried"), "1");
  EXPECT_EQ(steps[1].at("cut"), "1");
  EXPECT_EQ(steps[1].at("retried"), "0");
}

TEST_F(StictionCli, UnknownVtuFormatListsTheChoices) {
  const auto scene = SceneVariant().append("\n[output]\nvtu_format = \"xml\"\n");
  expect_error(solve_variant(scene, "vtu-format.toml"), 2, {"vtu-format.toml", "output.vtu_format", "'xml'", "accepted: binary, ascii"});
}

// The default VTU keeps every array zlib-compressed in the appended section (VTK's layout,
// decoded by vtu_reader independently of the writer); decoded, it holds the values of the
// same run written with `[output] vtu_format = "ascii"` (10 to 12 significant digits).
TEST_F(StictionCli, BinaryVtuDecodesToTheAsciiValues) {
  const auto run = [&](const SceneVariant& scene, const std::string& name) {
    const CliRun r = CliRun::of(
        {"solve", scene.write(dir_, name + ".toml").string(), "--quiet", "--out", (dir_ / name).string()}, dir_);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return dir_ / name / "step-004.vtu";
  };
  const fs::path binary_path = run(SceneVariant(), "binary");
  const fs::path ascii_path = run(SceneVariant().append("\n[output]\nvtu_format = \"ascii\"\n"), "ascii");
  stiction::test::VtuFile binary, ascii;
  ASSERT_NO_THROW(binary = stiction::test::read_vtu(binary_path.string()));
  ASSERT_NO_THROW(ascii = stiction::test::read_vtu(ascii_path.string()));

  EXPECT_EQ(binary.attributes["header_type"], "UInt64");
  EXPECT_EQ(binary.attributes["compressor"], "vtkZLibDataCompressor");
  for (const auto& a : binary.arrays) EXPECT_EQ(a.format, "appended") << a.name << " is not in the appended section";
  for (const auto& a : ascii.arrays) EXPECT_EQ(a.format, "ascii") << a.name;
  const size_t n_points = std::stoul(binary.piece.at("NumberOfPoints"));
  ASSERT_EQ(binary.array("Points").values.size(), 3 * n_points);
  ASSERT_EQ(binary.array("displacement").values.size(), 3 * n_points);
  double largest = 0;
  for (double v : binary.array("displacement").values) largest = std::max(largest, std::abs(v));
  EXPECT_GT(largest, 1.0) << "the tip deflects by about a third of the length 10";

  ASSERT_EQ(binary.arrays.size(), ascii.arrays.size());
  for (size_t k = 0; k < binary.arrays.size(); ++k) {
    const auto &b = binary.arrays[k], &a = ascii.arrays[k];
    SCOPED_TRACE(a.name);
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.type, a.type);
    EXPECT_EQ(b.n_components, a.n_components);
    ASSERT_EQ(b.values.size(), a.values.size());
    size_t differ = 0, first = 0;
    for (size_t i = 0; i < a.values.size(); ++i)
      if (!(std::abs(b.values[i] - a.values[i]) <= 1e-9 * std::abs(a.values[i])) && differ++ == 0) first = i;
    EXPECT_EQ(differ, 0u) << "first at " << first << ": binary " << b.values[first] << ", ascii " << a.values[first];
  }
  // Measured: 49 224 bytes against 100 668 (0.49); doubles barely compress, the integers do.
  EXPECT_LT(fs::file_size(binary_path), 0.75 * fs::file_size(ascii_path));
}

}  // namespace

TEST_F(StictionCli, UnreadableRecordIsAnError) {
  expect_error(CliRun::of({"replay", (dir_ / "no-such-record").string()}, dir_), 2, {"no-such-record", "not a directory"});
  fs::create_directories(dir_ / "record" / "system-001-01");
  expect_error(CliRun::of({"replay", (dir_ / "record").string()}, dir_), 2, {"unreadable record", "metadata.json"});
}

// A replay solves to the recorded Krylov tolerance (the CSV's krylov_rtol), unless the
// command line names the backend's own; a tolerance that is not one is an input error.
TEST_F(StictionCli, RecordThenReplayWithAnotherBackend) {
  const CliRun rec = solve("cantilever-2d", {"--record", (dir_ / "rec").string(), "--no-vtu", "--solver", "schur-amg",
                                             "--set", "newton.krylov_rtol=1e-7"});
  ASSERT_EQ(rec.exit_code, 0) << rec.err;
  EXPECT_FALSE(fs::exists(dir_ / "out" / "step-001.vtu"));
  const auto replay = [&](const std::string& csv, std::vector<std::string> extra) {
    std::vector<std::string> args{"replay", (dir_ / "rec").string(), "--solver", "schur-lu", "--csv",
                                  (dir_ / csv).string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return CliRun::of(args, dir_);
  };
  const auto rtol_column = [&](const std::string& csv) {
    std::vector<std::string> values;
    for (const auto& row : stiction::harness::read_csv((dir_ / csv).string()).rows) values.push_back(row.at("krylov_rtol"));
    return values;
  };
  const CliRun rep = replay("replay.csv", {});
  EXPECT_EQ(rep.exit_code, 0) << rep.err;
  const auto recorded = rtol_column("replay.csv");
  ASSERT_GE(recorded.size(), 2u);
  for (const auto& v : recorded) EXPECT_EQ(v, "1e-07");
  const CliRun own = replay("own.csv", {"-schur_lu_ksp_rtol", "1e-3"});
  EXPECT_EQ(own.exit_code, 0) << own.err;
  EXPECT_EQ(rtol_column("own.csv"), std::vector<std::string>(recorded.size(), ""));
  expect_error(replay("bad.csv", {"--krylov-rtol", "tight"}), 2, {"--krylov-rtol 'tight'"});
}

// The git revision in a run's header is the one the binary was built from, known without
// asking git at run time: with a git that fails first on PATH (a binary copied to a
// machine without the checkout) the header still names it.
TEST_F(StictionCli, RunHeaderNamesTheRevisionTheBinaryWasBuiltFrom) {
  const std::string built = stiction::harness::build_revision();
  if (built == "unknown") GTEST_SKIP() << "built outside a git checkout";
  fs::create_directories(dir_ / "bin");
  std::ofstream(dir_ / "bin" / "git") << "#!/bin/sh\nexit 1\n";
  fs::permissions(dir_ / "bin" / "git", fs::perms::owner_all);
  const std::string command = "cd " + shell_quote(dir_.string()) + " && PATH=" + shell_quote((dir_ / "bin").string()) +
                              ":\"$PATH\" " + without_mpi_environment() + " " + shell_quote(STICTION_BINARY) +
                              " solve cantilever-2d --quiet --no-vtu --out out > stdout.txt 2> stderr.txt";
  ASSERT_EQ(std::system(command.c_str()), 0) << read_file(dir_ / "stderr.txt");
  std::ifstream steps(dir_ / "out" / "steps.csv");
  std::string line;
  bool found = false;
  while (std::getline(steps, line))
    if (line.rfind("# git revision: ", 0) == 0) {
      found = true;
      // A hash, though git cannot be asked (the build's, not necessarily this test binary's).
      EXPECT_TRUE(std::regex_search(line, std::regex("^# git revision: [0-9a-f]{12}"))) << line;
    }
  EXPECT_TRUE(found) << "no git revision line in steps.csv";
}

// The Krylov tolerance of a run: --krylov-rtol first, then a -<backend>_ksp_rtol given on the
// command line, then the scene's newton.krylov_rtol, then the backend's options file (1e-4).
// The run header says which applies, and the solves meet it.
TEST_F(StictionCli, KrylovToleranceComesFromTheCommandLineThenTheSceneThenTheBackend) {
  const fs::path scene = SceneVariant().append("\n[newton]\nkrylov_rtol = 1e-7\n").write(dir_, "tight.toml");
  auto header_line = [&](const std::string& out) {
    std::ifstream steps(dir_ / out / "steps.csv");
    for (std::string line; std::getline(steps, line);)
      if (line.rfind("# solver: ", 0) == 0) return line;
    return std::string("no solver line in ") + out + "/steps.csv";
  };
  auto worst_relative_residual = [&](const std::string& out) {
    const auto rows = stiction::harness::read_csv((dir_ / out / "iterations.csv").string()).rows;
    EXPECT_FALSE(rows.empty()) << out;
    double worst = 0;
    for (const auto& row : rows) worst = std::max(worst, stiction::harness::number(row, "linear_relative_residual"));
    return worst;
  };
  const std::vector<std::string> common{"solve", scene.string(), "--solver", "schur-amg", "--quiet", "--no-vtu"};
  auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> args = common;
    args.insert(args.end(), more.begin(), more.end());
    return args;
  };

  ASSERT_EQ(CliRun::of(with({"--out", "scene"}), dir_).exit_code, 0);
  EXPECT_NE(header_line("scene").find("krylov rtol 1e-07 (scene)"), std::string::npos) << header_line("scene");
  EXPECT_LE(worst_relative_residual("scene"), 1e-7);

  const CliRun option = CliRun::of(with({"--out", "option", "-schur_amg_ksp_rtol", "1e-3"}), dir_);
  ASSERT_EQ(option.exit_code, 0) << option.err;
  EXPECT_NE(header_line("option").find("krylov rtol the backend's"), std::string::npos) << header_line("option");
  EXPECT_GT(worst_relative_residual("option"), 1e-7) << "the command line's 1e-3 applies";

  ASSERT_EQ(CliRun::of(with({"--out", "flag", "--krylov-rtol", "1e-5", "-schur_amg_ksp_rtol", "1e-3"}), dir_).exit_code, 0);
  EXPECT_NE(header_line("flag").find("krylov rtol 1e-05 (--krylov-rtol)"), std::string::npos) << header_line("flag");
  EXPECT_LE(worst_relative_residual("flag"), 1e-5);
  EXPECT_GT(worst_relative_residual("flag"), 1e-7);
}

// The GMRES restart of a run: a -<backend>_ksp_gmres_restart given by the user first, then
// the scene's newton.krylov_restart, then the backend's options file (100). The run header
// says which applies, every solve records the restart its KSP ran, and the run's recorded
// backend options give it (the sweep report compares levels by them).
TEST_F(StictionCli, KrylovRestartComesFromTheCommandLineThenTheSceneThenTheBackend) {
  const fs::path scene = SceneVariant().append("\n[newton]\nkrylov_restart = 7\n").write(dir_, "restart.toml");
  struct Ran {
    std::string header, settings;
    std::set<double> restarts;  // the ksp_gmres_restart of the solves
    size_t solves = 0;
  };
  auto run = [&](const std::string& scene_name, const std::string& solver, std::vector<std::string> more) {
    const std::string out = solver + "-" + std::to_string(more.size()) + "-" + fs::path(scene_name).stem().string();
    std::vector<std::string> args{"solve", scene_name, "--solver", solver, "--quiet", "--no-vtu", "--out", out,
                                  "--metrics", (dir_ / (out + ".toml")).string()};
    args.insert(args.end(), more.begin(), more.end());
    const CliRun r = CliRun::of(args, dir_);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    Ran ran;
    std::ifstream steps(dir_ / out / "steps.csv");
    for (std::string line; std::getline(steps, line);)
      if (line.rfind("# solver: ", 0) == 0) ran.header = line;
    const toml::table metrics = toml::parse_file((dir_ / (out + ".toml")).string());
    ran.settings = stiction::harness::effective_backend_settings(
        metrics["run"]["backend_options"].value_or(std::string()), solver);
    if (const auto* solves = metrics["linear_solve"].as_array())
      for (const auto& s : *solves) {
        ++ran.solves;
        if (const auto m = (*s.as_table())["ksp_gmres_restart"].value<double>()) ran.restarts.insert(*m);
      }
    return ran;
  };

  const Ran from_scene = run(scene.string(), "schur-amg", {});
  EXPECT_NE(from_scene.header.find("gmres restart 7 (scene)"), std::string::npos) << from_scene.header;
  ASSERT_GT(from_scene.solves, 0u);
  EXPECT_EQ(from_scene.restarts, std::set<double>{7});
  EXPECT_NE(from_scene.settings.find("-ksp_gmres_restart 7 "), std::string::npos) << from_scene.settings;

  const Ran from_user = run(scene.string(), "schur-amg", {"-schur_amg_ksp_gmres_restart", "12"});
  EXPECT_NE(from_user.header.find("gmres restart the backend's"), std::string::npos) << from_user.header;
  EXPECT_EQ(from_user.restarts, std::set<double>{12});
  EXPECT_NE(from_user.settings.find("-ksp_gmres_restart 12 "), std::string::npos) << from_user.settings;

  const Ran from_backend = run("cantilever-2d", "schur-amg", {});
  EXPECT_EQ(from_backend.restarts, std::set<double>{100});
  EXPECT_NE(from_backend.settings.find("-ksp_gmres_restart 100 "), std::string::npos) << from_backend.settings;

  // A direct backend has no restart: the scene's is neither announced nor recorded.
  const Ran direct = run(scene.string(), "lu-mumps", {});
  EXPECT_NE(direct.header.find("gmres restart the backend's"), std::string::npos) << direct.header;
  ASSERT_GT(direct.solves, 0u);
  EXPECT_TRUE(direct.restarts.empty());
  EXPECT_EQ(direct.settings.find("gmres_restart"), std::string::npos) << direct.settings;
}

// The speed/accuracy sweep on a scene without contact, short: a lu-mumps reference with a
// tight Newton tolerance, then schur-amg and lu-mumps at a loose Newton tolerance (1e-2)
// with Krylov tolerances 1e-2 to 1e-6. What must hold whatever the tuning: every row ends
// with a named status; at a fixed Newton tolerance the displacement error falls as the
// Krylov tolerance tightens, until it meets that of exact solves at the same Newton
// tolerance (lu-mumps); the report names the Pareto front and a recommendation, and
// `stiction report` rebuilds it from the CSV alone.
TEST_F(StictionCli, TradeoffErrorFallsWithTheKrylovToleranceUntilItMeetsTheNewtonTolerance) {
  const std::vector<std::string> arguments{"tradeoff", "cantilever-2d", "--solvers", "schur-amg,lu-mumps",
                                           "--newton-rtols", "1e-2", "--krylov-rtols", "1e-2,1e-4,1e-6",
                                           "--knob", "schur_amg_qq_pc_sor_its=2", "--discretisation", "--out",
                                           "sweep"};
  const CliRun sweep = CliRun::of(arguments, dir_);
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  const auto rows = stiction::harness::read_csv((dir_ / "sweep" / "tradeoff.csv").string()).rows;
  ASSERT_EQ(rows.size(), 9u)
      << "references at levels 0 and 1, two defaults, three schur-amg settings, a knob, one lu-mumps setting";
  EXPECT_EQ(rows.at(0).at("id"), "reference");
  EXPECT_EQ(rows.at(1).at("id"), "reference-L1");
  std::map<std::string, double> error;
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("status"), "ok") << row.at("id") << ": " << row.at("detail");
    if (row.at("id").rfind("reference", 0) != 0) error[row.at("id")] = stiction::harness::number(row, "error_u_h1");
  }
  const double loose = error.at("schur-amg-fixed-newton0.01-krylov0.01"),
               middle = error.at("schur-amg-fixed-newton0.01-krylov0.0001"),
               tight = error.at("schur-amg-fixed-newton0.01-krylov1e-06"),
               exact = error.at("lu-mumps-fixed-newton0.01");
  EXPECT_GT(loose, 10 * tight);
  EXPECT_GE(loose, middle);
  EXPECT_GE(middle, tight);
  EXPECT_NEAR(tight, exact, exact) << "at Krylov 1e-6 the Newton tolerance decides the error";
  EXPECT_LT(error.at("lu-mumps-default"), 1e-9) << "the defaults (Newton 1e-8) against the reference";
  EXPECT_LT(error.at("schur-amg-schur_amg_qq_pc_sor_its=2"), 1e-6) << "a knob at the default tolerances";

  // The mesh changes the answer by far more than the tolerances do here.
  const auto levels = stiction::harness::read_csv((dir_ / "sweep" / "discretisation.csv").string()).rows;
  ASSERT_EQ(levels.size(), 1u);
  EXPECT_GT(stiction::harness::number(levels[0], "displacement_h1"), 10 * error.at("lu-mumps-default"));

  const std::string report = read_file(dir_ / "sweep" / "report.md");
  EXPECT_NE(report.find("## What the mesh changes"), std::string::npos);
  EXPECT_NE(report.find("## Pareto front"), std::string::npos);
  EXPECT_NE(report.find("at most 0.01: `stiction solve cantilever-2d"), std::string::npos) << report;
  fs::remove(dir_ / "sweep" / "report.md");
  ASSERT_EQ(CliRun::of({"report", (dir_ / "sweep").string()}, dir_).exit_code, 0);
  EXPECT_EQ(read_file(dir_ / "sweep" / "report.md"), report);

  std::vector<std::string> resumed = arguments;
  resumed.push_back("--resume");
  const CliRun again = CliRun::of(resumed, dir_);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(stiction::harness::read_csv((dir_ / "sweep" / "tradeoff.csv").string()).rows.size(), 9u)
      << "a resumed sweep reruns nothing that finished";

  const CliRun unknown = CliRun::of({"tradeoff", "cantilever-2d", "--solvers", "no-such", "--out", "bad"}, dir_);
  EXPECT_EQ(unknown.exit_code, 2);
  ASSERT_EQ(unknown.error_lines().size(), 1u) << unknown.err;
  EXPECT_NE(unknown.error_lines()[0].find("unknown solver backend 'no-such'"), std::string::npos);
  const CliRun stray = CliRun::of({"tradeoff", "cantilever-2d", "--knob", "lu_mumps_mat_mumps_icntl_14=50", "--out", "bad"}, dir_);
  EXPECT_EQ(stray.exit_code, 2);
  ASSERT_EQ(stray.error_lines().size(), 1u) << stray.err;
  EXPECT_NE(stray.error_lines()[0].find("prefix of none of the backends"), std::string::npos) << stray.err;
}

// --set KEY=VALUE edits a scene key for one run, validated as the file would be: friction on
// the frictionless hertz-cylinder-2d makes nodes stick and slip; a misspelt key, a missing
// array entry and a value that is not TOML are bad input with one message each.
TEST_F(StictionCli, SetChangesASceneKeyForOneRun) {
  ASSERT_EQ(CliRun::of({"solve", "hertz-cylinder-2d", "--quiet", "--no-vtu", "--out", "plain"}, dir_).exit_code, 0);
  const CliRun rough = CliRun::of({"solve", "hertz-cylinder-2d", "--quiet", "--no-vtu", "--out", "rough", "--set",
                                   "contact[0].friction=0.3", "--set", "newton.max_iterations=40"},
                                  dir_);
  ASSERT_EQ(rough.exit_code, 0) << rough.err;
  auto sticking = [&](const std::string& out) {
    const auto rows = stiction::harness::read_csv((dir_ / out / "steps.csv").string()).rows;
    EXPECT_FALSE(rows.empty());
    return rows.empty() ? -1.0 : stiction::harness::number(rows.back(), "contact_ground_stick");
  };
  EXPECT_EQ(sticking("plain"), 0);
  EXPECT_GT(sticking("rough"), 0);
  for (const auto& [set, message] : {std::pair{"contact[0].frction=0.3", "unknown key"},
                                     std::pair{"contact[3].friction=0.3", "the scene has no contact[3]"},
                                     std::pair{"newton.rtol=abc", "the value is not TOML"}}) {
    const CliRun bad = CliRun::of({"solve", "hertz-cylinder-2d", "--quiet", "--no-vtu", "--out", "bad", "--set", set}, dir_);
    EXPECT_EQ(bad.exit_code, 2) << set;
    ASSERT_EQ(bad.error_lines().size(), 1u) << bad.err;
    EXPECT_NE(bad.error_lines()[0].find(message), std::string::npos) << bad.err;
  }
}

// The stability atlas, short: hertz-cylinder-2d with friction 0 and 1 and with one or three
// Newton iterations per increment allowed, for schur-amg and boomeramg (which cannot solve a
// contact system). Whatever the tuning, every cell ends converged or with a named reason and
// exit code 3, no output holds a NaN, and the report says no cell broke what must hold; a
// converged cell says how many increments were cut (schur-amg with three iterations to the
// Newton tolerance 1e-8: two, the steps.csv of `stiction solve hertz-cylinder-2d --set
// newton.max_iterations=3 --set newton.rtol=1e-8`); a cell stopped by the time limit is a
// hang, and the report names it.
TEST_F(StictionCli, AtlasNamesEveryCellsEndAndReportsAHang) {
  const CliRun atlas = CliRun::of({"atlas", "hertz-cylinder-2d", "--solvers", "schur-amg,boomeramg", "--axis",
                                   "contact[0].friction=0,1", "--axis", "newton.max_iterations=1,3", "--set",
                                   "newton.rtol=1e-8", "--out", "atlas"},
                                  dir_);
  ASSERT_EQ(atlas.exit_code, 0) << atlas.err;
  const auto rows = stiction::harness::read_csv((dir_ / "atlas" / "atlas.csv").string()).rows;
  ASSERT_EQ(rows.size(), 8u);
  int converged = 0, failed = 0;
  for (const auto& row : rows) {
    SCOPED_TRACE(row.at("axis") + " = " + row.at("value") + ", " + row.at("solver"));
    EXPECT_TRUE(row.at("status") == "ok" || row.at("status") == "newton-failed") << row.at("status");
    EXPECT_EQ(row.at("exit_code"), row.at("status") == "ok" ? "0" : "3");
    EXPECT_FALSE(row.at("reason").empty());
    EXPECT_EQ(row.at("nan_in_output"), "0");
    EXPECT_EQ(row.at("violation"), "");
    (row.at("status") == "ok" ? converged : failed) += 1;
  }
  EXPECT_GE(converged, 3) << "schur-amg converges with friction 0 and 1 and with three iterations";
  EXPECT_GE(failed, 4) << "boomeramg on every cell";
  const std::string report = read_file(dir_ / "atlas" / "report.md");
  EXPECT_NE(report.find("None: every cell converged or named why"), std::string::npos) << report;
  EXPECT_NE(report.find(", 2 cut |"), std::string::npos) << report;
  EXPECT_NE(report.find("## contact[0].friction"), std::string::npos);
  // GMRES's conditioning estimate: per converged cell, and in the reason of a failed one
  // (schur-amg stopped after one Newton iteration).
  EXPECT_NE(report.find("Largest conditioning estimate of the preconditioned operator"), std::string::npos) << report;
  EXPECT_NE(report.find("preconditioned operator's condition estimate"), std::string::npos) << report;
  fs::remove(dir_ / "atlas" / "report.md");
  ASSERT_EQ(CliRun::of({"report", (dir_ / "atlas").string()}, dir_).exit_code, 0);
  EXPECT_EQ(read_file(dir_ / "atlas" / "report.md"), report);

  const CliRun slow = CliRun::of({"atlas", "hertz-cylinder-2d", "--solvers", "schur-amg", "--axis", "level=3",
                                  "--time-limit", "1", "--out", "slow"},
                                 dir_);
  ASSERT_EQ(slow.exit_code, 0) << slow.err;
  const auto slow_rows = stiction::harness::read_csv((dir_ / "slow" / "atlas.csv").string()).rows;
  ASSERT_EQ(slow_rows.size(), 1u);
  EXPECT_EQ(slow_rows[0].at("status"), "time-limit");
  EXPECT_EQ(slow_rows[0].at("violation"), "hang");
  EXPECT_NE(read_file(dir_ / "slow" / "report.md").find("**hang**"), std::string::npos);

  const CliRun misspelt = CliRun::of({"atlas", "hertz-cylinder-2d", "--axis", "contact[0].frction=1", "--out", "bad"}, dir_);
  EXPECT_EQ(misspelt.exit_code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "bad" / "atlas.csv")) << "refused before any cell ran";
}

// Every run row names the ordering MUMPS ran and the Newton test it used; a sweep written
// before the ordering column existed is resumed with the column added (empty in its rows,
// which keep their values; its steps.csv likewise), and one with a column this version does
// not write is refused.
TEST_F(StictionCli, BenchRowsNameTheMumpsOrderingAndResumeAnOlderSweep) {
  const std::vector<std::string> bench = {"bench", "--scenes", "cantilever-2d", "--solvers", "lu-mumps", "--quick"};
  auto with_out = [&](const std::string& out, bool resume) {
    std::vector<std::string> args = bench;
    args.insert(args.end(), {"--out", (dir_ / out).string()});
    if (resume) args.push_back("--resume");
    return CliRun::of(args, dir_);
  };
  const CliRun fresh = with_out("sweep", false);
  ASSERT_EQ(fresh.exit_code, 0) << fresh.err;
  const auto table = stiction::harness::read_csv((dir_ / "sweep" / "runs.csv").string());
  ASSERT_EQ(table.rows.size(), 1u);
  EXPECT_EQ(table.rows[0].at("mumps_ordering"), "PORD") << "Debian's MUMPS orders with PORD";
  // The Newton test the run stopped at, and its forcing: cantilever-2d keeps the defaults.
  EXPECT_EQ(table.rows[0].at("newton_rtol"), "1e-06");
  EXPECT_EQ(table.rows[0].at("newton_forcing"), "fixed");

  // A table as an older version wrote it: `table` without `column`, first row only; returns
  // its header.
  auto write_without = [&](const stiction::harness::CsvTable& t, const std::string& column, const fs::path& path) {
    std::string header, row;
    for (const auto& c : t.columns)
      if (c != column) {
        header += (header.empty() ? "" : ",") + c;
        row += (row.empty() ? "" : ",") + t.rows[0].at(c);
      }
    std::ofstream(path) << "# an older sweep\n" << header << "\n" << row << "\n";
    return header;
  };
  // The resumed sweep's table at `path` has `t`'s columns again, `column` empty in its one
  // row and every other value kept.
  auto expect_upgraded = [&](const fs::path& path, const stiction::harness::CsvTable& t, const std::string& column) {
    const auto upgraded = stiction::harness::read_csv(path.string());
    EXPECT_EQ(upgraded.columns, t.columns) << path;
    ASSERT_EQ(upgraded.rows.size(), 1u) << path;
    EXPECT_EQ(upgraded.rows[0].at(column), "") << path;
    for (const auto& c : t.columns)
      if (c != column) {
        EXPECT_EQ(upgraded.rows[0].at(c), t.rows[0].at(c)) << path << ": " << c;
      }
  };
  // The same sweep as an older version wrote it: runs.csv without the mumps_ordering column,
  // steps.csv without the processes column.
  fs::create_directories(dir_ / "old");
  const std::string old_header = write_without(table, "mumps_ordering", dir_ / "old" / "runs.csv");
  const auto steps = stiction::harness::read_csv((dir_ / "sweep" / "steps.csv").string());
  ASSERT_FALSE(steps.rows.empty());
  write_without(steps, "processes", dir_ / "old" / "steps.csv");
  const CliRun resumed = with_out("old", true);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  expect_upgraded(dir_ / "old" / "runs.csv", table, "mumps_ordering");  // the finished run was not run again
  expect_upgraded(dir_ / "old" / "steps.csv", steps, "processes");  // the lines a resumed sweep appends match

  fs::create_directories(dir_ / "other");
  std::ofstream(dir_ / "other" / "runs.csv") << old_header << ",a_column_from_elsewhere\n";
  const CliRun refused = with_out("other", true);
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_EQ(refused.error_lines().size(), 1u) << refused.err;
}

// A row gives the factor entries MUMPS stored over its full-rank estimate: the block low-rank
// compression of lu-mumps-blr (0.67 on block-compression level 0, the whole run), about 1
// for the full-rank lu-mumps, and nothing for a backend without a MUMPS factorisation.
TEST_F(StictionCli, BenchRowsGiveTheBlockLowRankCompressionOfTheFactors) {
  const CliRun sweep = CliRun::of({"bench", "--scenes", "block-compression", "--solvers", "lu-mumps,lu-mumps-blr,gamg",
                                   "--quick", "--out", (dir_ / "sweep").string()},
                                  dir_);
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  std::map<std::string, std::string> fraction;
  for (const auto& row : stiction::harness::read_csv((dir_ / "sweep" / "runs.csv").string()).rows)
    fraction[row.at("solver")] = row.at("mumps_factor_fraction");
  ASSERT_EQ(fraction.size(), 3u);
  EXPECT_NEAR(std::stod(fraction["lu-mumps"]), 1.0, 0.05);
  EXPECT_LT(std::stod(fraction["lu-mumps-blr"]), 0.9);
  EXPECT_EQ(fraction["gamg"], "");
}

// A row names the PETSc options the sweep gave its backend beyond the defaults, and the
// report shows them beside the status, so that rows run with other settings are told apart.
TEST_F(StictionCli, BenchRowsNameThePetscOptionsTheirBackendRanWith) {
  const CliRun sweep = CliRun::of({"bench", "--scenes", "cantilever-2d", "--solvers", "lu-mumps,lu-umfpack", "--quick",
                                   "--out", (dir_ / "sweep").string(), "-lu_mumps_mat_mumps_icntl_14", "40"},
                                  dir_);
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  std::map<std::string, std::string> options;
  for (const auto& row : stiction::harness::read_csv((dir_ / "sweep" / "runs.csv").string()).rows)
    options[row.at("solver")] = row.at("petsc_options");
  ASSERT_EQ(options.size(), 2u);
  EXPECT_EQ(options["lu-mumps"], "-lu_mumps_mat_mumps_icntl_14 40");
  EXPECT_EQ(options["lu-umfpack"], "");
  const std::string report = read_file(dir_ / "sweep" / "report.md");
  EXPECT_NE(report.find("| lu-mumps | ok (-lu_mumps_mat_mumps_icntl_14 40) |"), std::string::npos) << report;
  EXPECT_NE(report.find("| lu-umfpack | ok |"), std::string::npos) << report;
}

// A pair of keys is swept together: every value of one with every value of the other, each
// cell's run getting both settings (friction changes the Newton count of the converged cells,
// one Newton iteration fails every cell), and the report shows one grid per backend.
TEST_F(StictionCli, AtlasSweepsAPairOfKeysTogether) {
  const CliRun atlas = CliRun::of({"atlas", "hertz-cylinder-2d", "--solvers", "lu-mumps", "--pair",
                                   "contact[0].friction=0,1", "newton.max_iterations=1,3", "--out", "pair"},
                                  dir_);
  ASSERT_EQ(atlas.exit_code, 0) << atlas.err;
  std::map<std::string, std::map<std::string, std::string>> by_value;
  for (const auto& row : stiction::harness::read_csv((dir_ / "pair" / "atlas.csv").string()).rows) {
    EXPECT_EQ(row.at("axis"), "contact[0].friction & newton.max_iterations");
    by_value[row.at("value")] = row;
  }
  ASSERT_EQ(by_value.size(), 4u);
  for (const char* one_iteration : {"0 & 1", "1 & 1"}) {
    ASSERT_TRUE(by_value.count(one_iteration)) << one_iteration;
    EXPECT_EQ(by_value[one_iteration].at("reason"), "DIVERGED_MAX_ITERATIONS") << one_iteration;
  }
  ASSERT_TRUE(by_value.count("0 & 3") && by_value.count("1 & 3"));
  EXPECT_EQ(by_value["0 & 3"].at("status"), "ok");
  EXPECT_EQ(by_value["1 & 3"].at("status"), "ok");
  EXPECT_NE(by_value["0 & 3"].at("newton_iterations"), by_value["1 & 3"].at("newton_iterations"))
      << "the friction setting did not reach the runs";
  const std::string report = read_file(dir_ / "pair" / "report.md");
  EXPECT_NE(report.find("### lu-mumps: contact[0].friction (rows) x newton.max_iterations (columns)"), std::string::npos)
      << report;
  EXPECT_TRUE(fs::exists(dir_ / "pair" / "atlas-axis-0.svg") || report.find("Heat map not drawn") != std::string::npos);
  // A failed lu-mumps cell names MUMPS's pivoting in its last solve (contact rows: delayed pivots).
  EXPECT_NE(report.find("MUMPS delayed"), std::string::npos) << report;

  const CliRun same_key = CliRun::of({"atlas", "hertz-cylinder-2d", "--pair", "contact[0].friction=0,1",
                                      "contact[0].friction=2", "--out", "bad"},
                                     dir_);
  EXPECT_EQ(same_key.exit_code, 2) << same_key.err;
  EXPECT_EQ(same_key.error_lines().size(), 1u) << same_key.err;
  const CliRun one_axis = CliRun::of({"atlas", "hertz-cylinder-2d", "--pair", "contact[0].friction=0,1", "--out", "bad"}, dir_);
  EXPECT_EQ(one_axis.exit_code, 2) << one_axis.err;
  EXPECT_FALSE(fs::exists(dir_ / "bad" / "atlas.csv")) << "refused before any cell ran";
  // A second --pair is read as a pair of its own: its misspelt key is named.
  const CliRun second_pair = CliRun::of({"atlas", "hertz-cylinder-2d", "--pair", "contact[0].friction=0,1",
                                         "newton.max_iterations=3", "--pair", "contact[0].friction=1",
                                         "newton.max_iteratons=3", "--out", "bad"},
                                        dir_);
  EXPECT_EQ(second_pair.exit_code, 2) << second_pair.err;
  EXPECT_NE(second_pair.err.find("max_iteratons"), std::string::npos) << second_pair.err;
  EXPECT_FALSE(fs::exists(dir_ / "bad" / "atlas.csv")) << "refused before any cell ran";
}

// On a scene that models an analytic solution the sweep also compares each run with it,
// the reference's own figures included; on other scenes those columns stay empty.
// hertz-cylinder-2d level 0 fits the half-width and the peak pressure within 0.3%
// (Hertz2D.CylinderOnRigidPlaneConvergesToHertz: 0.18% and 0.13%). The patch test carries
// its uniform pressure to round-off with exact solves (ContactPatch.*: 1e-8) and further
// from it with a loose Krylov tolerance. cattaneo-mindlin-2d level 0 places the stick-zone
// edge within 2% of the contact half-width of Mindlin's (Friction.CattaneoMindlin*'s bound;
// measured 0.7%).
TEST_F(StictionCli, TradeoffComparesScenesWithTheirAnalyticSolutions) {
  using stiction::harness::number;
  const auto sweep = [&](const std::string& scene, const std::string& krylov_rtols) {
    const CliRun run = CliRun::of({"tradeoff", scene, "--solvers", "schur-amg", "--newton-rtols", "1e-8",
                                   "--krylov-rtols", krylov_rtols, "--out", scene},
                                  dir_);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return stiction::harness::read_csv((dir_ / scene / "tradeoff.csv").string()).rows;
  };
  const auto hertz = sweep("hertz-cylinder-2d", "1e-6");
  ASSERT_EQ(hertz.size(), 3u);
  for (const auto& row : hertz) {
    SCOPED_TRACE(row.at("id"));
    ASSERT_FALSE(row.at("error_hertz_a").empty());
    EXPECT_GT(number(row, "error_hertz_a"), 0);
    EXPECT_LT(number(row, "error_hertz_a"), 3e-3);
    EXPECT_LT(number(row, "error_hertz_p0"), 3e-3);
    EXPECT_TRUE(row.at("error_stick_zone").empty());
    EXPECT_TRUE(row.at("error_patch_pressure").empty());
  }

  const auto patch = sweep("contact-patch-2d", "1e-1,1e-10");  // reference, default, loose, tight
  ASSERT_EQ(patch.size(), 4u);
  for (const auto& row : patch) ASSERT_FALSE(row.at("error_patch_pressure").empty()) << row.at("id");
  EXPECT_LT(number(patch[0], "error_patch_pressure"), 1e-8);
  EXPECT_LT(number(patch[3], "error_patch_pressure"), 1e-8);
  EXPECT_GT(number(patch[2], "error_patch_pressure"), 10 * number(patch[3], "error_patch_pressure"));
  EXPECT_TRUE(patch[0].at("error_hertz_a").empty());

  const auto mindlin = sweep("cattaneo-mindlin-2d", "1e-6");
  ASSERT_EQ(mindlin.size(), 3u);
  for (const auto& row : mindlin) {
    SCOPED_TRACE(row.at("id"));
    ASSERT_FALSE(row.at("error_stick_zone").empty());
    EXPECT_GT(number(row, "error_stick_zone"), 0);
    EXPECT_LT(number(row, "error_stick_zone"), 0.02);
  }

  const CliRun plain = CliRun::of({"tradeoff", "cantilever-2d", "--solvers", "lu-mumps", "--newton-rtols", "1e-8",
                                   "--out", "plain"},
                                  dir_);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  for (const auto& row : stiction::harness::read_csv((dir_ / "plain" / "tradeoff.csv").string()).rows)
    for (const char* column : {"error_hertz_a", "error_stick_zone", "error_patch_pressure"})
      EXPECT_TRUE(row.at(column).empty()) << row.at("id") << " " << column;
}

// The mesh as a knob: with --coarser-levels each backend also runs at its defaults on the
// coarser meshes, compared with the reference across meshes. hertz-cylinder-2d level 0
// against level 1 (measured): contact force 2.3e-4, the difference of |u|_H1 6.1e-5, Hertz a
// 1.8e-3; those rows stay off the Pareto front, and a level not below --level is refused.
TEST_F(StictionCli, TradeoffRunsTheBackendsOnCoarserMeshes) {
  using stiction::harness::number;
  const CliRun sweep = CliRun::of({"tradeoff", "hertz-cylinder-2d", "--level", "1", "--coarser-levels", "0", "--solvers",
                                   "schur-amg", "--newton-rtols", "1e-8", "--krylov-rtols", "1e-6", "--out", "mesh"},
                                  dir_);
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  const auto rows = stiction::harness::read_csv((dir_ / "mesh" / "tradeoff.csv").string()).rows;
  ASSERT_EQ(rows.size(), 4u);
  const auto& coarse = rows.back();
  EXPECT_EQ(coarse.at("id"), "L0-schur-amg-default");
  EXPECT_EQ(coarse.at("level"), "0");
  ASSERT_EQ(coarse.at("status"), "ok");
  EXPECT_GT(number(coarse, "error_contact_force"), 1e-5);
  EXPECT_LT(number(coarse, "error_contact_force"), 1e-2);
  EXPECT_GT(number(coarse, "error_u_h1"), 0);
  EXPECT_LT(number(coarse, "error_hertz_a"), 3e-3);
  EXPECT_TRUE(coarse.at("state_changes").empty()) << "states are not compared across meshes";
  const std::string report = read_file(dir_ / "mesh" / "report.md");
  const auto knob = report.find("## The mesh as a knob"), front = report.find("## Pareto front");
  ASSERT_NE(knob, std::string::npos) << report;
  ASSERT_NE(front, std::string::npos) << report;
  EXPECT_EQ(report.find("L0-schur-amg-default", front), std::string::npos) << "off the front";

  const CliRun same = CliRun::of({"tradeoff", "hertz-cylinder-2d", "--level", "1", "--coarser-levels", "1", "--out",
                                  "bad"},
                                 dir_);
  EXPECT_EQ(same.exit_code, 2) << same.err;
  EXPECT_NE(same.err.find("not below --level"), std::string::npos) << same.err;
}

// With a memory limit in the environment (as `stiction bench` sets for its runs), the
// MUMPS backends compare MUMPS's estimate after analysis with what the process may still
// use and refuse a factorisation that would not fit: a named failure with the estimate,
// exit 3. lu-mumps-blr's estimate is the one with compressed factors, INFOG(37). 50 MB is
// less than the process holds before the first factorisation; 100 GB lets it factorise.
// The refused run's record still names the ordering MUMPS's analysis ran (PORD, code 4)
// and the factor entries it estimated, from the guard's own analysis.
TEST_F(StictionCli, MumpsBackendsRefuseAFactorisationBeyondTheMemoryLimit) {
  for (const auto& [backend, estimate] : {std::pair{"lu-mumps", "INFOG(17)"}, std::pair{"lu-mumps-blr", "INFOG(37)"}}) {
    SCOPED_TRACE(backend);
    const fs::path metrics = dir_ / (std::string(backend) + "-refused.toml");
    setenv("STICTION_MEMORY_LIMIT_MB", "50", 1);
    const CliRun refused = solve("cantilever-2d", {"--solver", backend, "--metrics", metrics.string()});
    setenv("STICTION_MEMORY_LIMIT_MB", "100000", 1);
    const CliRun fits = solve("cantilever-2d", {"--solver", backend});
    unsetenv("STICTION_MEMORY_LIMIT_MB");
    expect_error(refused, 3, {"PC_SETUP_FAILED", "MUMPS estimates", estimate, "limit 50 MB"});
    EXPECT_EQ(fits.exit_code, 0) << fits.err;
    const toml::table record = toml::parse_file(metrics.string());
    const auto* first_solve = record["linear_solve"][0].as_table();
    ASSERT_NE(first_solve, nullptr);
    EXPECT_EQ((*first_solve)["mumps_ordering"].value_or(-1.0), 4.0) << "the ordering of the guard's analysis";
    EXPECT_GT((*first_solve)["mumps_factor_entries_full_rank"].value_or(0.0), 0.0);
  }
}

// The guard's estimate is MUMPS's analysis with the backend's own ordering (PORD): an upper
// bound of the memory the factorisation then used (INFOG(22)) and within a factor 1.5 of it
// (block-compression level 0: 540 MB estimated, 458 MB used; analysed in the natural order,
// the estimate was 5 811 MB and a level-1 factorisation of 7 GB was refused at 339 GB).
TEST_F(StictionCli, MumpsMemoryEstimateIsThatOfTheFactorisationThatRuns) {
  const fs::path metrics = dir_ / "metrics.toml";
  setenv("STICTION_MEMORY_LIMIT_MB", "100000", 1);
  const CliRun run = solve("block-compression", {"--solver", "lu-mumps", "--until", "0.25", "--no-vtu", "--metrics",
                                                 metrics.string()});
  unsetenv("STICTION_MEMORY_LIMIT_MB");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const toml::table record = toml::parse_file(metrics.string());
  const auto* first_solve = record["linear_solve"][0].as_table();
  ASSERT_NE(first_solve, nullptr);
  const double estimate = (*first_solve)["mumps_estimate_MB"].value_or(0.0);
  const double used = (*first_solve)["mumps_memory_MB"].value_or(0.0);
  ASSERT_GT(used, 100.0);
  EXPECT_GE(estimate, used);
  EXPECT_LE(estimate, 1.5 * used);
}

// MUMPS's pivoting in every lu-mumps solve's record: the multiplier rows of a contact system
// (zero diagonal) have pivots delayed to a parent front (sliding-block-2d --quick: 19-22
// per solve once contact is active), the cantilever's elasticity has none.
TEST_F(StictionCli, MumpsPivotingIsRecordedAndDelaysPivotsOnlyWhereContactRowsAre) {
  const auto largest_delay = [&](const std::string& scene) {
    const fs::path metrics = dir_ / (scene + ".toml");
    const CliRun run = solve(scene, {"--solver", "lu-mumps", "--quick", "--no-vtu", "--metrics", metrics.string()});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    const toml::table record = toml::parse_file(metrics.string());
    const toml::array* solves = record["linear_solve"].as_array();
    double largest = -1;
    if (!solves) return largest;
    for (const auto& s : *solves) {
      const auto* t = s.as_table();
      if (!t || !(*t)["mumps_delayed_pivots"].value<double>() || !(*t)["mumps_off_diagonal_pivots"].value<double>())
        return -1.0;  // a solve without the figures
      largest = std::max(largest, *(*t)["mumps_delayed_pivots"].value<double>());
    }
    return largest;
  };
  EXPECT_GT(largest_delay("sliding-block-2d"), 0);
  EXPECT_EQ(largest_delay("cantilever-2d"), 0);
}

// A run's large arrays (1 MB and more by default) are mapped on their own, so that memory a
// phase frees leaves the process and the peak RSS is what a phase needs
// (common/process_memory.hpp): block-compression's
// matrix and vectors at its first linear solve, backed by transparent huge pages (the run
// re-executed itself with glibc.malloc.hugetlb=1). With STICTION_HOLD_FREED_MEMORY=1 (the
// settings SuperLU_dist's CombBLAS leaves in every program that loads PETSc) none is, and
// freed memory stays resident. The run header names the setting; a threshold glibc would
// refuse is an input error.
TEST_F(StictionCli, LargeArraysAreMappedSoThatFreedMemoryLeavesTheProcess) {
  const auto run = [&](const std::string& name, double* mapped_mb, std::string* header) {
    const fs::path metrics = dir_ / (name + ".toml");
    const CliRun r = solve("block-compression",
                           {"--solver", "schur-amg", "--until", "0.25", "--no-vtu", "--metrics", metrics.string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const toml::table record = toml::parse_file(metrics.string());
    const auto* first_solve = record["linear_solve"][0].as_table();
    ASSERT_NE(first_solve, nullptr);
    *mapped_mb = (*first_solve)["memory_mapped_MB"].value_or(-1.0);
    std::ifstream steps(dir_ / "out" / "steps.csv");
    for (std::string line; std::getline(steps, line);)
      if (line.rfind("# memory allocator: ", 0) == 0) *header = line;
  };
  double mapped = -1, held_mapped = -1;
  std::string header, held_header;
  run("mapped", &mapped, &header);
  setenv("STICTION_HOLD_FREED_MEMORY", "1", 1);
  run("held", &held_mapped, &held_header);
  unsetenv("STICTION_HOLD_FREED_MEMORY");
  EXPECT_GT(mapped, 10.0);  // at least the matrix (45 438 rows, about 28 MB of values)
  EXPECT_EQ(held_mapped, 0.0);
  EXPECT_NE(header.find("blocks of 1 MB and more mapped on their own"), std::string::npos) << header;
  EXPECT_NE(header.find("glibc.malloc.hugetlb=1"), std::string::npos) << header;
  EXPECT_NE(held_header.find("freed memory held"), std::string::npos) << held_header;
  setenv("STICTION_MMAP_THRESHOLD_MB", "64", 1);  // beyond glibc's 32 MB
  const CliRun refused = solve("cantilever-2d");
  unsetenv("STICTION_MMAP_THRESHOLD_MB");
  expect_error(refused, 2, {"STICTION_MMAP_THRESHOLD_MB", "from 0.125 to 32", "'64'"});
}

// The block with strips' schedules and geometry, broken one at a time: one clear message
// naming the file once, exit 2, before anything is solved.
TEST_F(StictionCli, BlockStripsScheduleAndGrooveErrorsAreInputErrors) {
  const std::string block = stiction::harness::builtin_scenes().at("block-strips");
  struct Case {
    std::string from, to, file;
    std::vector<std::string> needles;
  };
  const std::vector<Case> cases = {
      {"friction_table = [[0.0, 0.0], [4.0, 0.3]]", "friction_table = [[0.0, 0.0, 1.0], [4.0, 0.3]]", "mu-row.toml",
       {"friction_table", "2 numbers"}},
      {"[8.0, 6.0, 0.0, 1.5]]", "[8.0, 6.0, 1.5]]", "motion-row.toml", {"motion_table", "4 numbers", "one has 3"}},
      {"{ until = 8.0, steps = 4 }", "{ until = 3.0, steps = 4 }", "phases.toml", {"phases[1]", "until > 4"}},
      {"generator = \"grooved-block\"", "generator = \"grooved-block\"\ngrooves = 100", "grooves.toml",
       {"100 grooves", "do not fit"}}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.file);
    SceneVariant v;
    v.text = block;
    v.replace(c.from, c.to);
    const CliRun run = solve_variant(v, c.file);
    expect_error(run, 2, c.needles);
    const auto line = run.error_lines().empty() ? std::string() : run.error_lines().front();
    size_t mentions = 0;
    for (auto at = line.find(c.file); at != std::string::npos; at = line.find(c.file, at + 1)) ++mentions;
    EXPECT_EQ(mentions, 1u) << line;
  }
}

TEST_F(StictionCli, FailedFactorisationIsANamedNumericalFailure) {
  // A factorisation that cannot be set up (here: a solver package PETSc does not have)
  // is a result of the backend: Newton stops with DIVERGED_LINEAR_SOLVE, exit 3.
  expect_error(solve("cantilever-2d", {"-lu_mumps_pc_factor_mat_solver_type", "no_such_package"}), 3,
               {"DIVERGED_LINEAR_SOLVE", "PC_SETUP_FAILED", "no_such_package"});
}
