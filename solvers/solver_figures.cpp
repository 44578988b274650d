#include "solver_figures.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "common/petsc.hpp"

namespace stiction::solvers {

void add_mumps_figures(KSP ksp, const std::string& key_prefix, std::map<std::string, double>& extra) {
  PC pc;
  Mat F;
  PetscBool is_factor = PETSC_FALSE;
  if (KSPGetPC(ksp, &pc)) return;
  PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(pc), &is_factor, PCLU, PCCHOLESKY, "");
  if (!is_factor || PCFactorGetMatrix(pc, &F)) return;
  MatSolverType type;
  if (MatFactorGetSolverType(F, &type) || std::string(type) != MATSOLVERMUMPS) return;
  PetscInt mem = 0, ordering = 0;
  PetscReal flops = 0;
  if (!MatMumpsGetInfog(F, 22, &mem)) extra[key_prefix + "mumps_memory_MB"] = static_cast<double>(mem);
  if (!MatMumpsGetInfog(F, 7, &ordering)) extra[key_prefix + "mumps_ordering"] = static_cast<double>(ordering);
  if (!MatMumpsGetRinfog(F, 3, &flops)) extra[key_prefix + "mumps_factor_flops"] = flops;
}

double current_rss_mb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::strtod(line.c_str() + 6, nullptr) / 1024.0;  // kB
  return 0;
}

std::string full_view(KSP ksp) {
  char path[] = "/tmp/stiction-kspview-XXXXXX";
  const int fd = mkstemp(path);
  if (fd < 0) return "(KSP view unavailable)";
  close(fd);
  PetscViewer viewer;
  STICTION_PETSC(PetscViewerASCIIOpen(PETSC_COMM_SELF, path, &viewer));
  STICTION_PETSC(KSPView(ksp, viewer));
  STICTION_PETSC(PetscViewerDestroy(&viewer));
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::remove(path);
  return text.str();
}

}  // namespace stiction::solvers
