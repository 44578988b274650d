#pragma once
// Minimal CSV for the harness's own files: '#' lines are provenance comments, the first
// other line is the header, fields never contain commas (writers replace them).
#include <map>
#include <string>
#include <vector>

namespace stiction::harness {

struct CsvTable {
  std::vector<std::string> comments;  // without the leading "# "
  std::vector<std::string> columns;
  std::vector<std::map<std::string, std::string>> rows;
};

CsvTable read_csv(const std::string& path);  // empty table if the file does not exist
CsvTable parse_csv(const std::string& text);
// A row's field as a number: 0 when it is missing, empty or not a number.
double number(const std::map<std::string, std::string>& row, const std::string& key);
std::string csv_field(std::string text);     // commas and newlines replaced

// Appends one line and forces it to disk (fsync), so a killed sweep loses no finished row.
void append_durably(const std::string& path, const std::string& line);

}  // namespace stiction::harness
