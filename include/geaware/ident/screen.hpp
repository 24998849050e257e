// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Screening of a log before any fit (issue 11, "no silent fits"): the columns a fit needs are
// checked for being all zero or constant, rotor-speed channels for alternating with 0 (dead ESC
// telemetry: 0, 9900, 0, 9900, …), and the rows no fit can use (a rotor at 0 rpm, thrust ≤ 0)
// are dropped and counted. Every refusal is an IdentError naming the log and the column.

#include <string>
#include <vector>

#include "geaware/ident/least_squares.hpp"
#include "geaware/ident/rig_logs.hpp"

namespace geaware::ident {

/// One column of a log as the user named it, and its values.
struct NamedColumn {
  std::string name;
  const std::vector<double>* values = nullptr;
};

/// Throws IdentError ("<source>: column '<name>' is all zero" / "is constant (v)") for the first
/// column in `columns` with no two different values; an empty column is left to the fit.
void requireVarying(const std::string& source, const std::vector<NamedColumn>& columns);

/// Throws IdentError for the first column that is all zero.
void requireNonZero(const std::string& source, const std::vector<NamedColumn>& columns);

/// Switches between 0 and non-zero in `values` that make it a channel alternating with 0: more
/// than 4 switches, and more than one switch per 10 samples (a log that is at 0 rpm on the
/// ground before and after a flight switches twice). Returns the number of switches.
[[nodiscard]] std::size_t zeroSwitches(const std::vector<double>& values) noexcept;

/// Throws IdentError naming the first rotor channel that alternates with 0 (zeroSwitches).
void refuseAlternatingWithZero(const std::string& source, const std::vector<NamedColumn>& rotors);

/// The stand log screened: rpm, thrust, torque and throttle must vary, rpm must not alternate
/// with 0; rows at rpm = 0 or thrust ≤ 0 are dropped. Returns notes (the count dropped).
[[nodiscard]] std::vector<std::string> screenRotorStand(RotorStandLog& log, const RotorStandColumns& columns);

/// A flight or hover log screened: no rotor channel all zero or alternating with 0, az_ext not
/// all zero; rows with any rotor at 0 rpm are dropped. Returns notes (the count dropped).
[[nodiscard]] std::vector<std::string> screenFlight(FlightLog& log, const FlightColumns& columns);

/// The platform log screened: no rotor channel all zero or alternating with 0, fz must vary;
/// rows with any rotor at 0 rpm are dropped. Returns notes (the count dropped).
[[nodiscard]] std::vector<std::string> screenPlatform(PlatformLog& log, const PlatformColumns& columns);

}  // namespace geaware::ident
