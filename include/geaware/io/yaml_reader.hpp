// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Strict reading of YAML maps, shared by every file loader (vehicle, scenario and weight files):
// every key read is recorded with its line, keys never read are reported as unknown, and type
// errors name the key path. Problems accumulate so that one run reports everything wrong with a
// file, not just the first thing. Include it only from loaders: it brings in yaml-cpp.

#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "geaware/io/config_error.hpp"

namespace geaware::io {

/// Line of `key` in `lines` (key path → line), or of its nearest recorded parent
/// ("a.b[2]" → "a.b" → "a"); 0 when none is recorded.
[[nodiscard]] int lineOfKey(const std::map<std::string, int>& lines, std::string key);

/// Shared state of one file's reading: its problems and the line of every key path seen.
struct YamlContext {
  std::vector<ConfigProblem> problems;
  std::map<std::string, int> lines;  ///< key path → 1-based line

  void problem(int line, std::string key, std::string message) {
    problems.push_back({line, std::move(key), std::move(message)});
  }
  /// Line of `key`, or of its nearest recorded parent ("a.b[2]" → "a.b" → "a").
  [[nodiscard]] int lineOf(std::string key) const { return lineOfKey(lines, std::move(key)); }
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

  // Strict reading (the weight file): numbers are parsed with std::from_chars, so "1.5x" is not a
  // number ("expected a number, got '1.5x'") and .nan/inf are named ("'.nan' is not a finite
  // number"). Item paths are "key[i]" (and "key[i][j]"); every item's line is recorded in
  // ctx.lines so that later checks can name it.

  /// A finite number; NaN after a problem.
  [[nodiscard]] double finiteNumber(const std::string& key);
  /// A list of finite numbers; with `length`, any other count is a problem "has N entries,
  /// expected M" (the items are still read and returned).
  [[nodiscard]] std::vector<double> finiteNumbers(const std::string& key,
                                                  std::optional<std::size_t> length = std::nullopt);
  /// A list of lists of finite numbers, each row checked as finiteNumbers with `row_length`
  /// (none: the first row's length). Rows are returned as read, also when their length is wrong.
  [[nodiscard]] std::vector<std::vector<double>> finiteRows(
      const std::string& key, std::optional<std::size_t> row_length);
  /// A list of maps, one reader per item (path "key[i]", missing keys reported at the item's
  /// line). An item that is not a map is a problem and gives an invalid reader, so the indices
  /// of the items after it are kept.
  [[nodiscard]] std::vector<MapReader> maps(const std::string& key);
  /// A list of texts.
  [[nodiscard]] std::vector<std::string> texts(const std::string& key);
  /// An optional map of free-form keys with text values (empty when absent).
  [[nodiscard]] std::map<std::string, std::string> optionalTextMap(const std::string& key);
  /// Whether `key`'s value is the scalar `word` (e.g. `none`). Like has(), it does not mark the
  /// key as read: the caller reads it next, as text or as whatever else it may be.
  [[nodiscard]] bool valueIs(const std::string& key, std::string_view word) const;
  /// Whether `key` is present with a scalar value (not a map or list). Does not mark it as read.
  [[nodiscard]] bool isScalar(const std::string& key) const;
  /// Whether this reader has a map to read (false for a missing or non-map value, whose keys
  /// then read as placeholders without further problems).
  [[nodiscard]] bool valid() const noexcept { return valid_; }

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
