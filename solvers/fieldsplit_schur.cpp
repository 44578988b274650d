// fieldsplit-schur: PETSc's own Schur-complement field split (PCFIELDSPLIT, type schur) over
// the fields the Newton system carries: the displacement (u_l and u_q together) against the
// constraint unknowns (pressure and/or contact multipliers), built from PETSc's parts only
// (options/fieldsplit-schur.opts): GAMG on the displacement block with the rigid-body modes as
// near-null space, the selfp Schur approximation A_cc - A_cu diag(A_uu)^-1 A_uc factorised.
// It is the generic answer to the paper's hand-built nesting (schur-amg): where the two
// differ, the difference is in the Schur approximation and the displacement AMG, not in
// the factorisation, which -fieldsplit_schur_pc_fieldsplit_schur_fact_type selects as
// -contact_fact does for the paper's contact level (upper by default in both).
// A system without a pressure or multiplier block has nothing to split: set-up is refused
// with that reason (gamg is PETSc's answer there).
#include <petscksp.h>

#include <vector>

#include "field_sets.hpp"
#include "ksp_solver.hpp"
#include "solver_figures.hpp"

namespace stiction::solvers {

namespace {

class FieldsplitSchur final : public KspSolver {
public:
  explicit FieldsplitSchur(MPI_Comm comm) : KspSolver("fieldsplit-schur", comm) {}

  // PETSc 3.18's view of a Schur field split that was never set up dereferences the
  // missing Schur complement (a crash in MatSchurComplementGetAinvType).
  std::string describe() const override {
    if (setup_succeeded()) return KspSolver::describe();
    return "fieldsplit-schur (not set up for the last system; options: " + compact_options(name()) + ")\n";
  }

protected:
  void configure(const nonlinear::NewtonSystem& system) override {
    const PetscInt n_u = displacement_size(system);
    PetscInt n = 0;
    STICTION_PETSC(MatGetSize(system.matrix, &n, nullptr));
    if (n_u == n) return;  // refuse_setup says why
    PC pc;
    STICTION_PETSC(KSPGetPC(ksp(), &pc));
    STICTION_PETSC(PCSetType(pc, PCFIELDSPLIT));
    // The splits live until the PC is reset (a new contact matrix) or replaced.
    IS existing = nullptr;
    STICTION_PETSC(PCFieldSplitGetIS(pc, "u", &existing));
    if (existing) return;
    PetscIS u = union_of_fields(system, {"u_l", "u_q"}), c = complement_in(system.matrix, u);
    // PCFIELDSPLIT hands a near-null space composed on a split's IS to that block's matrix:
    // the rigid-body modes on the displacement's unknowns.
    if (system.near_null_space) {
      const PetscNullSpace modes = restrict_null_space(system.near_null_space, u);
      STICTION_PETSC(PetscObjectCompose(reinterpret_cast<PetscObject>(u.get()), "nearnullspace",
                                        reinterpret_cast<PetscObject>(modes.get())));
    }
    STICTION_PETSC(PCFieldSplitSetIS(pc, "u", u));
    STICTION_PETSC(PCFieldSplitSetIS(pc, "c", c));
  }

  std::string refuse_setup(const nonlinear::NewtonSystem& system) override {
    PetscInt n = 0;
    STICTION_PETSC(MatGetSize(system.matrix, &n, nullptr));
    if (displacement_size(system) < n) return {};
    return "fieldsplit-schur splits the displacement from a pressure or contact multiplier block and this system "
           "has neither (gamg is PETSc's answer there)";
  }

  // PCFIELDSPLIT builds its splits' solvers (the displacement AMG, the Schur complement's
  // factorisation) only at the first application: set them up here, so that the set-up
  // time and the AMG complexity are the set-up's and not the first solve's.
  void set_up_inner_solvers() override {
    for (KSP sub : split_solvers()) STICTION_PETSC(KSPSetUp(sub));
  }

  void collect_setup_figures(std::map<std::string, double>& extra) const override {
    // The split's solvers exist only after a successful set-up.
    if (!setup_succeeded()) return;
    const std::vector<KSP> subs = split_solvers();
    const double c = subs.empty() ? 0.0 : mg_operator_complexity(subs[0]);
    if (c > 0) extra["amg_operator_complexity"] = c;
  }

private:
  // The splits' solvers: the displacement's, then the Schur complement's.
  std::vector<KSP> split_solvers() const {
    PC pc;
    KSP* sub = nullptr;
    PetscInt n = 0;
    STICTION_PETSC(KSPGetPC(ksp(), &pc));
    STICTION_PETSC(PCFieldSplitGetSubKSP(pc, &n, &sub));
    std::vector<KSP> out(sub, sub + n);
    PetscFree(sub);
    return out;
  }

  // The displacement unknowns (u_l and u_q): their count.
  static PetscInt displacement_size(const nonlinear::NewtonSystem& system) {
    PetscInt size = 0, k = 0;
    for (const char* name : {"u_l", "u_q"})
      if (const auto* f = system.field(name)) {
        STICTION_PETSC(ISGetSize(f->is, &k));
        size += k;
      }
    return size;
  }
};

}  // namespace

std::unique_ptr<nonlinear::LinearSolver> make_fieldsplit_schur(MPI_Comm comm) {
  return std::make_unique<FieldsplitSchur>(comm);
}

}  // namespace stiction::solvers
