// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Errors in files the user gave us: each names the file, the line, the key and what was
// expected, so a person can fix the file without reading our code.

#include <stdexcept>
#include <string>
#include <vector>

namespace geaware::io {

/// One problem in a configuration file.
struct ConfigProblem {
  int line = 0;         ///< 1-based line, 0 when unknown (e.g. a missing key: its parent's line)
  std::string key;      ///< key path, dot separated ("rotor.k_T_N_per_rpm2"), may be empty
  std::string message;  ///< what is wrong and what was expected
};

/// Thrown by loaders; what() is one line per problem, "FILE:LINE: key 'K': MESSAGE".
class ConfigError : public std::runtime_error {
 public:
  ConfigError(std::string file, std::vector<ConfigProblem> problems);
  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  [[nodiscard]] const std::vector<ConfigProblem>& problems() const noexcept { return problems_; }

 private:
  std::string file_;
  std::vector<ConfigProblem> problems_;
};

}  // namespace geaware::io
