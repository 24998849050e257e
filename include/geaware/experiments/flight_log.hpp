// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The flight log: one CSV row per control tick, streamed through io::CsvWriter's fixed buffer
// (the whole log is never held in memory), with every stage of the data path — reference, estimate, truth,
// heights, commands, torques, rotor speeds, throttles, flags — in columns whose names carry
// their units, so a plotting tool opens the file directly (pandas.read_csv, gnuplot, a
// spreadsheet). The column list is flightLogColumns(); docs/closed-loop.md describes each.
// Times are written as the shortest text that reads back to the same double, every other value
// as the shortest text that reads back to the same float32 (6–9 significant digits: far finer
// than any sensor's noise, and half the size and formatting time of doubles). The same flight
// gives a byte-identical file. Comment lines (provenance) may precede the header; the columns
// that `geaware identify flight` reads come last, so the log is its input as it stands.

#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "geaware/experiments/flight.hpp"
#include "geaware/io/csv_writer.hpp"
#include "geaware/io/output_file.hpp"

namespace geaware::experiments {

/// Column names, in file order.
[[nodiscard]] const std::vector<std::string_view>& flightLogColumns();

/// Streams the ticks of a flight to a CSV file.
class CsvFlightLog final : public FlightObserver {
 public:
  /// Writes `file` through an io::AtomicFile (an existing file is replaced only by finish()/
  /// close(); a flight that throws leaves it untouched), beginning with `header_comment` (lines
  /// starting "# ", e.g. io::provenanceComment) and the header; throws std::runtime_error naming
  /// the file when it cannot be written. `vehicle` is the controller's (nominal) vehicle: its mass and k_T give the
  /// external-acceleration columns that `geaware identify flight` reads.
  CsvFlightLog(const std::filesystem::path& file, const model::VehicleParams& vehicle,
               std::string_view header_comment = {});
  ~CsvFlightLog() override;
  CsvFlightLog(const CsvFlightLog&) = delete;
  CsvFlightLog& operator=(const CsvFlightLog&) = delete;

  /// Formats one row into the buffer; writes the buffer out when it is nearly full. A write
  /// error is remembered and reported by finish()/close(). No allocation.
  void onTick(const FlightTick& tick) noexcept override;
  /// Flushes and commits the file; throws std::runtime_error naming the file on any write error
  /// (the existing file, if any, is then unchanged).
  void finish(const FlightResult& result) override;
  void close();

  [[nodiscard]] std::size_t rows() const noexcept { return csv_.rows(); }
  [[nodiscard]] const std::filesystem::path& path() const noexcept { return path_; }

 private:
  std::filesystem::path path_;
  io::AtomicFile file_;  // the comment lines are written before the header
  io::CsvWriter csv_;            // buffered; rows are formatted into its fixed buffer
  double k_T_N_per_rpm2_;
  double mass_kg_;
};

}  // namespace geaware::experiments
