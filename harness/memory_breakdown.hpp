#pragma once
// Where a run's memory goes, from the figures every backend records per linear solve
// (metrics.toml: memory_matrix_MB, memory_setup_MB, memory_block_copies_MB,
// memory_krylov_MB, memory_heap_MB, memory_heap_free_MB): at the solve that held the most
// heap, the Newton matrix, what the preconditioner or factorisation kept (of it, blocks
// copied out of the matrix), the Krylov space, the rest of the heap (mesh, fields, state,
// contact data), and what the allocator held freed.
#include <map>
#include <string>
#include <vector>

namespace stiction::harness {

// A markdown table over the finished runs of the given scenes (runs.csv rows); runs made
// before these figures existed are left out; empty when none has them. out_dir holds the
// sweep (runs/<run>/metrics.toml).
std::string memory_breakdown_table(const std::vector<std::map<std::string, std::string>>& runs,
                                   const std::string& out_dir, const std::vector<std::string>& scenes);

}  // namespace stiction::harness
