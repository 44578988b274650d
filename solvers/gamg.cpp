// gamg: GMRES with PETSc's smoothed-aggregation AMG (PCGAMG) on the whole system, with the
// rigid-body modes the Newton matrix carries as its near-null space (options/gamg.opts).
// Aggregation AMG is built for the elliptic displacement operator: a system with a pressure
// or multiplier block is a saddle point (zero or negative diagonal there), and set-up is
// refused with that reason; schur-gamg puts GAMG inside the paper's hierarchy instead.
#include "ksp_solver.hpp"
#include "solver_figures.hpp"

namespace stiction::solvers {

namespace {

class Gamg final : public KspSolver {
public:
  explicit Gamg(MPI_Comm comm) : KspSolver("gamg", comm) {}

protected:
  std::string refuse_setup(const nonlinear::NewtonSystem& system) override {
    for (const char* block : {"p", "lambda"})
      if (system.field(block))
        return std::string("gamg is an AMG for the displacement operator alone and this system has a ") +
               (block[0] == 'p' ? "pressure" : "contact multiplier") +
               " block (a saddle point), for which schur-gamg or fieldsplit-schur is made";
    return {};
  }
  void collect_setup_figures(std::map<std::string, double>& extra) const override {
    const double c = mg_operator_complexity(ksp());
    if (c > 0) extra["amg_operator_complexity"] = c;
  }
};

}  // namespace

std::unique_ptr<nonlinear::LinearSolver> make_gamg(MPI_Comm comm) { return std::make_unique<Gamg>(comm); }

}  // namespace stiction::solvers
