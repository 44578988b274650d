// README.md's headline figures are the committed paper tables' (reports/paper-tables/):
// the table between the headline markers must be exactly what `stiction report --headline`
// computes from samples.csv and runs.csv, so the two cannot drift apart.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "readme_headline.hpp"

#ifndef STICTION_SOURCE_DIR
#error "STICTION_SOURCE_DIR must be defined by the build"
#endif

namespace stiction::harness {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ReadmeHeadline, IsTheCommittedPaperTables) {
  const std::string readme = read_text(std::string(STICTION_SOURCE_DIR) + "/README.md");
  const std::string open = "<!-- headline:", close = "<!-- /headline -->";
  const size_t from = readme.find(open), to = readme.find(close);
  ASSERT_NE(from, std::string::npos) << "README.md has no headline marker";
  ASSERT_NE(to, std::string::npos);
  const size_t table = readme.find('\n', from) + 1;
  ASSERT_LT(table, to);
  const std::string in_readme = readme.substr(table, to - table);
  const std::string expected = readme_headline(std::string(STICTION_SOURCE_DIR) + "/reports/paper-tables");
  EXPECT_EQ(in_readme, expected) << "refresh it with: build/stiction report --headline reports/paper-tables";
}

TEST(ReadmeHeadline, IsAtMost12KB) {
  EXPECT_LE(read_text(std::string(STICTION_SOURCE_DIR) + "/README.md").size(), 12u * 1024);
}

TEST(ReportsIndex, IsAtMost15KB) {
  EXPECT_LE(read_text(std::string(STICTION_SOURCE_DIR) + "/reports/README.md").size(), 15u * 1024);
}

}  // namespace
}  // namespace stiction::harness
