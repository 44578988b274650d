#include "csv_table.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "common/error.hpp"

namespace stiction::harness {

namespace {
std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string field;
  while (std::getline(ss, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}
}  // namespace

CsvTable read_csv(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return parse_csv(text.str());
}

CsvTable parse_csv(const std::string& text) {
  CsvTable t;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    if (line[0] == '#') {
      t.comments.push_back(line.size() > 2 ? line.substr(2) : "");
      continue;
    }
    const auto fields = split(line);
    if (t.columns.empty()) {
      t.columns = fields;
      continue;
    }
    std::map<std::string, std::string> row;
    for (size_t k = 0; k < t.columns.size(); ++k) row[t.columns[k]] = k < fields.size() ? fields[k] : "";
    t.rows.push_back(std::move(row));
  }
  return t;
}

double number(const std::map<std::string, std::string>& row, const std::string& key) {
  const auto it = row.find(key);
  if (it == row.end() || it->second.empty()) return 0;
  return std::strtod(it->second.c_str(), nullptr);
}

std::string csv_field(std::string text) {
  for (char& c : text)
    if (c == ',' || c == '\n' || c == '\r') c = ';';
  return text;
}

void append_durably(const std::string& path, const std::string& line) {
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  if (fd < 0) throw Error(fmt::format("cannot write '{}'", path));
  const std::string text = line.back() == '\n' ? line : line + "\n";
  const bool ok = write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size()) && fsync(fd) == 0;
  close(fd);
  if (!ok) throw Error(fmt::format("cannot write '{}'", path));
}

}  // namespace stiction::harness
