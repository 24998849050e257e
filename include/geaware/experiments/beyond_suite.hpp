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

/// One flight of a beyond cell: the suite metrics plus what its kind adds.
struct BeyondFlight {
  SuiteFlight suite;
  /// All-RMSE over the last lap of a lemniscate of two or more laps (NaN otherwise, or struck
  /// before it) [cm].
  double last_lap_rmse_cm = 0.0;
  std::optional<GroundContactSummary> contact;  ///< landings and take-offs
  std::optional<double> min_obstacle_clearance_m;  ///< scenarios with obstacles [m]
};

struct BeyondCell {
  std::string scenario;
  std::string controller;
  std::vector<BeyondFlight> flights;  ///< in seed order

  [[nodiscard]] int strikes() const noexcept;
  /// Mean of `metric` over the finished flights; NaN when every flight struck [cm].
  [[nodiscard]] double meanFinished(double SuiteFlight::*metric) const noexcept;
};

/// A scenario of the suite: its sweep entry (trajectory, terrain, obstacles) and kind.
struct BeyondScenario {
  SweepScenario sweep;
  BeyondKind kind = BeyondKind::kFlight;
  int laps = 0;  ///< laps of a lemniscate (0: another trajectory)
  /// Trajectory time at which its last lap starts (lemniscates of ≥ 2 laps; NaN otherwise) [s].
  double last_lap_from_s = 0.0;
};

/// Two controllers' flights of one scenario, seed by seed: a struck flight ranks below every
/// finished one, and the RMSE is compared on the seeds both finished.
struct BeyondComparison {
  int both_finished = 0;
  int only_first_struck = 0;   ///< seeds where the first struck and the second finished
  int only_second_struck = 0;  ///< seeds where the second struck and the first finished
  double first_rmse_cm = 0.0;  ///< mean over the seeds both finished (NaN: none) [cm]
  double second_rmse_cm = 0.0;
  /// first / second on those seeds (NaN: none).
  [[nodiscard]] double ratio() const noexcept { return first_rmse_cm / second_rmse_cm; }
};

[[nodiscard]] BeyondComparison compareBeyond(const BeyondCell& first, const BeyondCell& second,
                                             double SuiteFlight::*metric = &SuiteFlight::rmse_all_cm);

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

/// Flies the suite: every scenario × controller × seed of `spec` (one case: the sweep's first,
/// normally `none`). Throws std::invalid_argument for an unknown scenario or controller name,
/// a spec with more than one case, and whatever a flight throws.
[[nodiscard]] BeyondResult runBeyond(const SweepSpec& spec, const BeyondOptions& options);

/// The checks of `recommended` on `r` (runBeyond fills r.checks with them).
[[nodiscard]] std::vector<SuiteCheck> beyondChecks(const BeyondResult& r);

/// The human summary: a table per scenario, the checks, the timing.
[[nodiscard]] std::string formatBeyond(const BeyondResult& r);
/// The suite's JSON ("suite": "beyond", one cell per scenario × controller, "case" the scenario).
[[nodiscard]] io::Json beyondJson(const BeyondResult& r);
/// Writes DIR/beyond.html (the checks and every cell) and DIR/beyond-<scenario>.html per
/// scenario (its geometry seen from the side and from above with the first seed of each
/// controller, heights and errors over time); with `png`, DIR/beyond.png too. Returns the
/// index page's path.
std::filesystem::path writeBeyondReport(const BeyondResult& r, const std::filesystem::path& dir,
                                        const io::RunInfo& run, bool png);

}  // namespace geaware::experiments
