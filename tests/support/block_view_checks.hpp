#pragma once
// Block views (solvers/block_view.hpp) against copies (MatCreateSubMatrix) of the same blocks
// of a Newton system: the products of A_qq, A_ql and A_lq, the SOR sweeps of A_qq and its
// diagonal. Shared by the one-process tests and the two-process ones (mpi/).
#include <string>
#include <vector>

#include "nonlinear/newton_system.hpp"

namespace stiction::test {

// One MatSOR call: flag, omega, shift, its, lits.
struct SorCase {
  int flag;
  double omega, shift;
  PetscInt its, lits;
};

// Whether the three blocks were views (MATSHELL) and how far each result lies from the
// copy's, relative (the largest over products, over sweeps, and for the diagonal).
struct ViewAgreement {
  bool views_are_shells = false;
  double product = 0, sweep = 0, diagonal = 0;
};

ViewAgreement compare_views_with_copies(const nonlinear::NewtonSystem& sys, const std::vector<SorCase>& sweeps);

// HP on sys under the options prefix, an LU of A_ll (factor package `lu_package`) and one
// SOR sweep of kind `sweep` ("symmetric", or "local_symmetric" on several processes) on A_qq,
// with copies of its blocks when asked: which blocks it held as views, and GMRES on sys.
struct HierarchicalRun {
  bool ll_view = false, ql_view = false, qq_view = false;
  int iterations = 0;
  double residual = 0;
};
HierarchicalRun run_hierarchical(const nonlinear::NewtonSystem& sys, const std::string& prefix, bool copies,
                                 const char* lu_package, const char* sweep);

}  // namespace stiction::test
