#include "builtin_scenes.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <sstream>

#include "common/error.hpp"
#include "scene/overrides.hpp"

namespace stiction::harness {

const std::map<std::string, std::string>& embedded_scenes();  // generated

const std::map<std::string, std::string>& builtin_scenes() { return embedded_scenes(); }

std::unique_ptr<scene::Scene> open_scene(const std::string& name, int level, const std::vector<std::string>& overrides) {
  if (std::filesystem::is_regular_file(name)) return scene::load_scene_file(name, level, overrides);
  auto it = builtin_scenes().find(name);
  if (it != builtin_scenes().end())
    return scene::build_scene(scene::apply_overrides(it->second, overrides, "built-in:" + name), "built-in:" + name,
                              ".", level);
  std::string names;
  for (const auto& [n, text] : builtin_scenes()) names += (names.empty() ? "" : ", ") + n;
  throw Error(fmt::format("scene '{}' is neither a file nor a built-in scene (built-in: {})", name, names));
}

std::string scene_summary(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("# ", 0) == 0) return line.substr(2);
  return "";
}

}  // namespace stiction::harness
