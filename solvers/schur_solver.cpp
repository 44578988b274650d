#include "schur_solver.hpp"

#include "common/error.hpp"
#include "field_sets.hpp"
#include "solver_figures.hpp"
#include "stdout_capture.hpp"

namespace stiction::solvers {

SchurSolver::SchurSolver(const std::string& name, MPI_Comm comm)
    : KspSolver(name, comm), hp_(comm, options_prefix(name)) {
  MPI_Comm_size(comm, &processes_);
  // PETSc's SOR on a distributed matrix sweeps each process's rows only (MatSOR_MPIAIJ has
  // no global sweep): the qq_ and pp_ sweeps become the process-local symmetric ones, which
  // PCSetFromOptions applies after -qq_pc_sor_symmetric.
  if (processes_ > 1) {
    const std::string prefix = "-" + options_prefix(name);
    for (const char* key : {"qq_pc_sor_local_symmetric", "pp_pc_sor_local_symmetric"})
      STICTION_PETSC(PetscOptionsSetValue(nullptr, (prefix + key).c_str(), nullptr));
  }
}

void SchurSolver::configure(const nonlinear::NewtonSystem& system) {
  const auto* linear = system.field("u_l");
  const auto* quadratic = system.field("u_q");
  if (!linear || !quadratic)
    throw Error(name() + " needs a P2 displacement field split into u_l and u_q (scene basis p2-hierarchical)");
  PC pc;
  STICTION_PETSC(KSPGetPC(ksp(), &pc));
  hp_.setup(system.matrix, linear->is, quadratic->is, system.near_null_space, linear->block_size);
  const auto* pressure = system.field("p");
  const ShellPreconditioner* inner = &hp_;
  std::string name = "HP (10): A_ll^-1 then S~^-1 on u_q; the ll_ and qq_ solvers are listed below";
  if (pressure) {
    if (!mhp_) mhp_ = std::make_unique<MixedPreconditioner>(system.comm, options_prefix(this->name()), hp_);
    if (!displacement_) displacement_ = union_of_fields(system, {"u_l", "u_q"});
    mhp_->setup(system.matrix, displacement_, pressure->is, system.pressure_mass, system.mixed_shear_modulus,
                system.mixed_bulk_modulus);
    inner = mhp_.get();
    name = "MHP (11): alpha M_p on p (pp_ solver), then HP (10) on u (ll_ and qq_ solvers)";
  }
  if (const auto* lambda = system.field("lambda")) {
    if (!contact_) contact_ = std::make_unique<ContactPreconditioner>(system.comm, options_prefix(this->name()));
    contact_->setup(system.matrix, lambda->is, system.multiplier_surface, *inner);
    inner = contact_.get();
    name = "global Schur level (33) (factors: contact_fact) with " + std::string(pressure ? "MHP (11)" : "HP (10)") +
           " for A^-1 and S~ = D + G (G: contact_schur, fractional in its dense or rational form, or the mass (32)) by the ss_ solver";
  }
  use_as_shell(pc, *inner, name.c_str());
}

void SchurSolver::release() {
  KspSolver::release();
  hp_.release();
  if (mhp_) mhp_->release();
  if (contact_) contact_->release();
}

void SchurSolver::collect_setup_figures(std::map<std::string, double>& extra) const {
  // Of memory_setup_MB: the blocks held as copies (the rest: inner factors, AMG hierarchy).
  extra["memory_block_copies_MB"] = hp_.copied_blocks_mb() + (mhp_ ? mhp_->copied_blocks_mb() : 0.0) +
                                    (contact_ ? contact_->copied_blocks_mb() : 0.0);
  add_mumps_figures(hp_.linear_solver(), "ll_", extra);
  double c = parse_operator_complexity(setup_output());  // BoomerAMG prints it
  if (!(c > 0)) c = mg_operator_complexity(hp_.linear_solver());  // GAMG is asked
  if (c > 0) extra["amg_operator_complexity"] = c;
  if (contact_) {
    extra["contact_schur_scale"] = contact_->scale();
    extra["contact_scale_diagonal"] = contact_->scale_estimates().diagonal;
    extra["contact_scale_smooth"] = contact_->scale_estimates().smooth;
    const FractionalFit& fit = contact_->fractional_fit();
    extra["contact_schur_fractional"] = fit.fitted ? 1 : 0;  // 0: the scaled mass (32)
    if (fit.fitted) {
      extra["contact_fractional_beta"] = fit.beta;
      extra["contact_fractional_mu_max"] = fit.mu_max;
      extra["contact_fractional_rows"] = fit.rows;
      extra["contact_fractional_nodes"] = fit.rational_terms;  // 0: the dense form
      if (fit.rational_terms > 0) extra["contact_fractional_error"] = fit.rational_error;
    }
  }
}

std::string SchurSolver::describe() const {
  std::string text = KspSolver::describe() + "\nLinear block A_ll solver:\n" + full_view(hp_.linear_solver()) +
                     "\nQuadratic block solver:\n" + full_view(hp_.quadratic_solver());
  if (mhp_) text += "\nPressure block (alpha M_p) solver:\n" + full_view(mhp_->pressure_solver());
  if (contact_) text += "\nContact Schur approximation (32) solver:\n" + full_view(contact_->schur_solver());
  return text;
}

std::unique_ptr<nonlinear::LinearSolver> make_schur_lu(MPI_Comm comm) {
  return std::make_unique<SchurSolver>("schur-lu", comm);
}

std::unique_ptr<nonlinear::LinearSolver> make_schur_amg(MPI_Comm comm) {
  return std::make_unique<SchurSolver>("schur-amg", comm);
}

std::unique_ptr<nonlinear::LinearSolver> make_schur_gamg(MPI_Comm comm) {
  return std::make_unique<SchurSolver>("schur-gamg", comm);
}

}  // namespace stiction::solvers
