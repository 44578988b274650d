#include "tradeoff_command.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <set>
#include <sstream>

#include "builtin_scenes.hpp"
#include "child_process.hpp"
#include "common/error.hpp"
#include "csv_table.hpp"
#include "ksp_solver.hpp"
#include "registry.hpp"
#include "scaling_plots.hpp"
#include "solution_accuracy.hpp"
#include "solve_child.hpp"
#include "sweep_table.hpp"
#include "tradeoff_report.hpp"

namespace stiction::harness {

namespace fs = std::filesystem;

namespace {

// One configuration: a backend at its defaults (newton_rtol and krylov_rtol < 0, forcing
// and knob empty: the scene's and the backend's), with the given tolerances, or with one
// PETSc option of its own (knob, "option=value").
struct Setting {
  std::string solver, forcing;
  double newton_rtol = -1, krylov_rtol = -1;
  std::string knob;
  bool is_default() const { return forcing.empty() && newton_rtol < 0 && krylov_rtol < 0 && knob.empty(); }
  std::string id() const {
    if (is_default()) return solver + "-default";
    if (!knob.empty()) return solver + "-" + knob;
    std::string s = fmt::format("{}-{}-newton{:g}", solver, forcing, newton_rtol);
    if (krylov_rtol >= 0) s += fmt::format("-krylov{:g}", krylov_rtol);
    return s;
  }
  std::vector<std::string> arguments() const {
    std::vector<std::string> a{"--solver", solver};
    if (!forcing.empty()) a.insert(a.end(), {"--forcing", forcing});
    if (newton_rtol >= 0) a.insert(a.end(), {"--newton-rtol", fmt::format("{:g}", newton_rtol)});
    if (krylov_rtol >= 0) a.insert(a.end(), {"--krylov-rtol", fmt::format("{:g}", krylov_rtol)});
    if (!knob.empty()) a.insert(a.end(), {"-" + knob.substr(0, knob.find('=')), knob.substr(knob.find('=') + 1)});
    return a;
  }
};

// "option=v1,v2" -> the option and its values; throws when malformed.
std::pair<std::string, std::vector<std::string>> parse_knob(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size() || text[0] == '-')
    throw Error(fmt::format("knob '{}' is not option=value,value,... (the PETSc option without its dash)", text));
  std::vector<std::string> values;
  std::istringstream list(text.substr(eq + 1));
  for (std::string v; std::getline(list, v, ',');)
    if (!v.empty()) values.push_back(v);
  return {text.substr(0, eq), values};
}

// A direct backend (one exact solve, no Krylov iterations) has no Krylov tolerance to vary.
bool is_direct(const std::string& solver) {
  return solvers::default_options(solver).find("-ksp_type preonly") != std::string::npos;
}

std::vector<Setting> settings_of(const TradeoffOptions& o) {
  std::vector<Setting> all;
  for (const auto& solver : o.solvers) {
    all.push_back({solver, "", -1, -1});
    for (const auto& forcing : is_direct(solver) ? std::vector<std::string>{"fixed"} : o.forcings)
      for (double newton : o.newton_rtols) {
        if (is_direct(solver)) {
          all.push_back({solver, forcing, newton, -1});
          continue;
        }
        for (double krylov : o.krylov_rtols) all.push_back({solver, forcing, newton, krylov});
      }
    for (const auto& knob : o.knobs) {
      const auto [option, values] = parse_knob(knob);
      if (option.rfind(solvers::options_prefix(solver), 0) != 0) continue;
      for (const auto& v : values) all.push_back({solver, "", -1, -1, option + "=" + v});
    }
  }
  return all;
}

std::string number_or_blank(double x, bool set) { return set ? fmt::format("{:.3e}", x) : ""; }
std::string number_or_blank(const std::optional<double>& x) { return number_or_blank(x.value_or(0), x.has_value()); }

// One row of tradeoff.csv (kTradeoffColumns); accuracy null: not measured. A run on a
// coarser mesh than the reference's has no state-by-state comparison (states_compared false).
std::string row_of(const scene::Scene& scene, const std::string& id, const Setting& s, const SolveRun& run,
                   const SolutionAccuracy* accuracy, const std::optional<AnalyticAccuracy>& analytic,
                   bool states_compared = true) {
  const bool contact = accuracy && accuracy->contact;
  return fmt::format(
      "{},{},{},{},{},{},{},{},{},{},{},{:.0f},{:.0f},{:.0f},{:.3f},{:.3f},{:.1f},{},{},{},{},{},{},{},{},{},{}",
      scene.name,
      scene.level, id, s.solver, s.forcing, s.newton_rtol >= 0 ? fmt::format("{:g}", s.newton_rtol) : "",
      s.krylov_rtol >= 0 ? fmt::format("{:g}", s.krylov_rtol) : "", s.knob, s.is_default() ? 1 : 0, run.status,
      csv_field(run.reason.empty() ? run.status : run.reason), run.newton, run.solves, run.krylov, run.wall_seconds,
      run.linear_seconds, run.child.peak_rss_mb, number_or_blank(accuracy ? accuracy->displacement_l2 : 0, accuracy),
      number_or_blank(accuracy ? accuracy->displacement_h1 : 0, accuracy),
      number_or_blank(contact ? accuracy->contact_force : 0, contact),
      number_or_blank(contact ? accuracy->peak_pressure : 0, contact),
      contact && states_compared ? std::to_string(accuracy->state_changes) : "",
      number_or_blank(analytic ? analytic->hertz_a : std::nullopt),
      number_or_blank(analytic ? analytic->hertz_p0 : std::nullopt),
      number_or_blank(analytic ? analytic->stick_zone : std::nullopt),
      number_or_blank(analytic ? analytic->patch_pressure : std::nullopt), csv_field(run.detail));
}

// Solves the reference at `level` into dir (a row `id` of tradeoff.csv unless done has it);
// throws when it does not finish, since nothing can be measured against it.
void solve_reference(const TradeoffOptions& o, int level, const scene::Scene& scene, const std::string& id,
                     const std::string& dir, const ChildLimits& limits, const std::string& csv,
                     std::set<std::string>& done) {
  const Setting reference{o.reference_solver, "fixed", o.reference_newton_rtol, -1};
  const SolveRun run = run_solve_child(o.scene, level, reference.arguments(), {}, dir, limits);
  if (run.status != "ok")
    throw Error(fmt::format("the reference run at level {} ({} with newton rtol {:g}) ended {}: {} (see {}/stderr.txt)",
                            level, o.reference_solver, o.reference_newton_rtol, run.status, run.detail, dir),
                ErrorKind::Numerical);
  if (!done.count(id)) append_durably(csv, row_of(scene, id, reference, run, nullptr, analytic_accuracy(scene, dir)));
  done.insert(id);
}

// The mesh as a knob: every backend at its defaults on each coarser level, its final state
// against the reference at the sweep's level (a row "L<level>-<backend>-default").
void run_coarser_levels(const TradeoffOptions& o, const scene::Scene& fine, const std::string& reference_dir,
                        const ChildLimits& limits, const std::string& csv, std::set<std::string>& done) {
  for (int level : o.coarser_levels) {
    const auto coarse = open_scene(o.scene, level);
    for (const auto& solver : o.solvers) {
      const Setting s{solver, "", -1, -1};
      const std::string id = fmt::format("L{}-{}", level, s.id());
      if (done.count(id)) continue;
      const std::string run_dir = (fs::path(o.out_dir) / "runs" / id).string();
      const SolveRun run = run_solve_child(o.scene, level, s.arguments(), o.petsc_options, run_dir, limits);
      const bool measured = run.status == "ok";
      SolutionAccuracy a;
      if (measured) {
        const LevelDifference d = compare_levels(*coarse, run_dir, fine, reference_dir);
        a.displacement_l2 = d.displacement_l2;
        a.displacement_h1 = d.displacement_h1;
        a.contact = d.contact;
        a.contact_force = d.contact_force;
        a.peak_pressure = d.peak_pressure;
      }
      append_durably(csv, row_of(*coarse, id, s, run, measured ? &a : nullptr,
                                 measured ? analytic_accuracy(*coarse, run_dir) : std::nullopt, false));
      done.insert(id);
      fmt::print(stderr, "tradeoff: {} at level {}: {} in {:.2f} s\n", solver, level, run.status, run.wall_seconds);
      write_tradeoff_report(o.out_dir);
    }
  }
}

}  // namespace

void run_tradeoff(const TradeoffOptions& o, const RunInfo& info) {
  std::set<std::string> known;
  for (const auto& b : solvers::backends()) known.insert(b.name);
  for (const auto& s : o.solvers)
    if (!known.count(s)) throw Error(fmt::format("unknown solver backend '{}' (valid: {})", s, solvers::backend_names()));
  if (!known.count(o.reference_solver))
    throw Error(fmt::format("unknown reference backend '{}' (valid: {})", o.reference_solver, solvers::backend_names()));
  for (const auto& f : o.forcings)
    if (f != "fixed" && f != "eisenstat-walker")
      throw Error(fmt::format("unknown Newton forcing '{}' (accepted: fixed, eisenstat-walker)", f));
  for (const auto& list : {o.newton_rtols, o.krylov_rtols})
    for (double x : list)
      if (!(x > 0 && x < 1)) throw Error(fmt::format("tolerance {:g} outside (0, 1)", x));
  for (const auto& knob : o.knobs) {
    const std::string option = parse_knob(knob).first;
    bool matches = false;
    for (const auto& s : o.solvers) matches |= option.rfind(solvers::options_prefix(s), 0) == 0;
    if (!matches) throw Error(fmt::format("knob '{}' carries the prefix of none of the backends of this sweep", option));
  }
  for (const auto& option : o.petsc_options) {
    bool matches = false;
    for (const auto& s : o.solvers) matches |= option.rfind("-" + solvers::options_prefix(s), 0) == 0;
    if (!matches) throw Error(fmt::format("PETSc option '{}' matches none of the backends of this sweep", option));
  }
  if (o.discretisation && o.level >= 4) throw Error("--discretisation needs a level below 4 (it solves one finer)");
  for (int l : o.coarser_levels)
    if (l < 0 || l >= o.level)
      throw Error(fmt::format("--coarser-levels: level {} is not below --level {}", l, o.level));
  const auto scene = open_scene(o.scene, o.level);  // bad input fails here, before any run

  const std::string out = o.out_dir, csv = out + "/tradeoff.csv";
  std::error_code ec;
  fs::create_directories(fs::path(out) / "runs", ec);
  if (ec) throw Error(fmt::format("cannot create '{}': {}", out, ec.message()));
  const ChildLimits limits = sweep_limits(o.time_limit_seconds, o.memory_limit_mb);
  std::set<std::string> done;
  const CsvTable previous = open_sweep_table(csv, kTradeoffColumns, o.resume, info, [&] {
    std::string header = format_run_info(info, "# ");
    header += fmt::format("# scene: {} level {} ({} unknowns)\n", scene->name, scene->level, scene->space->n_dofs());
    header += fmt::format("# reference: {} with newton rtol {:g} and its exact solves\n", o.reference_solver,
                          o.reference_newton_rtol);
    header += fmt::format("# limits per run: {:.0f} s, {:.0f} MB resident\n", limits.seconds, limits.memory_mb);
    for (const auto& s : o.solvers) header += fmt::format("# backend {} options: {}\n", s, solvers::compact_options(s));
    for (const auto& opt : o.petsc_options) header += "# petsc option: " + opt + "\n";
    return header;
  });
  for (const auto& row : previous.rows) done.insert(row.at("id"));

  // The reference: solved once, kept for --resume.
  const std::string reference_dir = out + "/reference";
  if (!fs::exists(reference_dir + "/checkpoint.bin") || !done.count("reference")) {
    fmt::print(stderr, "tradeoff: reference ({} with newton rtol {:g})\n", o.reference_solver, o.reference_newton_rtol);
    solve_reference(o, o.level, *scene, "reference", reference_dir, limits, csv, done);
  }
  if (o.discretisation) {
    const auto fine = open_scene(o.scene, o.level + 1);
    const std::string fine_id = fmt::format("reference-L{}", o.level + 1), fine_dir = out + "/" + fine_id;
    if (!fs::exists(fine_dir + "/checkpoint.bin") || !done.count(fine_id)) {
      fmt::print(stderr, "tradeoff: reference at level {} (the discretisation error)\n", o.level + 1);
      solve_reference(o, o.level + 1, *fine, fine_id, fine_dir, limits, csv, done);
    }
    const LevelDifference d = compare_levels(*scene, reference_dir, *fine, fine_dir);
    write_text_file(out + "/discretisation.csv",
                    fmt::format("# the reference's final state at level {} against level {}'s (relative differences)\n"
                                "level,fine_level,displacement_l2,displacement_h1,contact_force,peak_pressure\n"
                                "{},{},{:.3e},{:.3e},{},{}\n",
                                o.level, o.level + 1, o.level, o.level + 1, d.displacement_l2, d.displacement_h1,
                                number_or_blank(d.contact_force, d.contact), number_or_blank(d.peak_pressure, d.contact)));
  }

  const auto settings = settings_of(o);
  int index = 0;
  for (const Setting& s : settings) {
    ++index;
    if (done.count(s.id())) continue;
    const std::string run_dir = (fs::path(out) / "runs" / s.id()).string();
    const SolveRun run = run_solve_child(o.scene, o.level, s.arguments(), o.petsc_options, run_dir, limits);
    SolutionAccuracy a;
    const bool measured = run.status == "ok";
    if (measured) a = compare_to_reference(*scene, run_dir, reference_dir);
    const std::string row = row_of(*scene, s.id(), s, run, measured ? &a : nullptr,
                                   measured ? analytic_accuracy(*scene, run_dir) : std::nullopt);
    append_durably(csv, row);
    fmt::print(stderr, "tradeoff [{}/{}] {}: {} in {:.2f} s{}\n", index, settings.size(), s.id(), run.status,
               run.wall_seconds, measured ? fmt::format(", displacement error {:.2e} (H1)", a.displacement_h1) : "");
    write_tradeoff_report(out);
  }
  run_coarser_levels(o, *scene, reference_dir, limits, csv, done);
  write_tradeoff_report(out);
}

}  // namespace stiction::harness
