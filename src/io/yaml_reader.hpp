#pragma once
// Strict reading of YAML maps (private to io/): every key read is recorded with its line, keys
// never read are reported as unknown, and type errors name the key path. Problems accumulate so
// that one run reports everything wrong with a file, not just the first thing.

#include <map>
#include <set>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "geaware/io/config_error.hpp"

namespace geaware::io::detail {

/// Shared state of one file's reading: its problems and the line of every key path seen.
struct YamlContext {
  std::vector<ConfigProblem> problems;
  std::map<std::string, int> lines;  ///< key path → 1-based line

  void problem(int line, std::string key, std::string message) {
    problems.push_back({line, std::move(key), std::move(message)});
  }
  /// Line of `key`, or of its nearest recorded parent ("a.b[2]" → "a.b" → "a").
  [[nodiscard]] int lineOf(std::string key) const;
};

/// Reads one YAML map. Missing required keys and wrong types become problems; the returned
/// values are then placeholders (NaN, empty) and the caller reports the problems at the end.
class MapReader {
 public:
  /// `header_line`: line of the key that opened this map (missing keys are reported there).
  MapReader(YAML::Node node, std::string path, YamlContext& ctx, int header_line = 1);

  [[nodiscard]] double number(const std::string& key);
  [[nodiscard]] std::string text(const std::string& key);
  [[nodiscard]] std::vector<double> numbers(const std::string& key);
  [[nodiscard]] MapReader map(const std::string& key);

  /// Reports keys present in the file but never read.
  void rejectUnknownKeys();

 private:
  [[nodiscard]] std::string pathOf(const std::string& key) const;
  [[nodiscard]] YAML::Node required(const std::string& key);

  YAML::Node node_;
  std::string path_;
  YamlContext& ctx_;
  std::set<std::string> read_;
  bool valid_;
  int header_line_;
};

}  // namespace geaware::io::detail
