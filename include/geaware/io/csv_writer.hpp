// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Streaming CSV writer: the one way geaware writes a CSV file (rig logs, the flight log, tables).
//
// The header is written on construction; rows are formatted cell by cell into a fixed buffer
// (fmt's shortest round-trip text, no locale) that is written out when it is nearly
// full, so a row costs no allocation and a long log is never held in memory. A write error is
// remembered and reported by close(), naming the file.
//
// Number formats: exact() writes the shortest text that reads back to the same double;
// single() the shortest text that reads back to the same float32 (6–9 significant digits: for
// values far noisier than that, half the size and formatting time); integer() a whole number.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace geaware::io {

class AtomicFile;

class CsvWriter {
 public:
  /// Writes `file` through an io::AtomicFile (a temporary file renamed over it by close(); a
  /// writer destroyed before close() leaves an existing file untouched) and writes the header;
  /// throws std::runtime_error naming the file when it cannot be written.
  CsvWriter(const std::filesystem::path& file, std::span<const std::string_view> columns);
  CsvWriter(const std::filesystem::path& file, std::initializer_list<std::string_view> columns)
      : CsvWriter(file, std::span<const std::string_view>(columns.begin(), columns.size())) {}
  /// Writes to an open stream it does not own (stdout, or an io::AtomicFile's stream); `name`
  /// names it in errors.
  CsvWriter(std::FILE* stream, std::string name, std::span<const std::string_view> columns);
  CsvWriter(std::FILE* stream, std::string name, std::initializer_list<std::string_view> columns)
      : CsvWriter(stream, std::move(name),
                  std::span<const std::string_view>(columns.begin(), columns.size())) {}
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  /// A cell: the shortest text that reads back to the same double. Cells after close() are
  /// ignored.
  void exact(double v) noexcept;
  /// A cell: the shortest text that reads back to the same float32.
  void single(double v) noexcept;
  /// A cell: a whole number.
  void integer(std::uint64_t v) noexcept;
  /// Ends the row.
  void endRow() noexcept;

  /// A whole row of exact() cells.
  void row(std::initializer_list<double> values) noexcept {
    for (double v : values) exact(v);
    endRow();
  }

  /// Writes out the buffer; completes (commits) the file when it owns it. Throws std::runtime_error naming
  /// the file on any write error (also one remembered from earlier rows). Idempotent.
  void close();

  [[nodiscard]] std::size_t rows() const noexcept { return rows_; }
  [[nodiscard]] std::size_t columns() const noexcept { return columns_; }
  [[nodiscard]] const std::string& name() const noexcept { return name_; }

 private:
  void writeHeader(std::span<const std::string_view> columns);
  void flush() noexcept;
  /// Makes room for one cell and writes the separator when it is not the row's first cell.
  char* cell() noexcept;

  std::string name_;
  std::unique_ptr<AtomicFile> atomic_;  // set when writing a file by name
  std::FILE* file_ = nullptr;
  bool owned_ = false;
  std::vector<char> buffer_;  // sized once; flushed when less than one cell's room is left
  std::size_t used_ = 0;
  std::size_t columns_ = 0;
  std::size_t cells_in_row_ = 0;
  std::size_t rows_ = 0;
  bool failed_ = false;
  int errno_ = 0;  // of the first failed write
};

}  // namespace geaware::io
