#pragma once
// Figures and descriptions shared by the backends.
#include <map>
#include <string>

#include <petscksp.h>

namespace stiction::solvers {

// MUMPS's own figures for a KSP whose PC is an LU/Cholesky factorisation by MUMPS:
// INFOG(22) memory effectively used (MB), INFOG(7) ordering used, RINFOG(3) flops, and the
// entries of the factors, as stored (INFOG(35), after block low-rank compression; INFOG(29)
// where that is not reported) and as the analysis estimated them at full rank (INFOG(20)):
// their ratio is the BLR compression rate, the full-rank count the fill of the ordering;
// and how hard pivoting was: pivots chosen off the diagonal (INFOG(12)) and delayed to a
// parent front (INFOG(13)), MUMPS's stand-in for the pivot growth it does not report.
// Keys get `key_prefix` ("" or "ll_"). Does nothing for other PCs.
void add_mumps_figures(KSP ksp, const std::string& key_prefix, std::map<std::string, double>& extra);
// What MUMPS knows about the factor matrix F after its analysis alone: the ordering it ran
// (INFOG(7)) and the estimated full-rank entries of the factors (INFOG(20)), under the same
// keys. Read from a factorisation that is never set up, they would be zeros (AMD's code).
void add_mumps_analysis_figures(Mat F, const std::string& key_prefix, std::map<std::string, double>& extra);
// Operator complexity (sum of the levels' nonzeros over the finest level's) of a KSP whose
// PC is PCMG or PCGAMG; 0 for other PCs or before set-up.
double mg_operator_complexity(KSP ksp);
// Bytes the allocator has handed out and not taken back (glibc mallinfo2), in MB: what
// PETSc, hypre, MUMPS and stiction hold on the heap now. Differences around a set-up or a
// solve say what that step kept.
double heap_in_use_mb();
// Bytes freed to the allocator and kept by it (glibc mallinfo2's fordblks), in MB: held by
// the process, and resident where they were touched, though nothing uses them. Resident
// memory above the heap in use and this is code, stacks and shared segments.
double heap_free_mb();
// Of the heap in use, the blocks mapped on their own (mallinfo2's hblkhd), in MB: returned
// to the system when freed (common/process_memory.hpp); 0 when mapping is switched off.
double mapped_blocks_mb();
// Storage of an assembled AIJ matrix (values, column indices, row starts), in MB; 0 for
// other types (shells, views).
double aij_storage_mb(Mat A);

// Full ASCII KSPView of a solver (PETSc's string viewer prints one line only).
std::string full_view(KSP ksp);

}  // namespace stiction::solvers
