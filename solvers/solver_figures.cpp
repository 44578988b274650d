#include "solver_figures.hpp"

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "common/petsc.hpp"

namespace stiction::solvers {

namespace {
// MUMPS gives a count above 2^31 as minus the count in millions.
double mumps_count(PetscInt v) { return v < 0 ? -1e6 * static_cast<double>(v) : static_cast<double>(v); }
}  // namespace

void add_mumps_analysis_figures(Mat F, const std::string& key_prefix, std::map<std::string, double>& extra) {
  PetscInt ordering = 0, full_rank = 0;
  if (!MatMumpsGetInfog(F, 7, &ordering)) extra[key_prefix + "mumps_ordering"] = static_cast<double>(ordering);
  if (!MatMumpsGetInfog(F, 20, &full_rank)) extra[key_prefix + "mumps_factor_entries_full_rank"] = mumps_count(full_rank);
}

void add_mumps_figures(KSP ksp, const std::string& key_prefix, std::map<std::string, double>& extra) {
  PC pc;
  Mat F;
  PetscBool is_factor = PETSC_FALSE;
  if (KSPGetPC(ksp, &pc)) return;
  PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(pc), &is_factor, PCLU, PCCHOLESKY, "");
  if (!is_factor || PCFactorGetMatrix(pc, &F)) return;
  MatSolverType type;
  if (MatFactorGetSolverType(F, &type) || std::string(type) != MATSOLVERMUMPS) return;
  add_mumps_analysis_figures(F, key_prefix, extra);
  PetscInt mem = 0;
  PetscReal flops = 0;
  if (!MatMumpsGetInfog(F, 22, &mem)) extra[key_prefix + "mumps_memory_MB"] = static_cast<double>(mem);
  if (!MatMumpsGetRinfog(F, 3, &flops)) extra[key_prefix + "mumps_factor_flops"] = flops;
  PetscInt stored = 0, compressed = 0;
  if (!MatMumpsGetInfog(F, 29, &stored) && !MatMumpsGetInfog(F, 35, &compressed))
    extra[key_prefix + "mumps_factor_entries"] = mumps_count(compressed != 0 ? compressed : stored);
  // Numerical pivoting: a pivot below the threshold CNTL(1) of its column is chosen off the
  // diagonal within its front (INFOG(12)) or, where no fully summed row will do, delayed to
  // the parent front (INFOG(13)), which grows the fronts and the factors past the analysis.
  PetscInt off_diagonal = 0, delayed = 0;
  if (!MatMumpsGetInfog(F, 12, &off_diagonal)) extra[key_prefix + "mumps_off_diagonal_pivots"] = static_cast<double>(off_diagonal);
  if (!MatMumpsGetInfog(F, 13, &delayed)) extra[key_prefix + "mumps_delayed_pivots"] = static_cast<double>(delayed);
}

double mg_operator_complexity(KSP ksp) {
  PC pc;
  PetscBool mg = PETSC_FALSE;
  if (KSPGetPC(ksp, &pc) || PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(pc), &mg, PCMG, PCGAMG, "") || !mg)
    return 0;
  PetscReal grid = 0, op = 0;
  if (PCMGGetGridComplexity(pc, &grid, &op)) return 0;
  return op;
}

double heap_in_use_mb() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks + m.hblkhd) / 1048576.0;
}

double heap_free_mb() { return static_cast<double>(mallinfo2().fordblks) / 1048576.0; }

double mapped_blocks_mb() { return static_cast<double>(mallinfo2().hblkhd) / 1048576.0; }

double aij_storage_mb(Mat A) {
  PetscBool aij = PETSC_FALSE;
  if (!A || PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(A), &aij, MATSEQAIJ, MATMPIAIJ, "") || !aij)
    return 0;
  MatInfo info;
  PetscInt rows;
  if (MatGetInfo(A, MAT_LOCAL, &info) || MatGetLocalSize(A, &rows, nullptr)) return 0;
  // nz_allocated is 0 for a matrix over caller-built arrays (seq_aij_over): it holds nz_used.
  const double nz = std::max(info.nz_allocated, info.nz_used);
  return (nz * (sizeof(PetscScalar) + sizeof(PetscInt)) + (rows + 1.0) * sizeof(PetscInt)) / 1048576.0;
}

std::string full_view(KSP ksp) {
  // The view is collective on the KSP's processes; rank 0 writes the file and reads it back.
  MPI_Comm comm;
  STICTION_PETSC(PetscObjectGetComm(reinterpret_cast<PetscObject>(ksp), &comm));
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  char path[] = "/tmp/stiction-kspview-XXXXXX";
  int ok = 1;
  if (rank == 0) {
    const int fd = mkstemp(path);
    ok = fd >= 0;
    if (ok) close(fd);
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, comm);
  if (!ok) return "(KSP view unavailable)";
  MPI_Bcast(path, sizeof(path), MPI_CHAR, 0, comm);
  PetscViewer viewer;
  STICTION_PETSC(PetscViewerASCIIOpen(comm, path, &viewer));
  STICTION_PETSC(KSPView(ksp, viewer));
  STICTION_PETSC(PetscViewerDestroy(&viewer));
  if (rank != 0) return {};
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::remove(path);
  return text.str();
}

}  // namespace stiction::solvers
