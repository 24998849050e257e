// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/ident/rig_logs.hpp"

#include <array>
#include <limits>
#include <vector>
#include <utility>

#include "fit_support.hpp"
#include "geaware/io/csv_reader.hpp"

namespace geaware::ident {

namespace {

using io::CsvColumn;
using io::CsvReadOptions;
using io::CsvTable;
using io::readCsv;

// Plausible ranges by unit: generous for real vehicles, tight enough to catch a unit slip
// (heights in mm, tilt in rad vs deg is not caught but a tilt in mrad or a throttle in % is).
constexpr double kInf = std::numeric_limits<double>::infinity();
CsvColumn time(const std::string& n) { return {n, -kInf, kInf}; }
CsvColumn height(const std::string& n) { return {n, 0.0, 100.0}; }     // [m]
CsvColumn tilt(const std::string& n) { return {n, -90.0, 90.0}; }      // [deg]
CsvColumn speed(const std::string& n) { return {n, 0.0, 1e5}; }        // [rpm]
CsvColumn force(const std::string& n) { return {n, -1e4, 1e4}; }       // [N]
CsvColumn torque(const std::string& n) { return {n, -1e3, 1e3}; }      // [N·m]
CsvColumn unit(const std::string& n) { return {n, 0.0, 1.0}; }         // throttle [-]
CsvColumn velocity(const std::string& n) { return {n, -200.0, 200.0}; }  // [m/s]
CsvColumn quaternion(const std::string& n) { return {n, -1.000001, 1.000001}; }
CsvColumn acceleration(const std::string& n) { return {n, -1000.0, 1000.0}; }  // [m/s²]
CsvColumn voltage(const std::string& n) { return {n, 0.0, 1000.0}; }  // [V]
CsvColumn count(const std::string& n) { return {n, 1.0, 1e12}; }      // samples behind a mean

/// The columns of one log: asked for in order by kind, then read and handed out in that order.
class LogColumns {
 public:
  LogColumns& add(CsvColumn (*kind)(const std::string&), const std::string& name) {
    columns_.push_back(kind(name));
    return *this;
  }
  template <std::size_t N>
  LogColumns& add(CsvColumn (*kind)(const std::string&), const std::array<std::string, N>& names) {
    for (const auto& n : names) add(kind, n);
    return *this;
  }

  /// Reads the file (the first column is the time); `log` gets its source and first data line.
  template <typename Log>
  void read(const std::filesystem::path& file, Log& log, const ColumnDefinitions& definitions) {
    CsvReadOptions o;
    o.definitions = definitions;
    o.time_column = columns_.front().name;
    o.columns = std::move(columns_);
    o.min_rows = 2;
    table_ = readCsv(file, o);
    log.source = table_.source;
    log.first_data_line = table_.first_data_line;
  }
  /// The next column, in the order added.
  void take(std::vector<double>& out) { out = std::move(table_.columns.at(next_++)); }
  template <std::size_t N>
  void take(std::array<std::vector<double>, N>& out) {
    for (auto& c : out) take(c);
  }

 private:
  std::vector<CsvColumn> columns_;
  CsvTable table_;
  std::size_t next_ = 0;
};

}  // namespace

PlatformLog readPlatformLog(const std::filesystem::path& file, const PlatformColumns& c,
                            const ColumnDefinitions& definitions) {
  PlatformLog log;
  LogColumns k;
  k.add(time, c.t).add(height, c.h).add(tilt, c.tilt).add(speed, c.n).add(force, c.f).add(torque, c.tau);
  if (!c.fz_std.empty()) k.add(force, c.fz_std);
  if (!c.count.empty()) k.add(count, c.count);
  k.read(file, log, definitions);
  k.take(log.t_s); k.take(log.h_m); k.take(log.tilt_deg);
  k.take(log.n_rpm); k.take(log.f_N); k.take(log.tau_Nm);
  if (!c.fz_std.empty()) k.take(log.fz_std_N);
  if (!c.count.empty()) k.take(log.count);
  for (std::size_t i = 0; i < log.fz_std_N.size(); ++i) {
    if (log.fz_std_N[i] > 0.0) continue;
    throw IdentError(log.source + ":" + std::to_string(log.first_data_line + i) + ": column '" + c.fz_std +
                     "': expected a standard deviation > 0 N, got " + detail::num(log.fz_std_N[i]) +
                     " (a row's weight is count/std²)");
  }
  return log;
}

RotorStandLog readRotorStandLog(const std::filesystem::path& file, const RotorStandColumns& c,
                                const ColumnDefinitions& definitions) {
  RotorStandLog log;
  LogColumns k;
  k.add(time, c.t).add(unit, c.throttle).add(speed, c.rpm).add(force, c.thrust).add(torque, c.torque);
  if (!c.voltage.empty()) k.add(voltage, c.voltage);
  k.read(file, log, definitions);
  k.take(log.t_s); k.take(log.throttle); k.take(log.rpm); k.take(log.thrust_N); k.take(log.torque_Nm);
  if (!c.voltage.empty()) k.take(log.voltage_V);
  return log;
}

FlightLog readFlightLog(const std::filesystem::path& file, const FlightColumns& c,
                        const ColumnDefinitions& definitions) {
  FlightLog log;
  LogColumns k;
  k.add(time, c.t).add(height, c.h).add(velocity, c.v).add(quaternion, c.q);
  k.add(acceleration, c.a_ext).add(speed, c.n);
  k.read(file, log, definitions);
  k.take(log.t_s); k.take(log.h_m); k.take(log.v_W); k.take(log.q_WB); k.take(log.a_ext_W);
  k.take(log.n_rpm);
  return log;
}

FlightLog readHoverLog(const std::filesystem::path& file, const FlightColumns& c,
                       const ColumnDefinitions& definitions) {
  FlightLog log;
  LogColumns k;
  k.add(time, c.t).add(height, c.h).add(acceleration, c.a_ext[2]).add(speed, c.n);
  k.read(file, log, definitions);
  k.take(log.t_s); k.take(log.h_m); k.take(log.a_ext_W[2]); k.take(log.n_rpm);
  return log;
}

}  // namespace geaware::ident
