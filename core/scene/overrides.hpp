#pragma once
// Scene keys set from the command line (`stiction solve SCENE --set KEY=VALUE`), so that a
// sweep can vary any key of a scene without writing a file per value: KEY is a dotted path
// whose array-of-tables entries carry an index (contact[0].friction, material[1].E,
// newton.krylov_rtol), VALUE a TOML value (0.6, "exact", [1.0, 2.0], true). The scene is then
// validated as if the file held the value.
#include <string>
#include <vector>

namespace stiction::scene {

// The TOML text with every override applied (missing tables along a path are created;
// indexed entries must exist). Throws stiction::Error (bad input) naming the override.
std::string apply_overrides(const std::string& text, const std::vector<std::string>& overrides,
                            const std::string& origin);

}  // namespace stiction::scene
