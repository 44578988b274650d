#pragma once
// Declarative schema for TOML scene files (deal.II ParameterHandler / amgcl style): every key
// has a type, a default or "required", a one-line doc and optional choices. validate()
// rejects unknown keys, wrong types and bad choices with a message naming the file, the
// key and what is accepted; the getters read values through the same declarations, so a
// default lives in exactly one place.
#include <toml++/toml.h>

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace stiction::scene {

enum class ValueType { Integer, Float, String, Boolean, FloatArray, FloatRows, StringArray, Table, TableArray };
std::string to_string(ValueType t);

struct TableSpec;

using DefaultValue = std::variant<std::monostate, std::int64_t, double, std::string, bool>;

struct KeySpec {
  std::string name;
  ValueType type;
  std::string doc;
  bool required = false;
  DefaultValue fallback;             // used when absent and not required
  std::vector<std::string> choices;  // allowed strings (String / StringArray)
  const TableSpec* table = nullptr;  // nested schema (Table / TableArray)
};

struct TableSpec {
  std::string name;
  std::vector<KeySpec> keys;
  const KeySpec* find(const std::string& key) const;
};

// Throws stiction::Error "<file>: <problem> at '<path.key>' ..." on the first violation.
void validate(const toml::table& table, const TableSpec& spec, const std::string& file, const std::string& path = "");

// Human-readable reference of a schema (stiction scenes --schema).
std::string document(const TableSpec& spec, const std::string& indent = "");

// Typed access through the schema: absent keys give the declared default.
double get_float(const toml::table& t, const TableSpec& spec, const std::string& key);
std::int64_t get_int(const toml::table& t, const TableSpec& spec, const std::string& key);
std::string get_string(const toml::table& t, const TableSpec& spec, const std::string& key);
bool get_bool(const toml::table& t, const TableSpec& spec, const std::string& key);
std::vector<double> get_floats(const toml::table& t, const std::string& key);       // empty if absent
std::vector<std::string> get_strings(const toml::table& t, const std::string& key);  // empty if absent
std::vector<std::vector<double>> get_float_rows(const toml::table& t, const std::string& key);  // empty if absent

}  // namespace stiction::scene
