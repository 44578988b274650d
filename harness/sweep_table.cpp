#include "sweep_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <vector>

#include "common/error.hpp"

namespace stiction::harness {

namespace {

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  size_t start = 0;
  for (size_t comma; (comma = line.find(',', start)) != std::string::npos; start = comma + 1)
    fields.push_back(line.substr(start, comma - start));
  fields.push_back(line.substr(start));
  return fields;
}

// An older sweep whose columns are all among `columns` (this version added some) is
// rewritten with the new columns, left empty in its rows; false when it has a column this
// version does not write.
bool upgrade_columns(const std::string& path, const std::vector<std::string>& found, const std::string& columns) {
  const std::vector<std::string> wanted = split_fields(columns);
  std::vector<int> source;  // per new column, its index among the old ones (-1: new)
  for (const auto& c : wanted) {
    const auto at = std::find(found.begin(), found.end(), c);
    source.push_back(at == found.end() ? -1 : static_cast<int>(at - found.begin()));
  }
  for (const auto& c : found)
    if (std::find(wanted.begin(), wanted.end(), c) == wanted.end()) return false;
  std::ifstream in(path);
  std::string text;
  bool header_seen = false;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') {
      text += line + "\n";
      continue;
    }
    if (!header_seen) {
      header_seen = true;
      text += columns + "\n";
      continue;
    }
    const std::vector<std::string> old = split_fields(line);
    std::string row;
    for (size_t k = 0; k < source.size(); ++k)
      row += (k ? "," : "") + (source[k] >= 0 && source[k] < static_cast<int>(old.size()) ? old[source[k]] : "");
    text += row + "\n";
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
                          const std::function<std::string()>& header) {
  if (!std::filesystem::exists(path)) {
    append_durably(path, header() + columns);
    return {};
  }
  if (!resume) throw Error(fmt::format("'{}' exists: pass --resume to continue that sweep or choose another --out", path));
  CsvTable previous = read_csv(path);
  std::string found;
  for (const auto& c : previous.columns) found += (found.empty() ? "" : ",") + c;
  if (found != columns) {
    if (!upgrade_columns(path, previous.columns, columns))
      throw Error(fmt::format("'{}' has columns this stiction does not write (another version's sweep): start a new "
                              "sweep in another --out",
                              path));
    append_durably(path, "# columns added by a newer version: the rows above have them empty");
    previous = read_csv(path);
  }
  append_durably(path, "# resumed: " + info.command_line + " at " + info.date + ", git " + info.git_revision);
  return previous;
}

}  // namespace stiction::harness
