// boomeramg: GMRES with one BoomerAMG V-cycle on the whole system (options/boomeramg.opts).
// Block size (dim) reaches hypre through the matrix; the operator complexity is read from
// hypre's set-up statistics.
#include "ksp_solver.hpp"
#include "stdout_capture.hpp"

namespace stiction::solvers {

namespace {

class BoomerAmg final : public KspSolver {
public:
  explicit BoomerAmg(MPI_Comm comm) : KspSolver("boomeramg", comm) {}

protected:
  bool capture_setup_output() const override { return true; }
  void collect_setup_figures(std::map<std::string, double>& extra) const override {
    const double c = parse_operator_complexity(setup_output());
    if (c > 0) extra["amg_operator_complexity"] = c;
  }
};

}  // namespace

std::unique_ptr<nonlinear::LinearSolver> make_boomeramg(MPI_Comm comm) { return std::make_unique<BoomerAmg>(comm); }

}  // namespace stiction::solvers
