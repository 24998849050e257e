// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/config_error.hpp"

namespace geaware::io {
namespace {

std::string render(const std::string& file, const std::vector<ConfigProblem>& problems) {
  std::string s;
  for (const auto& p : problems) {
    if (!s.empty()) s += '\n';
    s += file;
    if (p.line > 0) s += ":" + std::to_string(p.line);
    s += ": ";
    if (!p.key.empty()) s += "key '" + p.key + "': ";
    s += p.message;
  }
  return s.empty() ? file + ": invalid" : s;
}

}  // namespace

ConfigError::ConfigError(std::string file, std::vector<ConfigProblem> problems)
    : std::runtime_error(render(file, problems)),
      file_(std::move(file)),
      problems_(std::move(problems)) {}

}  // namespace geaware::io
