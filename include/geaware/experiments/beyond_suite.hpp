// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The beyond-the-paper suite (issue 13 item 6; `geaware bench --suite beyond`): the scenarios of
// the suite's sweep file (config/sweeps/beyond.yaml: table edge, step, ramp, ceiling, wall,
// 5 m/s low, landing, take-off, two laps that sweep the height) × its controllers × seeds, each
// flight exactly the sweep's (sweepFlightScenario: the same calibrated belief, world and seed),
// summarised per scenario × controller into the suite schema of the robustness suite
// ("case" = the scenario), with the checks of `recommended` reported as they are and a
// report page per scenario with its geometry drawn. Docs: docs/controller.md, "The beyond suite".

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geaware/experiments/flight_series.hpp"
#include "geaware/experiments/progress.hpp"
#include "geaware/experiments/robustness.hpp"
#include "geaware/experiments/sweep.hpp"
#include "geaware/io/json.hpp"
#include "geaware/io/provenance.hpp"

namespace geaware::experiments {

/// What kind of flight a scenario is, from its trajectory.
enum class BeyondKind : std::uint8_t { kFlight, kLanding, kTakeOff };

/// What a beyond flight adds to its suite flight.
struct BeyondExtras {
  /// All-RMSE over the last lap of a lemniscate of two or more laps (NaN otherwise, or when the
  /// flight struck before it) [cm].
  double last_lap_rmse_cm = 0.0;
  std::optional<GroundContactSummary> contact;     ///< landings and take-offs
  std::optional<double> min_obstacle_clearance_m;  ///< scenarios with obstacles [m]
};

/// One scenario × controller: a cell of the shared suite schema ("case" the scenario; height and
/// speed 0) and, per flight, what the scenario adds.
struct BeyondCell {
  SuiteCell suite;
  std::vector<BeyondExtras> extras;  ///< aligned with suite.flights (seed order)

  [[nodiscard]] const std::string& scenario() const noexcept { return suite.case_name; }
  [[nodiscard]] const std::string& controller() const noexcept { return suite.controller; }
};

/// A scenario of the suite: its sweep entry (trajectory, terrain, obstacles) and kind.
struct BeyondScenario {
  SweepScenario sweep;
  std::size_t index = 0;  ///< its position in the sweep file (names its report page)
  BeyondKind kind = BeyondKind::kFlight;
  int laps = 0;  ///< laps of a lemniscate (0: another trajectory)
  /// Trajectory time at which its last lap starts (lemniscates of ≥ 2 laps; NaN otherwise) [s].
  double last_lap_from_s = 0.0;
};

struct BeyondOptions {
  /// The scenarios to fly, by name (empty: all of the spec's), and the controllers (empty: all).
  std::vector<std::string> scenarios;
  std::vector<std::string> controllers;
  int jobs = 0;                 ///< flights in parallel (0: one per core)
  bool collect_series = false;  ///< each cell's first seed's series, for the report
  Progress* progress = nullptr;
};

struct BeyondResult {
  std::string source;  ///< the sweep file
  bool calibrated = true;  ///< the belief was calibrated (the file's `calibrate`)
  std::string recommended;  ///< the ACC:TORQUE pair `recommended` stands for
  std::vector<BeyondScenario> scenarios;
  std::vector<std::string> controllers;
  std::vector<std::uint64_t> seeds;
  std::vector<BeyondCell> cells;  ///< scenario-major, then controller
  std::vector<SuiteCheck> checks;
  /// The first seed's series per (scenario, controller), when collected.
  std::map<std::pair<std::string, std::string>, FlightSeries> series;
  int threads = 1;
  std::size_t flights = 0;
  double simulated_s = 0.0;
  double calibration_s = 0.0;  ///< wall times [s]
  double flights_s = 0.0;
  double wall_s = 0.0;

  [[nodiscard]] const BeyondCell* cell(const std::string& scenario, const std::string& controller) const noexcept;
};

/// The controller names the checks compare.
inline constexpr const char* kBeyondPaper = "model:model_indi";
inline constexpr const char* kBeyondIndi = "indi:none";
inline constexpr const char* kBeyondRecommended = "recommended";
inline constexpr const char* kBeyondLearning = "recommended+learn0";

/// Flies the suite: every scenario × controller × seed of `spec`, which has one case (normally
/// `none`). Throws std::invalid_argument for an unknown or twice-named scenario or controller,
/// a spec with more than one case, and whatever a flight throws.
[[nodiscard]] BeyondResult runBeyond(const SweepSpec& spec, const BeyondOptions& options);

/// The checks of `recommended` on `r`, those its scenarios and controllers allow (a check
/// that needs a controller or a kind of scenario that was not flown is left out); runBeyond
/// fills r.checks with them. A struck flight ranks below every finished one; RMSEs are compared
/// on the seeds both controllers finished.
[[nodiscard]] std::vector<SuiteCheck> beyondChecks(const BeyondResult& r);

/// Mean last-lap all-RMSE of the cell's finished flights (NaN: none, or no last lap) [cm].
[[nodiscard]] double meanLastLapCm(const BeyondCell& c) noexcept;

/// The human summary: a table per scenario, the checks, the timing.
[[nodiscard]] std::string formatBeyond(const BeyondResult& r);
/// The suite's JSON ("suite": "beyond", one cell per scenario × controller, "case" the scenario).
[[nodiscard]] io::Json beyondJson(const BeyondResult& r);
/// Writes DIR/beyond.html (the checks and every cell) and DIR/beyond-NN-<scenario>.html per
/// scenario (NN its position in the sweep file) (its geometry seen from the side and from above with the first seed of each
/// controller, heights and errors over time); with `png`, DIR/beyond.png too. Returns the
/// index page's path.
std::filesystem::path writeBeyondReport(const BeyondResult& r, const std::filesystem::path& dir,
                                        const io::RunInfo& run, bool png);

}  // namespace geaware::experiments
