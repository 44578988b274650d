#include "ksp_solver.hpp"

#include <HYPRE_utilities.h>

#include "solver_figures.hpp"
#include "stdout_capture.hpp"
#include "common/process_memory.hpp"

#include <fmt/format.h>

#include <chrono>
#include <memory>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>
#include <map>
#include <sstream>

namespace stiction::solvers {

const std::map<std::string, std::string>& embedded_options();  // generated

std::string options_prefix(const std::string& name) {
  std::string p = name;
  for (char& c : p)
    if (c == '-') c = '_';
  return p + "_";
}

std::string compact_options(const std::string& name) {
  std::istringstream lines(default_options(name));
  std::string line, out;
  while (std::getline(lines, line)) {
    line = line.substr(0, line.find('#'));
    while (!line.empty() && line.back() == ' ') line.pop_back();
    if (!line.empty()) out += (out.empty() ? "" : " ") + line;
  }
  return out;
}

// An options file's text with each "@include <name> [<key prefix>]" line replaced by the
// text of the embedded file <name>.opts (the parts several backends share), recursively;
// with a key prefix ("ll_"), every option of the included text gets it ("-pc_type" becomes
// "-ll_pc_type"), so one set of settings serves a whole system and an inner block.
std::string default_options(const std::string& name) {
  const auto& all = embedded_options();
  auto it = all.find(name);
  if (it == all.end()) return {};
  std::istringstream lines(it->second);
  std::string line, out;
  const std::string directive = "@include ";
  while (std::getline(lines, line)) {
    if (line.rfind(directive, 0) != 0) {
      out += line + "\n";
      continue;
    }
    std::istringstream words(line.substr(directive.size()));
    std::string part, key_prefix;
    words >> part >> key_prefix;
    if (!all.count(part)) throw Error(fmt::format("options file '{}': no embedded options '{}' to include", name, part), ErrorKind::Internal);
    std::istringstream included(default_options(part));
    while (std::getline(included, line))
      out += (line.rfind('-', 0) == 0 ? "-" + key_prefix + line.substr(1) : line) + "\n";
  }
  return out;
}

bool backend_option_given(const std::string& name, const std::string& key) {
  PetscBool given = PETSC_FALSE;
  STICTION_PETSC(PetscOptionsHasName(nullptr, nullptr, ("-" + options_prefix(name) + key).c_str(), &given));
  return given;
}

namespace {

// Sets each "-key [value]" line of an options file under the prefix, unless the user has
// already given that option (the command line wins over the file).
void insert_defaults(const std::string& prefix, const std::string& text) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string key, value;
    if (!(words >> key)) continue;
    words >> value;
    const std::string full = "-" + prefix + key.substr(1);
    PetscBool set = PETSC_FALSE;
    STICTION_PETSC(PetscOptionsHasName(nullptr, nullptr, full.c_str(), &set));
    if (!set) STICTION_PETSC(PetscOptionsSetValue(nullptr, full.c_str(), value.empty() ? nullptr : value.c_str()));
  }
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

// PETSc's default test, then the stagnation test (ksp_solver.hpp) on the residual history.
struct KspSolver::StagnationTest {
  void* default_context = nullptr;
  PetscInt window = 500;
  PetscReal margin = 3;
  // The residual the relative tolerance refers to: ||b||, which a continued solve (nonzero
  // initial guess) passes here; 0: the first residual of the solve (a zero initial guess).
  PetscReal reference = 0;
  std::vector<PetscReal> history;
  bool fired = false;

  static PetscErrorCode test(KSP ksp, PetscInt it, PetscReal rnorm, KSPConvergedReason* reason, void* context) {
    auto* self = static_cast<StagnationTest*>(context);
    PetscCall(KSPConvergedDefault(ksp, it, rnorm, reason, self->default_context));
    if (it == 0) self->fired = false;
    self->history.resize(it + 1);  // GMRES may test an iteration twice (at a restart)
    self->history[it] = rnorm;
    if (*reason != KSP_CONVERGED_ITERATING || self->margin <= 0 || self->window <= 0 || it < self->window) return 0;
    PetscReal rtol, abstol, dtol;
    PetscInt max_it;
    PetscCall(KSPGetTolerances(ksp, &rtol, &abstol, &dtol, &max_it));
    const PetscReal before = self->history[it - self->window];
    const PetscReal target = std::max(rtol * (self->reference > 0 ? self->reference : self->history.front()), abstol);
    // Iterations still needed at the window's mean rate (infinite without progress).
    const double needed = rnorm < before ? std::log(target / rnorm) / (std::log(rnorm / before) / self->window)
                                         : std::numeric_limits<double>::infinity();
    if (needed > self->margin * static_cast<double>(max_it - it)) {
      *reason = KSP_DIVERGED_ITS;
      self->fired = true;
    }
    return 0;
  }
  static PetscErrorCode destroy(void* context) {
    auto* self = static_cast<StagnationTest*>(context);
    PetscCall(KSPConvergedDefaultDestroy(self->default_context));
    delete self;
    return 0;
  }
};

KspSolver::KspSolver(std::string name, MPI_Comm comm) : name_(std::move(name)), comm_(comm) {
  create_ksp();
  insert_defaults(options_prefix(name_), default_options(name_));
}

void KspSolver::create_ksp() {
  stagnation_ = nullptr;  // the old KSP's convergence context went with it
  krylov_mb_ = 0;
  STICTION_PETSC(KSPCreate(comm_, ksp_.out()));
  STICTION_PETSC(KSPSetOptionsPrefix(ksp_, options_prefix(name_).c_str()));
}

void KspSolver::setup(const nonlinear::NewtonSystem& system) {
  const auto t0 = std::chrono::steady_clock::now();
  // hypre keeps a process-wide error flag that a failed set-up leaves raised (error 12 on
  // a saddle-point system); every later BoomerAMG set-up in the process would then fail.
  HYPRE_ClearAllErrors();
  // Some solvers print set-up statistics (hypre): keep them for the figures and the view.
  std::unique_ptr<StdoutCapture> capture;
  if (capture_setup_output()) capture = std::make_unique<StdoutCapture>();
  STICTION_PETSC(KSPSetOperators(ksp_, system.matrix, system.matrix));
  const double heap_before = heap_in_use_mb();
  configure(system);
  if (options_rtol_ > 0)
    STICTION_PETSC(KSPSetTolerances(ksp_, options_rtol_, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
  STICTION_PETSC(KSPSetFromOptions(ksp_));
  if (!(options_rtol_ > 0)) options_rtol_ = relative_tolerance();
  // A no-op for a KSP that is not GMRES or FGMRES (PETSc's KSPGMRESSetRestart tries the method).
  if (krylov_restart_ > 0) STICTION_PETSC(KSPGMRESSetRestart(ksp_, krylov_restart_));
  install_stagnation_test();
  if (estimates_singular_values()) STICTION_PETSC(KSPSetComputeSingularValues(ksp_, PETSC_TRUE));
  // A failed factorisation or preconditioner set-up (out of memory, zero pivot) is a
  // result of this backend on this system, not a program error: solve() reports it.
  setup_failure_ = refuse_setup(system);
  if (setup_failure_.empty()) try {
      STICTION_PETSC(KSPSetUp(ksp_));
      set_up_inner_solvers();
    } catch (const Error& e) {
      setup_failure_ = e.what();
    }
  if (capture) setup_output_ = capture->text();
  setup_seconds_ = seconds_since(t0);
  setup_extra_.clear();
  // Where the memory goes (MB): the Newton matrix, what the set-up kept (factors, AMG
  // hierarchies, copied blocks), and, after the solve, the Krylov space.
  setup_extra_["memory_matrix_MB"] = aij_storage_mb(system.matrix);
  setup_extra_["memory_setup_MB"] = heap_in_use_mb() - heap_before;
  collect_setup_figures(setup_extra_);
}

nonlinear::LinearSolveStats KspSolver::solve(const nonlinear::NewtonSystem& system, Vec x) {
  nonlinear::LinearSolveStats s;
  s.setup_seconds = setup_seconds_;
  s.extra = setup_extra_;
  if (!setup_failure_.empty()) {
    const auto colon = setup_failure_.rfind(": ");
    s.reason = "PC_SETUP_FAILED (" + setup_failure_.substr(colon == std::string::npos ? 0 : colon + 2) + ")";
    return s;
  }
  PetscReal bnorm, rnorm;
  STICTION_PETSC(VecNorm(system.rhs, NORM_2, &bnorm));
  // The Krylov tolerance is the inexact-Newton forcing term: report it with every solve.
  KSPType type;
  STICTION_PETSC(KSPGetType(ksp_, &type));
  const double heap_before = heap_in_use_mb();
  if (std::string(type) != KSPPREONLY) {
    PetscReal rtol, abstol, dtol;
    PetscInt max_it;
    STICTION_PETSC(KSPGetTolerances(ksp_, &rtol, &abstol, &dtol, &max_it));
    s.extra["ksp_rtol"] = rtol;
    s.extra["ksp_max_it"] = static_cast<double>(max_it);
  }
  if (type == std::string(KSPGMRES) || type == std::string(KSPFGMRES)) {
    PetscInt restart;
    STICTION_PETSC(KSPGMRESGetRestart(ksp_, &restart));
    s.extra["ksp_gmres_restart"] = static_cast<double>(restart);
  }
  const auto t0 = std::chrono::steady_clock::now();
  STICTION_PETSC(KSPSolve(ksp_, system.rhs, x));
  s.solve_seconds = seconds_since(t0);
  krylov_mb_ += heap_in_use_mb() - heap_before;  // the work vectors the KSP added, kept for later solves
  s.extra["memory_krylov_MB"] = krylov_mb_;
  s.extra["memory_heap_MB"] = heap_in_use_mb();
  // Resident memory now and at its peak so far, and what the allocator holds freed: a
  // resident peak far above the heap in use is fragmentation or a transient of one phase.
  s.extra["memory_heap_free_MB"] = heap_free_mb();
  s.extra["memory_mapped_MB"] = mapped_blocks_mb();
  s.extra["memory_resident_MB"] = resident_mb();
  s.extra["memory_peak_resident_MB"] = peak_resident_mb();
  KSPConvergedReason reason;
  PetscInt its;
  STICTION_PETSC(KSPGetConvergedReason(ksp_, &reason));
  STICTION_PETSC(KSPGetIterationNumber(ksp_, &its));
  // True residual: left-preconditioned Krylov methods stop on the preconditioned one.
  PetscVec r;
  STICTION_PETSC(VecDuplicate(system.rhs, r.out()));
  STICTION_PETSC(MatMult(system.matrix, x, r));
  STICTION_PETSC(VecAYPX(r, -1.0, system.rhs));
  STICTION_PETSC(VecNorm(r, NORM_2, &rnorm));
  s.iterations = static_cast<int>(its);
  s.reason = stagnation_ && stagnation_->fired ? "DIVERGED_STAGNATION" : KSPConvergedReasons[reason];
  s.initial_residual = bnorm;
  s.final_residual = rnorm;
  s.converged = reason > 0 && std::isfinite(rnorm);
  if (its > 0 && estimates_singular_values()) {
    PetscReal sigma_max = 0, sigma_min = 0;
    STICTION_PETSC(KSPComputeExtremeSingularValues(ksp_, &sigma_max, &sigma_min));
    if (std::isfinite(sigma_max) && std::isfinite(sigma_min) && sigma_max > 0 && sigma_min > 0) {
      s.extra["sigma_max_estimate"] = sigma_max;
      s.extra["sigma_min_estimate"] = sigma_min;
      s.extra["condition_estimate"] = sigma_max / sigma_min;
    }
  }
  return s;
}

bool KspSolver::estimates_singular_values() const {
  KSPType type;
  STICTION_PETSC(KSPGetType(ksp_, &type));
  const std::string t = type ? type : "";
  return t == KSPGMRES || t == KSPFGMRES;
}

void KspSolver::install_stagnation_test() {
  KSPType type;
  STICTION_PETSC(KSPGetType(ksp_, &type));
  void* current = nullptr;
  STICTION_PETSC(KSPGetConvergenceContext(ksp_, &current));
  if (std::string(type) == KSPPREONLY || (stagnation_ && current == stagnation_)) return;
  auto test = std::make_unique<StagnationTest>();
  const std::string prefix = options_prefix(name_);
  STICTION_PETSC(PetscOptionsGetInt(nullptr, prefix.c_str(), "-ksp_stagnation_window", &test->window, nullptr));
  STICTION_PETSC(PetscOptionsGetReal(nullptr, prefix.c_str(), "-ksp_stagnation_margin", &test->margin, nullptr));
  STICTION_PETSC(KSPConvergedDefaultCreate(&test->default_context));
  STICTION_PETSC(KSPSetConvergenceTest(ksp_, StagnationTest::test, test.get(), StagnationTest::destroy));
  stagnation_ = test.release();
}

PetscInt KspSolver::continuation_restart(PetscInt m, PetscInt n_local) const {
  const std::string prefix = options_prefix(name_);
  PetscReal factor = 3, budget_mb = 1024;
  STICTION_PETSC(PetscOptionsGetReal(nullptr, prefix.c_str(), "-ksp_stagnation_restart_factor", &factor, nullptr));
  STICTION_PETSC(PetscOptionsGetReal(nullptr, prefix.c_str(), "-ksp_stagnation_restart_mb", &budget_mb, nullptr));
  if (!(factor > 1) || n_local <= 0) return m;
  // GMRES holds restart + 1 basis vectors and a few work vectors (VEC_OFFSET in PETSc's gmres).
  constexpr PetscInt kWorkVectors = 3;
  const double fits = budget_mb * 1024 * 1024 / (8.0 * static_cast<double>(n_local)) - 1 - kWorkVectors;
  const double longer = std::min(std::floor(factor * static_cast<double>(m)), fits);
  return longer > static_cast<double>(m) ? static_cast<PetscInt>(longer) : m;
}

bool KspSolver::continue_longer(const nonlinear::NewtonSystem& system, Vec x, nonlinear::LinearSolveStats& s) {
  KSPType type;
  STICTION_PETSC(KSPGetType(ksp_, &type));
  if (!setup_failure_.empty() || !stagnation_ || !stagnation_->fired || !type ||
      (std::string(type) != KSPGMRES && std::string(type) != KSPFGMRES))
    return false;
  PetscInt m, n_local;
  STICTION_PETSC(KSPGMRESGetRestart(ksp_, &m));
  STICTION_PETSC(VecGetLocalSize(system.rhs, &n_local));
  // Every process must take the same branch: the smallest budget decides.
  PetscInt longer = continuation_restart(m, n_local);
  MPI_Allreduce(MPI_IN_PLACE, &longer, 1, MPIU_INT, MPI_MIN, comm_);
  if (longer <= m) return false;
  // The longer cycle from x, measured against ||b||; the settings are put back on the way out.
  struct Settings {
    KSP ksp;
    StagnationTest* test;
    PetscInt restart;
    ~Settings() {
      test->reference = 0;
      KSPSetInitialGuessNonzero(ksp, PETSC_FALSE);
      KSPGMRESSetRestart(ksp, restart);
    }
  } restore{ksp_, stagnation_, m};
  STICTION_PETSC(KSPGMRESSetRestart(ksp_, longer));
  STICTION_PETSC(KSPSetInitialGuessNonzero(ksp_, PETSC_TRUE));
  stagnation_->reference = s.initial_residual;
  nonlinear::LinearSolveStats more = solve(system, x);
  more.extra["krylov_iterations_before_continuing"] = s.iterations;
  more.extra["krylov_continued_restart"] = static_cast<double>(longer);
  more.extra["ksp_gmres_restart"] = static_cast<double>(m);  // the solve's own restart, before the continuation's
  more.iterations += s.iterations;
  more.solve_seconds += s.solve_seconds;
  more.initial_residual = s.initial_residual;
  s = std::move(more);
  return true;
}

void KspSolver::release() {
  // KSPReset keeps the type and options; the next setup() builds everything afresh, as it
  // would for a new matrix anyway. After a failed set-up the KSP is replaced instead: PETSc
  // 3.18's hypre PC, reset after a failed BoomerAMG set-up, keeps pointers to the IJ vectors
  // it freed and frees them again when the KSP is destroyed (valgrind: invalid reads in
  // HYPRE_IJVectorDestroy, then an abort in PetscFinalize, when a run retried an increment
  // after boomeramg's set-up had failed on sliding-block-2d). Either way the Krylov vectors
  // go too: kept for the next system instead (PCReset alone), the resident peak of
  // block-strips level 1 with schur-amg rose from 1 037 to 1 200 MB.
  krylov_mb_ = 0;
  if (setup_failure_.empty()) STICTION_PETSC(KSPReset(ksp_));
  else create_ksp();
}

void KspSolver::set_relative_tolerance(double rtol) {
  STICTION_PETSC(KSPSetTolerances(ksp_, rtol, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
}

double KspSolver::relative_tolerance() const {
  KSPType type;
  STICTION_PETSC(KSPGetType(ksp_, &type));
  if (type && std::string(type) == KSPPREONLY) return 0;
  PetscReal rtol, abstol, dtol;
  PetscInt max_it;
  STICTION_PETSC(KSPGetTolerances(ksp_, &rtol, &abstol, &dtol, &max_it));
  return rtol;
}

void KspSolver::apply_preconditioner(Vec in, Vec out) const {
  PC pc;
  STICTION_PETSC(KSPGetPC(ksp_, &pc));
  STICTION_PETSC(PCApply(pc, in, out));
}

std::string KspSolver::describe() const {
  std::string text = full_view(ksp_);
  if (stagnation_)
    text += stagnation_->margin > 0 && stagnation_->window > 0
                ? fmt::format("stagnation test: stop when the last {} iterations' rate needs over {:g} x the "
                              "iterations left\n",
                              stagnation_->window, stagnation_->margin)
                : std::string("stagnation test: off\n");
  if (!setup_output_.empty()) text += "\nSet-up statistics printed by the solver:\n" + setup_output_;
  return text;
}

}  // namespace stiction::solvers
