#include "atlas_command.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "atlas_report.hpp"
#include "builtin_scenes.hpp"
#include "common/error.hpp"
#include "csv_table.hpp"
#include "registry.hpp"
#include "solve_child.hpp"
#include "sweep_table.hpp"

namespace stiction::harness {

namespace fs = std::filesystem;

namespace {

struct Axis {
  std::string key;
  std::vector<std::string> values;
};

Axis parse_axis(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw Error(fmt::format("axis '{}' is not KEY=v1,v2,...", text));
  Axis a{text.substr(0, eq), {}};
  // Values that hold commas themselves (arrays, inline tables) are separated by ';'.
  const std::string values = text.substr(eq + 1);
  const char separator = values.find(';') != std::string::npos ? ';' : ',';
  std::istringstream list(values);
  for (std::string v; std::getline(list, v, separator);)
    if (!v.empty()) a.values.push_back(v);
  if (a.key == "level")
    for (const auto& v : a.values)
      if (v.size() != 1 || v[0] < '0' || v[0] > '4') throw Error(fmt::format("axis level: '{}' is not a level 0-4", v));
  return a;
}

// Whether any of the run's text outputs holds a NaN ("nan", "-nan", "NaN" as a field).
bool nan_in_outputs(const std::string& run_dir) {
  static const std::regex nan(R"((^|[,\s=])-?nan([,\s]|$))", std::regex::icase);
  for (const char* file : {"steps.csv", "iterations.csv", "contact.csv", "metrics.toml"}) {
    std::ifstream in(run_dir + "/" + file);
    for (std::string line; std::getline(in, line);)
      if (line.empty() || line[0] != '#')
        if (std::regex_search(line, nan)) return true;
  }
  return false;
}

// Sum of the steps.csv column state_changes (0 without contact).
double state_changes(const std::string& run_dir) {
  double sum = 0;
  for (const auto& row : read_csv(run_dir + "/steps.csv").rows) sum += number(row, "state_changes");
  return sum;
}

// What must hold in every cell: it ends converged, or with a named Newton reason and exit
// code 3; never a crash, a hang or a NaN in its output.
std::string violation_of(const SolveRun& run, bool nan) {
  if (nan) return "nan";
  if (run.status == "time-limit") return "hang";
  if (run.status == "ok") return "";
  if (run.status == "newton-failed") return run.reason.empty() ? "unnamed failure" : "";
  if (run.status == "memory-limit") return "";  // a named resource limit, not a defect of the method
  if (run.child.exit_code == 2) return "";       // bad input, named (e.g. a value the scene refuses)
  return "crash";
}

// One cell of the sweep before the backend is chosen: the axis and value it shows in the
// table ("KEY1 & KEY2" and "v1 & v2" for a pair), its mesh level and its scene settings.
struct CellSetting {
  std::string axis, value;
  int level = 0;
  std::vector<std::string> settings;  // KEY=VALUE, the base scene's first
};

// Every cell of a single axis (one key) or a pair (two keys, every combination of values).
std::vector<CellSetting> cells_of(const std::vector<Axis>& keys, const AtlasOptions& o) {
  std::vector<CellSetting> cells{{"", "", o.level, o.base}};
  for (const Axis& a : keys) {
    std::vector<CellSetting> grown;
    for (const CellSetting& c : cells)
      for (const auto& v : a.values) {
        CellSetting g = c;
        g.axis += (g.axis.empty() ? "" : kPairSeparator) + a.key;
        g.value += (g.value.empty() ? "" : kPairSeparator) + v;
        if (a.key == "level") g.level = std::stoi(v);
        else g.settings.push_back(a.key + "=" + v);
        grown.push_back(std::move(g));
      }
    cells = std::move(grown);
  }
  return cells;
}

}  // namespace

void run_atlas(const AtlasOptions& o, const RunInfo& info) {
  if (o.axes.empty() && o.pairs.empty()) throw Error("atlas: give at least one --axis KEY=v1,v2,... or --pair");
  if (o.pairs.size() % 2) throw Error("atlas: --pair takes two axes, KEY1=v1,v2,... KEY2=w1,w2,...");
  std::vector<std::vector<Axis>> sweeps;
  for (const auto& text : o.axes) sweeps.push_back({parse_axis(text)});
  for (size_t k = 0; k < o.pairs.size(); k += 2) {
    sweeps.push_back({parse_axis(o.pairs[k]), parse_axis(o.pairs[k + 1])});
    if (sweeps.back()[0].key == sweeps.back()[1].key)
      throw Error(fmt::format("atlas: --pair of '{}' with itself", sweeps.back()[0].key));
  }
  std::set<std::string> known;
  for (const auto& b : solvers::backends()) known.insert(b.name);
  for (const auto& s : o.solvers)
    if (!known.count(s)) throw Error(fmt::format("unknown solver backend '{}' (valid: {})", s, solvers::backend_names()));
  std::vector<CellSetting> settings;
  for (const auto& keys : sweeps) {
    const auto cells = cells_of(keys, o);
    settings.insert(settings.end(), cells.begin(), cells.end());
  }
  // Every cell must make a scene that builds: a misspelt key fails here, before any run.
  for (const auto& c : settings) open_scene(o.scene, c.level, c.settings);

  const std::string out = o.out_dir, csv = out + "/atlas.csv";
  std::error_code ec;
  fs::create_directories(fs::path(out) / "runs", ec);
  if (ec) throw Error(fmt::format("cannot create '{}': {}", out, ec.message()));
  const ChildLimits limits = sweep_limits(o.time_limit_seconds, o.memory_limit_mb);
  std::set<std::string> done;
  const CsvTable previous = open_sweep_table(csv, kAtlasColumns, o.resume, info, [&] {
    std::string header = format_run_info(info, "# ");
    header += fmt::format("# base scene: {} level {}{}\n# limits per cell: {:.0f} s, {:.0f} MB resident\n", o.scene,
                          o.level, o.quick ? " (its short version, --quick)" : "", limits.seconds, limits.memory_mb);
    for (const auto& setting : o.base) header += "# base setting: " + setting + "\n";
    return header;
  });
  for (const auto& row : previous.rows) done.insert(cell_id(row.at("axis"), row.at("value"), row.at("solver")));

  const size_t cells = settings.size() * o.solvers.size();
  size_t index = 0;
  for (const auto& c : settings)
    for (const auto& solver : o.solvers) {
      ++index;
      const std::string id = cell_id(c.axis, c.value, solver);
      if (done.count(id)) continue;
      const std::string run_dir = (fs::path(out) / "runs" / id).string();
      std::vector<std::string> arguments{"--solver", solver};
      for (const auto& setting : c.settings) arguments.insert(arguments.end(), {"--set", setting});
      if (o.quick) arguments.push_back("--quick");
      const SolveRun run = run_solve_child(o.scene, c.level, arguments, {}, run_dir, limits);
      const bool nan = nan_in_outputs(run_dir);
      const std::string violation = violation_of(run, nan);
      append_durably(csv, fmt::format("{},{},{},{},{},{},{},{},{:.0f},{:.0f},{:.0f},{:.3f},{:.1f},{},{},{}", o.scene,
                                      c.level, csv_field(c.axis), csv_field(c.value), solver, run.status,
                                      csv_field(run.reason.empty() ? run.status : run.reason), run.child.exit_code,
                                      run.newton, run.krylov, state_changes(run_dir), run.wall_seconds,
                                      run.child.peak_rss_mb, nan ? 1 : 0, violation, csv_field(run.detail)));
      fmt::print(stderr, "atlas [{}/{}] {} = {}, {}: {}{}\n", index, cells, c.axis, c.value, solver,
                 run.reason.empty() ? run.status : run.reason,
                 violation.empty() ? "" : " (VIOLATION: " + violation + ")");
      write_atlas_report(out);
    }
  write_atlas_report(out);
}

}  // namespace stiction::harness
