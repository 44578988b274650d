#include "scene/overrides.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <sstream>

#include "common/error.hpp"

namespace stiction::scene {

namespace {

struct Segment {
  std::string key;
  int index = -1;  // entry of an array of tables (-1: a plain key)
};

std::vector<Segment> parse_path(const std::string& path, const std::string& what) {
  std::vector<Segment> segments;
  std::istringstream parts(path);
  for (std::string part; std::getline(parts, part, '.');) {
    Segment s;
    const auto bracket = part.find('[');
    s.key = part.substr(0, bracket);
    if (bracket != std::string::npos) {
      const auto close = part.find(']', bracket);
      if (close != part.size() - 1) throw Error(fmt::format("{}: '{}' is not key[index]", what, part));
      try {
        s.index = std::stoi(part.substr(bracket + 1, close - bracket - 1));
      } catch (const std::exception&) {
        throw Error(fmt::format("{}: '{}' has no integer index", what, part));
      }
      if (s.index < 0) throw Error(fmt::format("{}: negative index in '{}'", what, part));
    }
    if (s.key.empty()) throw Error(fmt::format("{}: empty key in '{}'", what, path));
    segments.push_back(s);
  }
  if (segments.empty()) throw Error(fmt::format("{}: no key", what));
  return segments;
}

void apply(toml::table& root, const std::string& override_text, const std::string& origin) {
  const std::string what = fmt::format("--set '{}' on {}", override_text, origin);
  const auto eq = override_text.find('=');
  if (eq == std::string::npos) throw Error(fmt::format("{}: expected KEY=VALUE", what));
  const auto path = parse_path(override_text.substr(0, eq), what);
  toml::table value_holder;
  try {
    value_holder = toml::parse("value = " + override_text.substr(eq + 1));
  } catch (const toml::parse_error& e) {
    throw Error(fmt::format("{}: the value is not TOML ({})", what, e.description()));
  }
  toml::table* table = &root;
  for (size_t k = 0; k + 1 < path.size(); ++k) {
    const Segment& s = path[k];
    if (s.index >= 0) {
      toml::array* entries = (*table)[s.key].as_array();
      if (!entries || s.index >= static_cast<int>(entries->size()) || !(*entries)[s.index].as_table())
        throw Error(fmt::format("{}: the scene has no {}[{}]", what, s.key, s.index));
      table = (*entries)[s.index].as_table();
    } else {
      if (!(*table)[s.key]) table->insert(s.key, toml::table{});
      table = (*table)[s.key].as_table();
      if (!table) throw Error(fmt::format("{}: '{}' is not a table", what, s.key));
    }
  }
  if (path.back().index >= 0) throw Error(fmt::format("{}: the last key cannot be indexed", what));
  table->insert_or_assign(path.back().key, *value_holder["value"].node());
}

}  // namespace

std::string apply_overrides(const std::string& text, const std::vector<std::string>& overrides,
                            const std::string& origin) {
  if (overrides.empty()) return text;
  toml::table root;
  try {
    root = toml::parse(text, origin);
  } catch (const toml::parse_error&) {
    return text;  // the scene's own parse error is reported where it is built, with its line
  }
  for (const auto& o : overrides) apply(root, o, origin);
  std::ostringstream out;
  out << root;
  return out.str();
}

}  // namespace stiction::scene
