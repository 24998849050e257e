// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A flight log read as `geaware identify flight` reads it (identify_command.cpp), for the other
// commands that take flight logs (`geaware train-residual`): the same readers, log maps and
// column options.

#include <string>
#include <vector>

#include "geaware/ident/rig_logs.hpp"
#include "geaware/model/vehicle_params.hpp"

namespace geaware::cli {

/// `log` through the log map `map` (a built-in name or a file; a_ext computed by the paper's
/// observer with base's mass and k_T), or, with `map` empty, a CSV in identify flight's format;
/// `columns` and `constants` are the --column NAME=EXPR and --const NAME=VALUE definitions (a
/// bad one is a UsageError before the log is read). Screened (dead or alternating rotor
/// channels refused, rows at 0 rpm dropped), the notes printed to stderr. `vehicle_file` is the
/// file `base` came from (empty: the built-in vehicle, whose throttle curve a log with throttles
/// and no rotor speeds may not use).
[[nodiscard]] ident::FlightLog readFlightInput(const std::string& log, const std::string& map,
                                               const std::vector<std::string>& columns,
                                               const std::vector<std::string>& constants,
                                               const model::VehicleParams& base,
                                               const std::string& vehicle_file);

}  // namespace geaware::cli
