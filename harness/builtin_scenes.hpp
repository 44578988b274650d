#pragma once
// Built-in scenes: the TOML files of harness/scenes/, embedded in the executable.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace stiction::harness {

const std::map<std::string, std::string>& builtin_scenes();  // name -> TOML text
// SCENE is a path to a .toml file or a built-in name; throws listing the built-ins.
// overrides: KEY=VALUE settings of scene keys (scene/overrides.hpp).
std::unique_ptr<scene::Scene> open_scene(const std::string& scene, int level,
                                         const std::vector<std::string>& overrides = {});
// First comment line of a scene file (what it shows).
std::string scene_summary(const std::string& toml_text);

}  // namespace stiction::harness
