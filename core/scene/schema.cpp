#include "scene/schema.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "common/error.hpp"

namespace stiction::scene {

std::string to_string(ValueType t) {
  switch (t) {
    case ValueType::Integer: return "integer";
    case ValueType::Float: return "number";
    case ValueType::String: return "string";
    case ValueType::Boolean: return "boolean";
    case ValueType::FloatArray: return "array of numbers";
    case ValueType::FloatRows: return "array of arrays of numbers";
    case ValueType::StringArray: return "array of strings";
    case ValueType::Table: return "table";
    case ValueType::TableArray: return "array of tables";
  }
  return "?";
}

const KeySpec* TableSpec::find(const std::string& key) const {
  for (const auto& k : keys)
    if (k.name == key) return &k;
  return nullptr;
}

namespace {

std::string join_choices(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

std::string accepted_keys(const TableSpec& spec) {
  std::vector<std::string> names;
  for (const auto& k : spec.keys) names.push_back(k.name);
  return join_choices(names);
}

bool matches(const toml::node& n, ValueType t) {
  switch (t) {
    case ValueType::Integer: return n.is_integer();
    case ValueType::Float: return n.is_number();
    case ValueType::String: return n.is_string();
    case ValueType::Boolean: return n.is_boolean();
    case ValueType::FloatArray: {
      if (!n.is_array()) return false;
      for (const auto& e : *n.as_array())
        if (!e.is_number()) return false;
      return true;
    }
    case ValueType::FloatRows: {
      if (!n.is_array()) return false;
      for (const auto& row : *n.as_array())
        if (!matches(row, ValueType::FloatArray)) return false;
      return true;
    }
    case ValueType::StringArray: {
      if (!n.is_array()) return false;
      for (const auto& e : *n.as_array())
        if (!e.is_string()) return false;
      return true;
    }
    case ValueType::Table: return n.is_table();
    case ValueType::TableArray: return n.is_array_of_tables();
  }
  return false;
}

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table: return "table";
    case toml::node_type::array: return "array";
    case toml::node_type::string: return "string";
    case toml::node_type::integer: return "integer";
    case toml::node_type::floating_point: return "number";
    case toml::node_type::boolean: return "boolean";
    default: return "date/time";
  }
}

std::string line_of(const toml::node& n) {
  const auto& src = n.source();
  return src.begin.line ? fmt::format(" (line {})", src.begin.line) : "";
}

}  // namespace

void validate(const toml::table& table, const TableSpec& spec, const std::string& file, const std::string& path) {
  const std::string prefix = path.empty() ? "" : path + ".";
  for (const auto& [k, node] : table) {
    const std::string key(k.str());
    const KeySpec* ks = spec.find(key);
    if (!ks)
      throw Error(fmt::format("{}: unknown key '{}{}'{} (accepted in {}: {})", file, prefix, key, line_of(node),
                              spec.name.empty() ? "the scene" : "[" + spec.name + "]", accepted_keys(spec)));
    if (!matches(node, ks->type))
      throw Error(fmt::format("{}: key '{}{}'{} must be a {} (got {})", file, prefix, key, line_of(node),
                              to_string(ks->type), type_name(node)));
    if (!ks->choices.empty()) {
      std::vector<std::string> given;
      if (node.is_string()) given.push_back(node.as_string()->get());
      if (node.is_array())
        for (const auto& e : *node.as_array()) given.push_back(e.as_string()->get());
      for (const auto& g : given)
        if (std::find(ks->choices.begin(), ks->choices.end(), g) == ks->choices.end())
          throw Error(fmt::format("{}: key '{}{}'{} has value '{}' (accepted: {})", file, prefix, key, line_of(node), g,
                                  join_choices(ks->choices)));
    }
    if (ks->type == ValueType::Table) validate(*node.as_table(), *ks->table, file, prefix + key);
    if (ks->type == ValueType::TableArray) {
      int i = 0;
      for (const auto& e : *node.as_array())
        validate(*e.as_table(), *ks->table, file, fmt::format("{}{}[{}]", prefix, key, i++));
    }
  }
  for (const auto& ks : spec.keys)
    if (ks.required && !table.contains(ks.name))
      throw Error(fmt::format("{}: missing required key '{}{}' ({})", file, prefix, ks.name, ks.doc));
}

std::string document(const TableSpec& spec, const std::string& indent) {
  std::string out;
  for (const auto& k : spec.keys) {
    std::string def;
    if (k.required) def = "required";
    else if (auto* i = std::get_if<std::int64_t>(&k.fallback)) def = fmt::format("default {}", *i);
    else if (auto* d = std::get_if<double>(&k.fallback)) def = fmt::format("default {:g}", *d);
    else if (auto* s = std::get_if<std::string>(&k.fallback)) def = fmt::format("default \"{}\"", *s);
    else if (auto* b = std::get_if<bool>(&k.fallback)) def = fmt::format("default {}", *b ? "true" : "false");
    else def = "optional";
    out += fmt::format("{}{} ({}, {}): {}", indent, k.name, to_string(k.type), def, k.doc);
    if (!k.choices.empty()) out += fmt::format(" [{}]", join_choices(k.choices));
    out += "\n";
    if (k.table) out += document(*k.table, indent + "    ");
  }
  return out;
}

namespace {
const KeySpec& spec_of(const TableSpec& spec, const std::string& key) {
  const KeySpec* ks = spec.find(key);
  if (!ks) throw Error(fmt::format("schema: no key '{}' in [{}]", key, spec.name), ErrorKind::Internal);
  return *ks;
}
}  // namespace

double get_float(const toml::table& t, const TableSpec& spec, const std::string& key) {
  if (auto v = t[key].value<double>()) return *v;
  const auto& f = spec_of(spec, key).fallback;
  if (auto* d = std::get_if<double>(&f)) return *d;
  if (auto* i = std::get_if<std::int64_t>(&f)) return static_cast<double>(*i);
  throw Error(fmt::format("missing value for '{}'", key));
}

std::int64_t get_int(const toml::table& t, const TableSpec& spec, const std::string& key) {
  if (auto v = t[key].value<std::int64_t>()) return *v;
  if (auto* i = std::get_if<std::int64_t>(&spec_of(spec, key).fallback)) return *i;
  throw Error(fmt::format("missing value for '{}'", key));
}

std::string get_string(const toml::table& t, const TableSpec& spec, const std::string& key) {
  if (auto v = t[key].value<std::string>()) return *v;
  if (auto* s = std::get_if<std::string>(&spec_of(spec, key).fallback)) return *s;
  return "";
}

bool get_bool(const toml::table& t, const TableSpec& spec, const std::string& key) {
  if (auto v = t[key].value<bool>()) return *v;
  if (auto* b = std::get_if<bool>(&spec_of(spec, key).fallback)) return *b;
  return false;
}

std::vector<double> get_floats(const toml::table& t, const std::string& key) {
  std::vector<double> out;
  if (const auto* a = t[key].as_array())
    for (const auto& e : *a) out.push_back(e.value<double>().value_or(0.0));
  return out;
}

std::vector<std::string> get_strings(const toml::table& t, const std::string& key) {
  std::vector<std::string> out;
  if (const auto* a = t[key].as_array())
    for (const auto& e : *a) out.push_back(e.value<std::string>().value_or(""));
  return out;
}

std::vector<std::vector<double>> get_float_rows(const toml::table& t, const std::string& key) {
  std::vector<std::vector<double>> out;
  if (const auto* a = t[key].as_array())
    for (const auto& row : *a) {
      out.emplace_back();
      if (const auto* r = row.as_array())
        for (const auto& e : *r) out.back().push_back(e.value<double>().value_or(0.0));
    }
  return out;
}

}  // namespace stiction::scene
