#pragma once
// The headline of README.md: the block with strips beside the paper, computed from a
// published paper-tables sweep (samples.csv and runs.csv), so that the README's figures are
// the tables' (`stiction report --headline DIR` prints it; a unit test compares the README
// with it).
#include <string>

namespace stiction::harness {

// The markdown table of the headline for level `level` of `block-strips`: schur-amg against
// the fastest direct backend on the recorded sample, beside the paper's Table 2 ratios, each
// row naming whether it comes from the sample, a whole run or a projection. Throws when the
// sweep lacks the rows.
std::string readme_headline(const std::string& paper_tables_dir, int level = 1);

}  // namespace stiction::harness
