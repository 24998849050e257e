// SPDX-License-Identifier: BSD-3-Clause
// Units of log fields and columns (io/units.hpp).

#include "geaware/io/units.hpp"

#include <cmath>
#include <vector>

namespace geaware::io {
namespace {

constexpr Dimension dim(int m, int s, int kg = 0, int rad = 0, int V = 0, int A = 0) {
  return Dimension{{static_cast<std::int8_t>(m), static_cast<std::int8_t>(s),
                    static_cast<std::int8_t>(kg), static_cast<std::int8_t>(rad),
                    static_cast<std::int8_t>(V), static_cast<std::int8_t>(A)}};
}
constexpr double kG = 9.80665;              // standard gravity [m/s²]
constexpr double kDeg = M_PI / 180.0;       // [rad]
constexpr double kRpm = 2.0 * M_PI / 60.0;  // [rad/s]

const Dimension kNone{};
const Dimension kLength = dim(1, 0), kTime = dim(0, 1), kSpeed = dim(1, -1), kAccel = dim(1, -2);
const Dimension kAngle = dim(0, 0, 0, 1), kRate = dim(0, -1, 0, 1);
const Dimension kForce = dim(1, -2, 1), kTorque = dim(2, -2, 1), kVolt = dim(0, 0, 0, 0, 1);
const Dimension kAmp = dim(0, 0, 0, 0, 0, 1), kMass = dim(0, 0, 1), kPower = dim(0, 0, 0, 0, 1, 1);

const std::vector<Unit>& units() {
  static const std::vector<Unit> table = {
      {"1", 1.0, kNone},         {"-", 1.0, kNone},           {"%", 0.01, kNone},
      {"s", 1.0, kTime},         {"sec", 1.0, kTime},         {"ms", 1e-3, kTime},
      {"us", 1e-6, kTime},       {"\xC2\xB5s", 1e-6, kTime},  {"\xCE\xBCs", 1e-6, kTime},
      {"min", 60.0, kTime},      {"m", 1.0, kLength},         {"cm", 1e-2, kLength},
      {"mm", 1e-3, kLength},     {"km", 1e3, kLength},        {"m/s", 1.0, kSpeed},
      {"cm/s", 1e-2, kSpeed},    {"mm/s", 1e-3, kSpeed},      {"km/h", 1.0 / 3.6, kSpeed},
      {"m/s^2", 1.0, kAccel},    {"m/s2", 1.0, kAccel},       {"m/s\xC2\xB2", 1.0, kAccel},
      {"mm/s^2", 1e-3, kAccel},  {"cm/s^2", 1e-2, kAccel},    {"g", kG, kAccel},
      {"mg", 1e-3 * kG, kAccel}, {"rad", 1.0, kAngle},        {"mrad", 1e-3, kAngle},
      {"deg", kDeg, kAngle},     {"\xC2\xB0", kDeg, kAngle},  {"rad/s", 1.0, kRate},
      {"deg/s", kDeg, kRate},    {"\xC2\xB0/s", kDeg, kRate}, {"rpm", kRpm, kRate},
      {"RPM", kRpm, kRate},      {"rev/min", kRpm, kRate},    {"N", 1.0, kForce},
      {"mN", 1e-3, kForce},      {"gf", 1e-3 * kG, kForce},   {"kgf", kG, kForce},
      {"Nm", 1.0, kTorque},      {"N*m", 1.0, kTorque},       {"N\xC2\xB7m", 1.0, kTorque},
      {"mNm", 1e-3, kTorque},    {"Nmm", 1e-3, kTorque},      {"N*mm", 1e-3, kTorque},
      {"V", 1.0, kVolt},         {"mV", 1e-3, kVolt},         {"A", 1.0, kAmp},
      {"mA", 1e-3, kAmp},        {"cA", 1e-2, kAmp},          {"W", 1.0, kPower},
      {"kg", 1.0, kMass},
  };
  return table;
}

}  // namespace

std::string dimensionName(const Dimension& d) {
  const std::pair<Dimension, const char*> names[] = {{kNone, "dimensionless"},
                                                     {kLength, "length"},
                                                     {kTime, "time"},
                                                     {kSpeed, "velocity"},
                                                     {kAccel, "acceleration"},
                                                     {kAngle, "angle"},
                                                     {kRate, "angular velocity"},
                                                     {kForce, "force"},
                                                     {kTorque, "torque"},
                                                     {kVolt, "voltage"},
                                                     {kAmp, "current"},
                                                     {kMass, "mass"},
                                                     {kPower, "power"}};
  for (const auto& [k, n] : names) {
    if (k == d) return n;
  }
  static const char* base[] = {"m", "s", "kg", "rad", "V", "A"};
  std::string s;
  for (std::size_t i = 0; i < d.e.size(); ++i) {
    if (d.e[i] == 0) continue;
    s += (s.empty() ? "" : " ") + std::string(base[i]) +
         (d.e[i] == 1 ? "" : "^" + std::to_string(d.e[i]));
  }
  return s;
}

const Unit* findUnit(std::string_view name) noexcept {
  for (const auto& u : units()) {
    if (u.name == name) return &u;
  }
  return nullptr;
}

const Unit* unitOfColumnName(std::string_view column) noexcept {
  static const std::pair<std::string_view, std::string_view> suffixes[] = {
      {"s", "s"},         {"m", "m"},     {"mps", "m/s"}, {"mps2", "m/s^2"}, {"radps", "rad/s"},
      {"degps", "deg/s"}, {"rpm", "rpm"}, {"deg", "deg"}, {"rad", "rad"},    {"N", "N"},
      {"Nm", "Nm"},       {"V", "V"},     {"A", "A"},     {"kg", "kg"},      {"W", "W"}};
  const auto us = column.rfind('_');
  // A name that is a unit ("rpm", the stand log's rotor speed column) is in that unit.
  const std::string_view suffix = us == std::string_view::npos ? column : column.substr(us + 1);
  for (const auto& [s, u] : suffixes) {
    if (s == suffix) return findUnit(u);
  }
  return nullptr;
}

std::string knownUnitNames() {
  std::string s;
  for (const auto& u : units()) s += (s.empty() ? "" : ", ") + std::string(u.name);
  return s;
}

}  // namespace geaware::io
