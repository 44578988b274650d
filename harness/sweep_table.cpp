#include "sweep_table.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>

#include "common/error.hpp"

namespace stiction::harness {

namespace {

// An older sweep whose columns are all among `columns` (this version added some) is
// rewritten with the new columns, left empty in its rows (its comments first, then the
// table); false when it has a column this version does not write.
bool upgrade_columns(const std::string& path, const CsvTable& old, const std::string& columns) {
  const std::string joined = "," + columns + ",";
  for (const auto& c : old.columns)
    if (joined.find("," + c + ",") == std::string::npos) return false;
  const CsvTable header = parse_csv(columns);  // the new columns, in order
  std::string text;
  for (const auto& c : old.comments) text += "# " + c + "\n";
  text += columns + "\n";
  for (const auto& row : old.rows) {
    std::string line;
    for (size_t k = 0; k < header.columns.size(); ++k) {
      const auto it = row.find(header.columns[k]);
      line += (k ? "," : "") + (it == row.end() ? std::string() : it->second);
    }
    text += line + "\n";
  }
  const std::string upgraded = path + ".upgraded";
  {
    std::ofstream out(upgraded);
    out << text;
    if (!out) throw Error(fmt::format("cannot write '{}'", upgraded));
  }
  std::filesystem::rename(upgraded, path);
  return true;
}

}  // namespace

CsvTable open_sweep_table(const std::string& path, const std::string& columns, bool resume, const RunInfo& info,
                          const std::function<std::string()>& header, bool allow_other_revision) {
  if (!std::filesystem::exists(path)) {
    append_durably(path, header() + columns);
    return {};
  }
  if (!resume) throw Error(fmt::format("'{}' exists: pass --resume to continue that sweep or choose another --out", path));
  // The binary's own revision, without what the source tree was at when it ran.
  const auto binary = [](const std::string& r) { return r.substr(0, r.find(" (source tree at ")); };
  const std::string started_by = binary(sweep_revision(read_csv(path)));
  if (!allow_other_revision && !started_by.empty() && started_by != binary(info.git_revision))
    throw Error(fmt::format("'{}' was started by a binary of revision {}, this one is {}: resume it with that "
                            "binary, start a new sweep in another --out, or pass --allow-other-revision (each row "
                            "names its revision)",
                            path, started_by, binary(info.git_revision)));
  CsvTable previous = upgrade_sweep_columns(path, columns);
  append_durably(path, "# resumed: " + info.command_line + " at " + info.date + ", git " + info.git_revision);
  return previous;
}

std::string sweep_revision(const CsvTable& table) {
  const std::string key = "git revision: ";
  for (const auto& c : table.comments)
    if (c.rfind(key, 0) == 0) return c.substr(key.size());
  return "";
}

CsvTable upgrade_sweep_columns(const std::string& path, const std::string& columns) {
  CsvTable previous = read_csv(path);
  std::string found;
  for (const auto& c : previous.columns) found += (found.empty() ? "" : ",") + c;
  if (found == columns) return previous;
  if (!upgrade_columns(path, previous, columns))
    throw Error(fmt::format("'{}' has columns this stiction does not write (another version's sweep): start a new "
                            "sweep in another --out",
                            path));
  append_durably(path, "# columns added by a newer version: the rows above have them empty");
  return read_csv(path);
}

std::string run_status_text(const std::map<std::string, std::string>& row) {
  const std::string& status = row.at("status");
  if (status == "ok") {
    const std::string options = extra_petsc_options(row);
    return options.empty() ? "ok" : "ok (" + options + ")";
  }
  const std::string& detail = row.at("detail");
  return detail.empty() ? status : status + ": " + detail;
}

std::string extra_petsc_options(const std::map<std::string, std::string>& row) {
  const auto options = row.find("petsc_options");
  return options == row.end() ? "" : options->second;
}

bool stopped_with_solves(const std::map<std::string, std::string>& row) {
  return row.at("status") == "time-limit" && number(row, "linear_solves") > 0 &&
         number(row, "seconds_per_linear_solve") > 0;
}

std::string peak_memory_text(const std::map<std::string, std::string>& row) {
  const std::string mb = fmt::format("{:.0f}", number(row, "peak_rss_mb"));
  if (row.at("status") == "ok") return mb;
  return stopped_with_solves(row) ? "≥ " + mb : "—";
}

}  // namespace stiction::harness
