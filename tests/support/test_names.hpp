#pragma once
// GoogleTest names allow letters, digits and '_' only: a scene name as a parameter's name.
#include <algorithm>
#include <string>

namespace stiction::test {

inline std::string identifier(std::string scene_name) {
  std::replace(scene_name.begin(), scene_name.end(), '-', '_');
  return scene_name;
}

}  // namespace stiction::test
