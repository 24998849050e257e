// SPDX-License-Identifier: BSD-3-Clause
// The height-map file (docs/scenario-file.md): a regular grid of heights as CSV with a
// '#'-comment header, read into a model::HeightGrid that sim::HeightMap is built from.
#include "geaware/io/height_map_file.hpp"

#include "geaware/io/input_file.hpp"
#include "text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <optional>
#include <string_view>
#include <system_error>
#include <utility>

#include "geaware/io/format_version.hpp"

namespace geaware::io {

namespace {

std::string locationPrefix(const std::string& file, int line, int column) {
  std::string s = file;
  if (line > 0) s += ":" + std::to_string(line);
  if (line > 0 && column > 0) s += ":" + std::to_string(column);
  return s;
}

/// Parses the whole of `s` as a double; nothing on failure.
std::optional<double> parseNumber(std::string_view s) {
  if (s.empty()) return std::nullopt;
  if (s.front() == '+') s.remove_prefix(1);
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

/// "# format_version: N": absent means 1; a version this geaware does not read is an error
/// (the keys may mean something else in it), as is the key after the data or twice.
void checkFormatVersion(const std::string& path, int line, std::string_view value,
                        int first_data_line, int& version_line) {
  const std::string key = std::string("header key '") + kFormatVersionKey + "'";
  if (first_data_line > 0) {
    throw HeightMapFileError(path, line, 0, key + " after the first data row (line " +
                                                std::to_string(first_data_line) + ")");
  }
  if (version_line > 0) throw HeightMapFileError(path, line, 0, key + " given twice");
  version_line = line;
  const auto v = parseNumber(value);
  const bool known = v && std::find(kFormatVersions.begin(), kFormatVersions.end(), *v) !=
                              kFormatVersions.end();
  if (!known) {
    throw HeightMapFileError(path, line, 0,
                             key + ": '" + std::string(value) +
                                 "' is not a format version this geaware reads (it reads " +
                                 describeVersions(kFormatVersions) + ")");
  }
}

}  // namespace

HeightMapFileError::HeightMapFileError(std::string file, int line, int column,
                                   const std::string& message)
    : std::runtime_error(locationPrefix(file, line, column) + ": " + message),
      file_(std::move(file)),
      line_(line),
      column_(column) {}

model::HeightGrid readHeightMapFile(const std::string& path) {
  std::string bytes;
  try {
    bytes = readInputFile(path, "height-map file", "height-map text file");  // lines under 1 MiB
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    const std::string prefix = path + ": ";
    if (what.starts_with(prefix)) throw HeightMapFileError(path, 0, 0, what.substr(prefix.size()));
    throw;  // "<path>:<line>: line longer than 1 MiB …"
  }
  return parseHeightMapText(bytes, path);
}

model::HeightGrid parseHeightMapText(std::string_view bytes, const std::string& path) {
  std::istringstream in{std::string(bytes)};
  std::optional<double> origin_x;
  std::optional<double> origin_y;
  std::optional<double> cell;
  int first_data_line = 0;
  int version_line = 0;
  std::vector<std::vector<double>> rows;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    const std::string_view s = detail::trimBlanks(text);
    if (s.empty()) continue;
    if (s.front() == '#') {
      // "# key: value" for one of the known keys, anything else is a comment.
      const std::string_view body = detail::trimBlanks(s.substr(1));
      const auto colon = body.find(':');
      if (colon == std::string_view::npos) continue;
      const std::string_view key = detail::trimBlanks(body.substr(0, colon));
      if (key == kFormatVersionKey) {
        checkFormatVersion(path, line, detail::trimBlanks(body.substr(colon + 1)), first_data_line, version_line);
        continue;
      }
      std::optional<double>* slot = key == "origin_x_m"   ? &origin_x
                                    : key == "origin_y_m" ? &origin_y
                                    : key == "cell_m"     ? &cell
                                                          : nullptr;
      if (slot == nullptr) continue;
      if (first_data_line > 0) {
        throw HeightMapFileError(path, line, 0,
                               "header key '" + std::string(key) +
                                   "' after the first data row (line " +
                                   std::to_string(first_data_line) + ")");
      }
      if (slot->has_value())
        throw HeightMapFileError(path, line, 0, "header key '" + std::string(key) + "' given twice");
      const std::string_view value = detail::trimBlanks(body.substr(colon + 1));
      const auto v = parseNumber(value);
      if (!v || !std::isfinite(*v)) {
        throw HeightMapFileError(path, line, 0,
                               "header key '" + std::string(key) + "': '" + std::string(value) +
                                   "' is not a finite number");
      }
      if (slot == &cell && !(*v > 0.0)) {
        throw HeightMapFileError(
            path, line, 0, "header key 'cell_m': " + std::string(value) + " must be positive (m)");
      }
      *slot = *v;
      continue;
    }
    if (first_data_line == 0) first_data_line = line;
    std::vector<double> row;
    std::size_t start = 0;
    int column = 0;
    for (;;) {
      ++column;
      const std::size_t comma = s.find(',', start);
      const std::string_view field =
          detail::trimBlanks(s.substr(start, comma == std::string_view::npos ? s.npos : comma - start));
      const auto v = parseNumber(field);
      if (!v)
        throw HeightMapFileError(path, line, column, "'" + std::string(field) + "' is not a number");
      if (!std::isfinite(*v))
        throw HeightMapFileError(path, line, column,
                               "height '" + std::string(field) + "' is not finite");
      row.push_back(*v);
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (!rows.empty() && row.size() != rows.front().size()) {
      throw HeightMapFileError(path, line, 0,
                             "row has " + std::to_string(row.size()) +
                                 " values, the first row (line " + std::to_string(first_data_line) +
                                 ") has " + std::to_string(rows.front().size()) +
                                 ": the grid must be rectangular");
    }
    rows.push_back(std::move(row));
  }
  const char* missing = !origin_x   ? "origin_x_m"
                        : !origin_y ? "origin_y_m"
                        : !cell     ? "cell_m"
                                    : nullptr;
  if (missing != nullptr) {
    throw HeightMapFileError(path, 0, 0,
                           std::string("missing header key '") + missing + "' (a line '# " +
                               missing + ": VALUE' before the data)");
  }
  if (rows.size() < 2 || rows.front().size() < 2) {
    throw HeightMapFileError(
        path, 0, 0,
        "the grid has " + std::to_string(rows.size()) + " rows of " +
            std::to_string(rows.empty() ? 0 : rows.front().size()) +
            " values; at least 2 rows of 2 are needed for bilinear interpolation");
  }
  return model::HeightGrid{*origin_x, *origin_y, *cell, std::move(rows)};
}

}  // namespace geaware::io
