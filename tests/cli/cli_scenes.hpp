#pragma once
// Scene texts the CLI tests write to disk and vary.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

namespace stiction::test {

// harness/scenes/cantilever-2d.toml without its comments: solves in well under a second.
inline constexpr const char* cantilever_2d_scene = R"([scene]
name = "cantilever-2d"
description = "plane-strain Neo-Hookean cantilever under an end shear traction"

[[material]]
name = "soft"
model = "neo-hookean"
E = 1000.0
nu = 0.3

[[body]]
name = "beam"
material = "soft"
mesh = { generator = "box", size = [10.0, 1.0], h = 0.25 }

[[dirichlet]]
boundary = "xmin"
components = ["x", "y"]
value = [0.0, 0.0]

[[traction]]
boundary = "xmax"
value = [0.0, -1.0]

[load]
steps = 4
)";

// A variant of the cantilever-2d scene, edited by exact text replacement.
struct SceneVariant {
  std::string text = cantilever_2d_scene;

  SceneVariant& replace(const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    if (at == std::string::npos) ADD_FAILURE() << "scene text has no '" << from << "'";
    else text.replace(at, from.size(), to);
    return *this;
  }

  SceneVariant& append(const std::string& more) {
    text += more;
    return *this;
  }

  // 1-based line of the first occurrence of `needle` (0 if absent).
  int line_of(const std::string& needle) const {
    const auto at = text.find(needle);
    if (at == std::string::npos) return 0;
    return 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
  }

  std::filesystem::path write(const std::filesystem::path& dir, const std::string& name) const {
    const std::filesystem::path path = dir / name;
    std::ofstream(path) << text;
    return path;
  }
};

}  // namespace stiction::test
