// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The summary of one flight (`geaware fly`): the Table I metrics, the crash, the controller's
// flags and the speed, as text and as the JSON document of `fly --json`, and the single-flight
// report page built from the series and plot builders the campaign's page uses.

#include <cstdint>
#include <filesystem>
#include <string>

#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/flight_series.hpp"
#include "geaware/io/json.hpp"
#include "geaware/io/provenance.hpp"

namespace geaware::experiments {

/// "model:model_indi", or "recommended" (control::configurationName).
[[nodiscard]] std::string controllerName(const control::ControllerParams& p);

/// The metrics, crash, flags and real-time lines printed after a flight.
[[nodiscard]] std::string formatFlight(const FlightResult& r);

/// {"rmse_xy_cm", …, "crashed", "crash", "samples", "controller", "seed", "flags",
/// "guard_active_s" (null without a guard), "simulated_s", "wall_s", "real_time_factor"}
/// (docs/closed-loop.md); NaN as null.
[[nodiscard]] io::Json flightJson(const FlightScenario& s, const FlightResult& r);

/// A landing's touchdown as `fly --json` and sweep records write it: "touchdown_speed_mps" and
/// "bounce_m" (NaN, written as null, without a touchdown).
[[nodiscard]] io::Json touchdownJson(const GroundContactSummary& g);
/// A landing's or take-off's ground contact as sweep records and the beyond suite write it:
/// touchdownJson's, then "landed", "liftoff_t_s", "recontacts", "max_tilt_on_ground_deg".
[[nodiscard]] io::Json groundContactJson(const GroundContactSummary& g);

/// Writes DIR/flight.html (creating DIR) from the flight's series and returns its path: the
/// metrics, the provenance, the trajectory from above (equal aspect), the height over the
/// terrain, the errors, the rotor speeds and torques. Throws std::runtime_error when DIR exists
/// and is not a directory or the page cannot be written. With `png`, also the whole page as
/// DIR/flight.png (headless Chromium; throws when it cannot render).
std::filesystem::path writeFlightReport(const std::filesystem::path& dir, const FlightSeries& series,
                                        const FlightResult& r, const std::string& title,
                                        const io::RunInfo& run, bool png = false);

}  // namespace geaware::experiments
