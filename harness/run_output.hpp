#pragma once
// What `stiction solve` writes as its load steps finish: the step, iteration and contact
// tables (CSV), a checkpoint after every completed load step and that step's VTU. Process 0
// writes everything but, on several processes, the VTU pieces: each process writes the piece
// of its own cells, and process 0 a PVTU that joins them.
#include <memory>
#include <string>

#include "nonlinear/newton.hpp"
#include "result_tables.hpp"
#include "run_scene.hpp"
#include "vtu_writer.hpp"

namespace stiction::harness {

class RunOutput {
public:
  // append: a restarted run adds to the tables it finds in dir.
  RunOutput(const RunScene& run, const nonlinear::QuasiStaticSolver& newton, std::string dir,
            const std::string& header, bool append, bool write_vtu);
  // The rows of a converged increment or a failed load step.
  void add_rows(const nonlinear::StepResult& r);
  // After a completed load step (collective: the checkpoint gathers the state on process 0).
  void complete_step(const nonlinear::StepResult& r);

private:
  void write_step_vtu(const nonlinear::StepResult& r);

  const RunScene& run_;
  const nonlinear::QuasiStaticSolver& newton_;
  std::string dir_;
  int rank_ = 0, processes_ = 1;
  bool write_vtu_;
  std::unique_ptr<StepTable> steps_;
  std::unique_ptr<IterationTable> iterations_;
  std::unique_ptr<ContactTable> contacts_;
  std::unique_ptr<PvdCollection> pvd_;
};

}  // namespace stiction::harness
