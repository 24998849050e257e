#pragma once
// Strict reading of YAML maps, shared by every file loader (vehicle files, scenario files):
// every key read is recorded with its line, keys never read are reported as unknown, and type
// errors name the key path. Problems accumulate so that one run reports everything wrong with a
// file, not just the first thing. Include it only from loaders: it brings in yaml-cpp.

#include <map>
#include <set>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "geaware/io/config_error.hpp"

namespace geaware::io {

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

  /// Whether the map has `key` (with any value). Does not mark the key as read.
  [[nodiscard]] bool has(const std::string& key) const;
  [[nodiscard]] double number(const std::string& key);
  [[nodiscard]] std::string text(const std::string& key);
  [[nodiscard]] std::vector<double> numbers(const std::string& key);
  [[nodiscard]] MapReader map(const std::string& key);
  /// A whole-number value within [lo, hi].
  [[nodiscard]] long integer(const std::string& key, long lo, long hi);
  /// true/false.
  [[nodiscard]] bool boolean(const std::string& key);
  /// A list of exactly `n` numbers (e.g. a 3-vector).
  [[nodiscard]] std::vector<double> fixedNumbers(const std::string& key, std::size_t n);
  /// A list of lists of exactly `n` numbers each (e.g. waypoints).
  [[nodiscard]] std::vector<std::vector<double>> rows(const std::string& key, std::size_t n);
  /// One of `choices`; anything else is a problem listing them.
  [[nodiscard]] std::string choice(const std::string& key, const std::vector<std::string>& choices);
  /// Reports a problem at `key`'s line (for checks the reader cannot make itself).
  void problem(const std::string& key, const std::string& message);
  [[nodiscard]] const std::string& path() const noexcept { return path_; }
  /// Problems reported so far in the whole file (to skip building from values already known bad).
  [[nodiscard]] std::size_t problemCount() const noexcept { return ctx_.problems.size(); }

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

}  // namespace geaware::io
