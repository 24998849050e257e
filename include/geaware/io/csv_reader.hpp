// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Streaming CSV reader for rig and flight logs (docs/identification.md, "Log formats").
//
// One pass over the file through a large read buffer; only the requested columns are parsed
// (std::from_chars), the others are skipped. A log is therefore read into memory at most once:
// either row by row through CsvReader::next (aggregate while streaming), or as the requested
// columns only, as vectors of doubles (readCsv).
//
// Every problem is a CsvError naming the file, the line and the column: a missing or misnamed
// column (with the columns that were found), a cell that is not a number, NaN or infinity, a
// value outside the column's plausible range (unit slips: mm for m, rad for deg), a duplicated
// or decreasing timestamp, a row with the wrong number of cells, too few rows.

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "geaware/io/column_expression.hpp"

namespace geaware::io {

/// A problem in a log file. what() is "FILE:LINE: column 'NAME': MESSAGE" (the line and the
/// column are left out when they do not apply).
class CsvError : public std::runtime_error {
 public:
  CsvError(std::string file, std::size_t line, std::string column, const std::string& message);
  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  [[nodiscard]] std::size_t line() const noexcept { return line_; }  ///< 1-based, 0: none
  [[nodiscard]] const std::string& column() const noexcept { return column_; }

 private:
  std::string file_;
  std::size_t line_;
  std::string column_;
};

/// One column to read, with the range its values must lie in (a check of units by range).
struct CsvColumn {
  std::string name;                                            ///< header name
  double min = -std::numeric_limits<double>::infinity();       ///< smallest plausible value
  double max = std::numeric_limits<double>::infinity();        ///< largest plausible value
  /// NaN, ±inf and empty cells are read as NaN and ±inf rather than refused: a log's column that
  /// a reader may not use (a mapped CSV export, io::readLog), whose gaps its user then counts.
  bool non_finite = false;
};

struct CsvReadOptions {
  std::vector<CsvColumn> columns;  ///< the columns wanted, in the order they are returned
  /// Name of the timestamp column (must be one of `columns`): its values must increase
  /// strictly from row to row. Empty: no check.
  std::string time_column = "t_s";
  std::size_t min_rows = 2;                ///< fewer data rows is an error
  /// Cell separator; 0: detected from the header line (the most frequent of ',', ';' and tab;
  /// none of them: runs of spaces); ' ': runs of spaces and tabs.
  char delimiter = 0;
  std::size_t buffer_bytes = 1u << 22;     ///< read buffer [bytes]; grows for longer lines
  /// Requested columns computed from others (`--column h_m=z[mm]`, `--const tilt_deg=0`;
  /// io/column_expression.hpp): each must name a requested column. Only readCsv uses them; a
  /// defined column's range is checked on its computed values (in the column's unit), and rows
  /// that delta() leaves without a value (the first) are dropped.
  std::vector<ColumnDefinition> definitions;
};

/// Reads one CSV file row by row. The header is the first line that is neither empty nor a
/// comment ('#'), except that a '#' line directly followed by a data row (every cell a number)
/// is the header (lab exports write "# t,z"): the '#' and the blanks after it are dropped.
/// After the header every line is a data row (an empty line ends the data: only empty lines
/// may follow). Cells are trimmed of spaces; a leading '+' is accepted. A header name may carry
/// its unit, `z[mm]` or `z (mm)`: a requested column matches the whole name or the name without
/// the unit, and units() reports the unit.
class CsvReader {
 public:
  /// Opens the file and checks the header; throws CsvError.
  CsvReader(const std::filesystem::path& file, CsvReadOptions options);
  /// Reads `text` (not copied: it must outlive the reader), named `source` in messages (for
  /// tests and fuzzing); throws CsvError.
  CsvReader(std::string_view text, const std::string& source, CsvReadOptions options);
  ~CsvReader();
  CsvReader(const CsvReader&) = delete;
  CsvReader& operator=(const CsvReader&) = delete;
  CsvReader(CsvReader&&) noexcept;
  CsvReader& operator=(CsvReader&&) noexcept;

  /// Parses the next row into `values` (size = number of requested columns, in their order).
  /// Returns false at the end of the data, after checking the row count. Throws CsvError.
  [[nodiscard]] bool next(std::span<double> values);

  [[nodiscard]] std::size_t columnCount() const noexcept;
  [[nodiscard]] std::size_t rowsRead() const noexcept;       ///< data rows returned so far
  [[nodiscard]] std::size_t line() const noexcept;           ///< line of the last row returned
  [[nodiscard]] std::size_t bytesRead() const noexcept;      ///< bytes of the lines taken so far
  [[nodiscard]] const std::string& source() const noexcept;  ///< the file, as given
  /// Every column name of the header, in file order.
  [[nodiscard]] const std::vector<std::string>& header() const noexcept;
  /// The unit each header name carries ("mm" for `z[mm]`; empty when none), in file order.
  [[nodiscard]] const std::vector<std::string>& units() const noexcept;
  /// The cell separator in use (detected or given; ' ' for runs of blanks).
  [[nodiscard]] char delimiter() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The requested columns of a log, one vector of doubles per column.
struct CsvTable {
  std::string source;                      ///< the file it came from
  std::vector<std::string> names;          ///< requested column names, in order
  std::vector<std::vector<double>> columns;
  std::size_t first_data_line = 0;         ///< line of row 0 (row i is on line first + i)

  [[nodiscard]] std::size_t rows() const noexcept {
    return columns.empty() ? 0 : columns.front().size();
  }
  /// The column called `name`; throws std::out_of_range when it was not requested.
  [[nodiscard]] const std::vector<double>& column(std::string_view name) const;
};

/// Reads the requested columns of a whole log in one pass. Throws CsvError.
[[nodiscard]] CsvTable readCsv(const std::filesystem::path& file, const CsvReadOptions& options);

}  // namespace geaware::io
