#include "memory_breakdown.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <filesystem>

#include "bench_estimate.hpp"
#include "csv_table.hpp"

namespace stiction::harness {

std::string memory_breakdown_table(const std::vector<std::map<std::string, std::string>>& runs,
                                   const std::string& out_dir, const std::vector<std::string>& scenes) {
  std::string rows;
  for (const auto& r : runs) {
    if (std::find(scenes.begin(), scenes.end(), r.at("scene")) == scenes.end() || r.at("status") != "ok") continue;
    const std::string path = run_directory(out_dir, r) + "/metrics.toml";
    if (!std::filesystem::exists(path)) continue;
    toml::table metrics;
    try {
      metrics = toml::parse_file(path);
    } catch (const toml::parse_error&) {
      continue;
    }
    const toml::table* largest = nullptr;
    if (const auto* solves = metrics["linear_solve"].as_array())
      for (const auto& node : *solves) {
        const toml::table* s = node.as_table();
        if (s && (*s)["memory_heap_MB"].value<double>() &&
            (!largest || *(*s)["memory_heap_MB"].value<double>() > *(*largest)["memory_heap_MB"].value<double>()))
          largest = s;
      }
    if (!largest) continue;
    auto mb = [&](const char* key) { return (*largest)[key].value<double>().value_or(0.0); };
    const double heap = mb("memory_heap_MB"), matrix = mb("memory_matrix_MB"), setup = mb("memory_setup_MB"),
                 krylov = mb("memory_krylov_MB");
    const auto copies = (*largest)["memory_block_copies_MB"].value<double>();  // Schur backends only
    const auto held_free = (*largest)["memory_heap_free_MB"].value<double>();  // runs since it was recorded
    rows += fmt::format("| {} | {} | {} | {:.0f} | {:.0f} | {:.0f} | {:.0f}{} | {:.0f} | {:.0f} | {} |\n", r.at("scene"),
                        r.at("level"), r.at("solver"), number(r, "peak_rss_mb"), heap, matrix, setup,
                        copies ? fmt::format(" ({:.0f} copied blocks)", *copies) : "", krylov,
                        heap - matrix - setup - krylov, held_free ? fmt::format("{:.0f}", *held_free) : "—");
  }
  if (rows.empty()) return "";
  return "\n### Where the memory goes\n\nAt the linear solve that held the most heap (MB): the Newton matrix, what "
         "the set-up kept (factors, AMG hierarchies and blocks copied out of the matrix; the Schur backends read the "
         "other blocks in place), the Krylov vectors, and the rest of the heap (mesh, fields, state, contact data). "
         "The last column is what the allocator held freed at that solve: resident where it was once written, it "
         "counts in the peak RSS though nothing uses it. Peak RSS also counts what the assembly held at its own "
         "peak, code and libraries.\n\n"
         "| scene | level | solver | peak RSS | heap | matrix | set-up | Krylov | rest | freed, held |\n"
         "|---|---|---|---|---|---|---|---|---|---|\n" +
         rows;
}

}  // namespace stiction::harness
