#include "geaware/ident/rig_logs.hpp"

#include <limits>
#include <utility>

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

CsvReadOptions optionsFor(std::vector<CsvColumn> columns, const std::string& t) {
  CsvReadOptions o;
  o.columns = std::move(columns);
  o.time_column = t;
  o.min_rows = 2;
  return o;
}

}  // namespace

PlatformLog readPlatformLog(const std::filesystem::path& file, const PlatformColumns& c) {
  std::vector<CsvColumn> cols = {time(c.t), height(c.h), tilt(c.tilt)};
  for (const auto& n : c.n) cols.push_back(speed(n));
  for (const auto& n : c.f) cols.push_back(force(n));
  for (const auto& n : c.tau) cols.push_back(torque(n));
  CsvTable table = readCsv(file, optionsFor(std::move(cols), c.t));
  PlatformLog log;
  log.source = table.source;
  log.first_data_line = table.first_data_line;
  auto& k = table.columns;
  log.t_s = std::move(k[0]);
  log.h_m = std::move(k[1]);
  log.tilt_deg = std::move(k[2]);
  for (std::size_t i = 0; i < 4; ++i) log.n_rpm[i] = std::move(k[3 + i]);
  for (std::size_t i = 0; i < 3; ++i) log.f_N[i] = std::move(k[7 + i]);
  for (std::size_t i = 0; i < 3; ++i) log.tau_Nm[i] = std::move(k[10 + i]);
  return log;
}

RotorStandLog readRotorStandLog(const std::filesystem::path& file, const RotorStandColumns& c) {
  CsvTable table = readCsv(file, optionsFor({time(c.t), unit(c.throttle), speed(c.rpm),
                                             force(c.thrust), torque(c.torque)},
                                            c.t));
  RotorStandLog log;
  log.source = table.source;
  log.first_data_line = table.first_data_line;
  auto& k = table.columns;
  log.t_s = std::move(k[0]);
  log.throttle = std::move(k[1]);
  log.rpm = std::move(k[2]);
  log.thrust_N = std::move(k[3]);
  log.torque_Nm = std::move(k[4]);
  return log;
}

FlightLog readFlightLog(const std::filesystem::path& file, const FlightColumns& c) {
  std::vector<CsvColumn> cols = {time(c.t), height(c.h)};
  for (const auto& n : c.v) cols.push_back(velocity(n));
  for (const auto& n : c.q) cols.push_back(quaternion(n));
  for (const auto& n : c.a_ext) cols.push_back(acceleration(n));
  for (const auto& n : c.n) cols.push_back(speed(n));
  CsvTable table = readCsv(file, optionsFor(std::move(cols), c.t));
  FlightLog log;
  log.source = table.source;
  log.first_data_line = table.first_data_line;
  auto& k = table.columns;
  log.t_s = std::move(k[0]);
  log.h_m = std::move(k[1]);
  for (std::size_t i = 0; i < 3; ++i) log.v_W[i] = std::move(k[2 + i]);
  for (std::size_t i = 0; i < 4; ++i) log.q_WB[i] = std::move(k[5 + i]);
  for (std::size_t i = 0; i < 3; ++i) log.a_ext_W[i] = std::move(k[9 + i]);
  for (std::size_t i = 0; i < 4; ++i) log.n_rpm[i] = std::move(k[12 + i]);
  return log;
}

FlightLog readHoverLog(const std::filesystem::path& file, const FlightColumns& c) {
  std::vector<CsvColumn> cols = {time(c.t), height(c.h), acceleration(c.a_ext[2])};
  for (const auto& n : c.n) cols.push_back(speed(n));
  CsvTable table = readCsv(file, optionsFor(std::move(cols), c.t));
  FlightLog log;
  log.source = table.source;
  log.first_data_line = table.first_data_line;
  auto& k = table.columns;
  log.t_s = std::move(k[0]);
  log.h_m = std::move(k[1]);
  log.a_ext_W[2] = std::move(k[2]);
  for (std::size_t i = 0; i < 4; ++i) log.n_rpm[i] = std::move(k[3 + i]);
  return log;
}

}  // namespace geaware::ident
