#pragma once
// Resident memory of a process, read from /proc/<pid>/status (Linux), and how the C
// allocator gives freed memory back to the system.

#include <string>

namespace stiction {

// A memory field of /proc/<pid>/status ("VmRSS", "VmHWM", ...) in MB; pid 0 = this process;
// 0 when the file or the field cannot be read.
double proc_status_mb(int pid, const char* field);
// This process's resident memory now (VmRSS) and its peak so far (VmHWM), in MB.
inline double resident_mb() { return proc_status_mb(0, "VmRSS"); }
inline double peak_resident_mb() { return proc_status_mb(0, "VmHWM"); }

// Large blocks (1 MB and more; STICTION_MMAP_THRESHOLD_MB changes it) get their own mapping,
// returned to the system when freed, and the heap's free top is trimmed. Debian's PETSc
// links SuperLU_dist, whose CombBLAS headers switch both off in a static initialiser
// (mallopt(M_MMAP_MAX, 0), mallopt(M_TRIM_THRESHOLD, -1)) in every program that loads it:
// freed memory then stays resident for good, and the peak RSS counts the heap's high-water
// mark and its fragmentation rather than what a phase needs. Called by PetscSession;
// STICTION_HOLD_FREED_MEMORY=1 in the environment keeps CombBLAS's settings (to compare).
void return_freed_memory_to_the_system();
// Mapped blocks are faulted in anew each time a phase allocates them again (the Newton
// matrix at every assembly), which with 4 kB pages slows the assembly and the AMG set-up
// (reports/block-strips-studies/level2-block-strips-schur-amg/allocator/README.md). glibc
// backs them with transparent huge pages when its tunable glibc.malloc.hugetlb=1 is set,
// which it reads only at start-up: this re-executes the program (argv as given) with the
// tunable added to GLIBC_TUNABLES, unless that already names it or
// STICTION_HOLD_FREED_MEMORY=1. Returns if no re-execution took place. Call it first in main,
// before MPI or threads start.
void restart_with_huge_pages_for_mapped_blocks(char** argv);
// One line for a run's header: how the allocator was set.
std::string allocator_settings();

}  // namespace stiction
