#include "readme_headline.hpp"

#include <fmt/format.h>

#include "common/error.hpp"
#include "csv_table.hpp"

namespace stiction::harness {

const std::map<std::string, std::string>& embedded_reference();  // generated

namespace {

using Row = std::map<std::string, std::string>;

const Row& find_row(const CsvTable& t, const std::string& what, int level, const std::string& solver,
                    const std::string& source) {
  for (const auto& r : t.rows)
    if (r.at("scene") == what && number(r, "level") == level && r.at("solver") == solver) return r;
  throw Error(fmt::format("{} has no row of {} level {} {}", source, what, level, solver));
}

}  // namespace

std::string readme_headline(const std::string& dir, int level) {
  const std::string scene = "block-strips";
  const CsvTable samples = read_csv(dir + "/samples.csv"), runs = read_csv(dir + "/runs.csv");
  const Row& schur = find_row(samples, scene, level, "schur-amg", "samples.csv");
  const Row* direct = nullptr;  // the fastest direct backend on the sample, as the tables' ratios
  for (const auto& r : samples.rows)
    if (r.at("scene") == scene && number(r, "level") == level && r.at("status") == "ok" &&
        r.at("solver").rfind("lu-", 0) == 0 &&
        (!direct || number(r, "seconds_per_linear_solve") < number(*direct, "seconds_per_linear_solve")))
      direct = &r;
  if (!direct) throw Error(fmt::format("samples.csv has no direct backend that solved level {}", level));
  const Row& whole = find_row(runs, scene, level, "schur-amg", "runs.csv");
  const CsvTable paper = parse_csv(embedded_reference().at("tables2-3-times"));
  const Row *p_schur = nullptr, *p_lu = nullptr;
  for (const auto& p : paper.rows)
    if (number(p, "table") == 2 && number(p, "level") == level) (p.at("solver") == "GlobalLU" ? p_lu : p_schur) = &p;
  if (!p_schur || !p_lu) throw Error(fmt::format("the paper's Table 2 has no level {}", level));
  auto paper_ratio = [&](const char* key) { return fmt::format("{:.2f}x", number(*p_lu, key) / number(*p_schur, key)); };
  const std::string& lu = direct->at("solver");
  const double unknowns = number(schur, "unknowns");
  std::string md = fmt::format(
      "| `block-strips`, level {} ({:.0f} unknowns) | schur-amg | {} | {} / schur-amg | paper: GlobalLU / Schur |\n"
      "|---|---|---|---|---|\n",
      level, unknowns, lu, lu);
  md += fmt::format("| time per linear solve, s (recorded sample) | {:.2f} | {:.2f} | **{:.2f}x** | {} |\n",
                    number(schur, "seconds_per_linear_solve"), number(*direct, "seconds_per_linear_solve"),
                    number(*direct, "seconds_per_linear_solve") / number(schur, "seconds_per_linear_solve"),
                    paper_ratio("seconds_per_linear_solve"));
  md += fmt::format("| peak memory, MB (recorded sample) | {:.0f} | {:.0f} | **{:.2f}x** | {} |\n",
                    number(schur, "peak_rss_mb"), number(*direct, "peak_rss_mb"),
                    number(*direct, "peak_rss_mb") / number(schur, "peak_rss_mb"), paper_ratio("memory_mb"));
  md += fmt::format("| total time, s (schur-amg: whole run, {:.0f} Newton iterations; {}: projected) | {:.0f} | {:.0f} "
                    "| **{:.2f}x** | {} |\n",
                    number(whole, "newton_iterations"), lu, number(whole, "wall_seconds"),
                    number(*direct, "projected_total_seconds"),
                    number(*direct, "projected_total_seconds") / number(whole, "wall_seconds"),
                    paper_ratio("total_seconds"));
  return md;
}

}  // namespace stiction::harness
