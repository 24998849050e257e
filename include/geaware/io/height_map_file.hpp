// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The height-map file: a regular grid of heights, one CSV row per j (the first row at
// origin_y) with one value per i, in metres, after a '#' header:
//
//     # geaware height map
//     # origin_x_m: -2.0
//     # origin_y_m: -2.0
//     # cell_m: 0.05
//     0.00, 0.00, 0.01, ...
//
// Header lines start with '#'; a line "# key: value" with one of the three keys sets it, every
// key is required once, other '#' lines are comments. Blank lines are skipped. An optional
// "# format_version: 1" names the format's version (absent: 1; another: an error).
// sim::HeightMap is built from the grid (bilinear between the nodes, held at the border).

#include <stdexcept>
#include <string>
#include <string_view>

#include "geaware/model/height_grid.hpp"

namespace geaware::io {

/// A problem in a height-map file; what() reads "FILE:LINE[:COLUMN]: message".
class HeightMapFileError : public std::runtime_error {
 public:
  HeightMapFileError(std::string file, int line, int column, const std::string& message);
  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  [[nodiscard]] int line() const noexcept { return line_; }  ///< 1-based, 0: whole file
  [[nodiscard]] int column() const noexcept { return column_; }  ///< 1-based CSV field, 0: whole line

 private:
  std::string file_;
  int line_;
  int column_;
};

/// Reads the format above: at least 2×2 finite heights, rectangular, cell > 0. Throws
/// HeightMapFileError naming the file, line and column.
[[nodiscard]] model::HeightGrid readHeightMapFile(const std::string& path);
/// Parses height-map text (the bytes of a file; `source` names it in errors) as
/// readHeightMapFile does after reading the file.
[[nodiscard]] model::HeightGrid parseHeightMapText(std::string_view text, const std::string& source);

}  // namespace geaware::io
