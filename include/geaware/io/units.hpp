// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Units of log fields and of geaware's columns (docs/identification.md, "Columns from
// expressions"): each with its factor into SI and its dimension, so that a value given in mm,
// deg/s, g, µs or mV is converted into m, rad/s, m/s², s or V, and a length given for a rotor
// speed is refused.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace geaware::io {

/// A physical dimension: the exponents of m, s, kg, rad, V and A.
struct Dimension {
  std::array<std::int8_t, 6> e{};
  friend bool operator==(const Dimension&, const Dimension&) = default;
};
/// "length", "angular velocity", "m^2 s^-1", "dimensionless".
[[nodiscard]] std::string dimensionName(const Dimension& d);

/// A unit: its factor into SI and its dimension (rpm: 2π/60 rad/s; g: 9.80665 m/s²).
struct Unit {
  std::string_view name;
  double to_si = 1.0;
  Dimension dimension;
};
/// The unit called `name` (as written in brackets, e.g. "mm", "deg/s", "µs"), or nullptr.
[[nodiscard]] const Unit* findUnit(std::string_view name) noexcept;
/// The unit a column name carries in its last '_' segment ("h_m" → m, "a_x_mps2" → m/s²,
/// "n1_rpm" → rpm, "tilt_deg" → deg), or nullptr (dimensionless: "qw", "throttle").
[[nodiscard]] const Unit* unitOfColumnName(std::string_view column) noexcept;
/// Every unit name understood, comma separated (for messages).
[[nodiscard]] std::string knownUnitNames();

}  // namespace geaware::io
