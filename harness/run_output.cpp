#include "run_output.hpp"

#include <fmt/format.h>

#include <vector>

#include "checkpoint.hpp"

namespace stiction::harness {

RunOutput::RunOutput(const RunScene& run, const nonlinear::QuasiStaticSolver& newton, std::string dir,
                     const std::string& header, bool append, bool write_vtu)
    : run_(run), newton_(newton), dir_(std::move(dir)) {
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank_);
  MPI_Comm_size(PETSC_COMM_WORLD, &processes_);
  const scene::Scene& scene = *run.scene;
  const scene::SceneView& view = *run.view;
  write_vtu_ = write_vtu && scene.output.vtu;
  if (rank_ != 0) return;
  if (scene.output.csv) {
    const bool contact = !view.problem->constraints.empty();
    if (contact) contacts_ = std::make_unique<ContactTable>(dir_ + "/contact.csv", header, view.dim(), append);
    steps_ = std::make_unique<StepTable>(dir_ + "/steps.csv", header, view, append);
    iterations_ = std::make_unique<IterationTable>(dir_ + "/iterations.csv", header, contact, append);
  }
  pvd_ = std::make_unique<PvdCollection>(dir_ + "/solution.pvd");
}

void RunOutput::add_rows(const nonlinear::StepResult& r) {
  if (steps_) steps_->add(r, *run_.view);
  if (iterations_) iterations_->add(r);
}

void RunOutput::complete_step(const nonlinear::StepResult& r) {
  // The checkpoint needs the whole state, gathered on process 0 (every process takes part);
  // the contact table reads the contact surfaces, which every process holds.
  const nonlinear::QuasiStaticSolver::State state = newton_.state();
  if (rank_ == 0)
    write_checkpoint(dir_ + "/checkpoint.bin",
                     {run_.scene->name, run_.level(), state, newton_.linear_tally(), newton_.cut_back()});
  if (contacts_) contacts_->add(r, *run_.view, newton_.held_displacement(), newton_.multipliers());
  if (write_vtu_) write_step_vtu(r);
}

void RunOutput::write_step_vtu(const nonlinear::StepResult& r) {
  const fem::StateView u = newton_.held_displacement();
  const std::string stem = fmt::format("step-{:03d}", r.step);
  if (processes_ == 1) {
    write_vtu(dir_ + "/" + stem + ".vtu", *run_.scene, u, newton_.multipliers(), r.time);
    pvd_->add(r.time, stem + ".vtu");
    return;
  }
  write_vtu_piece(fmt::format("{}/{}-p{}.vtu", dir_, stem, rank_), *run_.view, u, newton_.multipliers(), r.time,
                  newton_.partition().owned_cells, rank_);
  if (rank_ != 0) return;
  std::vector<std::string> pieces;
  for (int k = 0; k < processes_; ++k) pieces.push_back(fmt::format("{}-p{}.vtu", stem, k));
  write_pvtu(dir_ + "/" + stem + ".pvtu", *run_.view, newton_.multipliers(), pieces);
  pvd_->add(r.time, stem + ".pvtu");
}

}  // namespace stiction::harness
