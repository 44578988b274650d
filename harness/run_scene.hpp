#pragma once
// The scene a solve runs on, and what each process holds of it. On one process, or when
// asked (--whole-mesh), every process builds the whole scene at the level asked. Otherwise
// each process holds only its part of the mesh and the space and problem over it
// (scene::divide_scene; with contact, the contact surfaces whole besides); when the scene's
// levels are uniform refinements of level 0, level 0 is divided and the parts refined where
// they are, so that the finer mesh is never whole on any process (the same mesh as the whole
// level; its cells are split as level 0's were). A scene whose levels are re-meshed is built
// whole at its level and then divided. Once divided, the whole mesh is freed.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <mpi.h>

#include "nonlinear/linear_solver.hpp"
#include "nonlinear/newton.hpp"
#include "scene/scene.hpp"
#include "scene/scene_part.hpp"
#include "scene/scene_view.hpp"

namespace stiction::harness {

struct RunScene {
  // Whole; divided, its settings, laws and loads alone (scene::release_whole_mesh).
  std::unique_ptr<scene::Scene> scene;
  std::unique_ptr<scene::ScenePart> part;  // this process's part; null: the whole scene is solved
  int refined_in_parts = 0;                // levels the parts were refined after division
  std::optional<scene::SceneView> view;    // what the outputs read

  int level() const { return view->level; }
};

// Collective. level < 0: the scene's own.
RunScene open_run_scene(MPI_Comm comm, const std::string& name, int level, const std::vector<std::string>& overrides,
                        bool whole_mesh);
// The Newton solver over what this process holds of the run's scene (the scene's settings).
// The part's ownership moves into the solver's layout (run.part->ownership is left empty).
std::unique_ptr<nonlinear::QuasiStaticSolver> make_quasi_static_solver(MPI_Comm comm, RunScene& run,
                                                                       nonlinear::LinearSolver& linear);

}  // namespace stiction::harness
