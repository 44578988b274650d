#include "run_settings.hpp"

#include <toml++/toml.h>

#include <cctype>
#include <filesystem>
#include <sstream>
#include <vector>

#include "bench_estimate.hpp"
#include "ksp_solver.hpp"

namespace stiction::harness {

namespace {

// "-ksp_type" is an option's key; "-1" (a negative value) is not.
bool is_key(const std::string& token) {
  return token.size() > 1 && token[0] == '-' && std::isalpha(static_cast<unsigned char>(token[1]));
}

}  // namespace

std::string effective_backend_settings(const std::string& backend_options, const std::string& solver) {
  std::vector<std::string> tokens;
  std::istringstream lines(backend_options);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line.substr(0, line.find('#')));
    for (std::string word; words >> word;) tokens.push_back(word);
  }
  const std::string prefixed = "-" + solvers::options_prefix(solver);
  std::map<std::string, std::string> settings;
  for (size_t k = 0; k < tokens.size(); ++k) {
    if (!is_key(tokens[k])) continue;
    std::string key = tokens[k];
    if (key.rfind(prefixed, 0) == 0) key = "-" + key.substr(prefixed.size());
    settings[key] = k + 1 < tokens.size() && !is_key(tokens[k + 1]) ? tokens[k + 1] : "";
  }
  std::string text;
  for (const auto& [key, value] : settings) text += (text.empty() ? "" : " ") + key + (value.empty() ? "" : " " + value);
  return text;
}

std::string run_backend_settings(const std::string& out_dir, const std::map<std::string, std::string>& row) {
  const std::string path = run_directory(out_dir, row) + "/metrics.toml";
  if (!std::filesystem::exists(path)) return "";
  try {
    const toml::table metrics = toml::parse_file(path);
    const auto options = metrics["run"]["backend_options"].value<std::string>();
    return options ? effective_backend_settings(*options, row.at("solver")) : "";
  } catch (const toml::parse_error&) {
    return "";
  }
}

}  // namespace stiction::harness
