#pragma once
// A scene: bodies (mesh source + material), boundary conditions, load steps, Newton
// settings and outputs, read from a TOML file whose schema is declared in scene.cpp.
// The builder creates only what the scene names. The linear solver never appears in a
// scene: scene x solver x mesh level is the harness's sweep.
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "fem/field_space.hpp"
#include "materials/material.hpp"
#include "mesh/mesh.hpp"
#include "nonlinear/newton.hpp"
#include "nonlinear/problem.hpp"
#include "scene/schema.hpp"

namespace stiction::scene {

// How a VTU stores its arrays: zlib-compressed binary in VTK's appended section, or ASCII
// (larger and slower, for diffing and debugging).
enum class VtuFormat { Binary, Ascii };

struct OutputSettings {
  bool vtu = true;  // VTU per load step + PVD collection
  VtuFormat vtu_format = VtuFormat::Binary;
  bool csv = true;  // per-step quantities
};

struct Scene {
  std::string name;
  std::string description;
  std::string origin;  // file path or "built-in:<name>"
  int level = 0;
  int file_level = 0;  // the level the scene file asks for ([scene] level), which --level overrides
  mesh::Mesh mesh;     // all bodies, merged, at `level`
  // Whether every level is the uniform refinement of level 0 (false when a body's generator
  // re-meshes each level: curved Gmsh geometry, spheres, tubes), so that level 0 refined in
  // mesh parts is the scene's own finer level (scene::divide_scene).
  bool levels_by_refinement = true;
  std::vector<std::string> body_names;
  std::vector<int> body_of_cell;
  std::vector<std::unique_ptr<materials::Material>> materials;
  std::vector<std::string> material_of_body;  // descriptions, for reports
  std::unique_ptr<fem::FieldSpace> space;
  std::vector<std::unique_ptr<nonlinear::MultiplierConstraint>> contacts;  // problem.constraints
  nonlinear::ElasticityProblem problem;
  nonlinear::NewtonSettings newton;
  OutputSettings output;
  // Pseudo-time where the short version of the scene stops (`--quick`: the test suite's
  // runs of long scenes); infinity: the whole run.
  double quick_until = std::numeric_limits<double>::infinity();

  Scene() = default;
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;
};

// The declared schema of a scene file (for documentation and validation).
const TableSpec& scene_schema();

// Parses and builds a scene. `text` is the TOML source, `origin` names it in messages,
// `base_dir` resolves relative mesh paths; `level` >= 0 overrides the scene's mesh level.
std::unique_ptr<Scene> build_scene(const std::string& text, const std::string& origin, const std::string& base_dir,
                                   int level = -1);
// Reads a scene file from disk; overrides: KEY=VALUE settings of its keys (overrides.hpp).
std::unique_ptr<Scene> load_scene_file(const std::string& path, int level = -1,
                                       const std::vector<std::string>& overrides = {});

}  // namespace stiction::scene
