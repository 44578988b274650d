#include "run_scene.hpp"

#include <fmt/format.h>

#include <utility>

#include "builtin_scenes.hpp"
#include "common/error.hpp"

namespace stiction::harness {

RunScene open_run_scene(MPI_Comm comm, const std::string& name, int level, const std::vector<std::string>& overrides,
                        bool whole_mesh) {
  int processes = 1;
  MPI_Comm_size(comm, &processes);
  RunScene run;
  if (processes == 1 || whole_mesh) {
    run.scene = open_scene(name, level, overrides);
    run.view.emplace(*run.scene);
    return run;
  }
  // Level 0 first: it tells whether the scene has contact and how its levels are made, and
  // is the mesh that is divided when they are refinements of it.
  run.scene = open_scene(name, 0, overrides);
  const int wanted = level >= 0 ? level : run.scene->file_level;
  if (wanted < 0 || wanted > 4)
    throw Error(fmt::format("scene '{}': mesh level {} outside 0..4", run.scene->name, wanted), ErrorKind::Input);
  if (wanted > 0 && !run.scene->levels_by_refinement) run.scene = open_scene(name, wanted, overrides);
  run.refined_in_parts = run.scene->level == wanted ? 0 : wanted;
  run.part = scene::divide_scene(comm, *run.scene, run.refined_in_parts);
  run.view.emplace(scene::view_of_part(comm, *run.scene, *run.part, wanted));
  scene::release_whole_mesh(*run.scene);  // the parts hold all a process needs
  return run;
}

std::unique_ptr<nonlinear::QuasiStaticSolver> make_quasi_static_solver(MPI_Comm comm, RunScene& run,
                                                                       nonlinear::LinearSolver& linear) {
  const scene::Scene& s = *run.scene;
  if (!run.part) return std::make_unique<nonlinear::QuasiStaticSolver>(comm, s.problem, s.newton, linear);
  return std::make_unique<nonlinear::QuasiStaticSolver>(comm, run.part->problem, run.part->part,
                                                        std::move(run.part->ownership), s.newton, linear);
}

}  // namespace stiction::harness
