#include "sweep_table.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "common/error.hpp"

namespace stiction::harness {

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
  if (found != columns)
    throw Error(fmt::format("'{}' has other columns than this stiction writes (an older version's sweep): start a new "
                            "sweep in another --out",
                            path));
  append_durably(path, "# resumed: " + info.command_line + " at " + info.date + ", git " + info.git_revision);
  return previous;
}

}  // namespace stiction::harness
