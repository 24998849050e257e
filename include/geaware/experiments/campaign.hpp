// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The paper's experiments in one call (issue 6, `geaware bench`; docs/results.md):
//   1. calibrate: the virtual rigs on the truth → the controller's identified parameters
//      (experiments/calibration.hpp);
//   2. the Neural-Lander baseline: collection flights, training, a cached weight file
//      (experiments/neural_baseline.hpp);
//   3. the eight Table I experiments over seeds, and the hover-descent experiment for the four
//      torque compensations (experiments/table_one.hpp, hover_experiment.hpp), flown on a
//      thread pool (experiments/flight_pool.hpp) with results identical to a serial run;
//   4. the summary: Table I beside the paper's, the headline ratios and the acceptance checks
//      of the issue (text and JSON: experiments/campaign_summary.hpp).
// The report page is experiments/campaign_report.hpp.
//
// Every flight's controller is built from the IDENTIFIED parameters; the truth, its per-flight
// variation, the sensors and the disturbances are the world's (a truth file, docs/truth-file.md;
// by default the vehicle file's ideal world, sim::idealWorld).

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "geaware/experiments/calibration.hpp"
#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/flight_series.hpp"
#include "geaware/experiments/hover_experiment.hpp"
#include "geaware/experiments/neural_baseline.hpp"
#include "geaware/experiments/progress.hpp"
#include "geaware/experiments/table_one.hpp"
#include "geaware/model/vehicle_params.hpp"
#include "geaware/sim/truth_params.hpp"
#include "geaware/sim/world.hpp"

namespace geaware::experiments {

/// The per-flight variation of config/truths/ideal_varied.yaml (once `--truth-mismatch`), for a
/// vehicle whose mass is weighed and whose inertia and CoG come from CAD: mass ±1 %, each
/// principal moment ±10 %, CoG ±2 mm in x, y and ±5 mm in z, per-motor thrust ±2 %. (The paper's
/// position loop has no integrator: 1 % of mass is ≈ 3 cm of height error with K^P = 3 /s².)
[[nodiscard]] sim::MismatchSpec defaultTruthMismatch();

struct CampaignOptions {
  /// The vehicle file (nominal): the controller gets it with the identified values merged in.
  model::VehicleParams vehicle;
  /// The world the rigs and the flights run in (truth, per-flight variation, sensors,
  /// disturbances); empty: sim::idealWorld(vehicle).
  std::optional<sim::World> world;
  int seeds = 5;                 ///< flights per experiment and per hover curve
  std::uint64_t first_seed = 1;  ///< seeds first_seed … first_seed + seeds − 1 (all experiments)
  /// Table I rows to fly: the paper's 1–8 and geaware's `recommended` rows 9, 10.
  std::vector<int> experiments = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  bool hover = true;             ///< fly the hover experiment
  int jobs = 0;                  ///< flight threads; 0: the hardware's
  std::filesystem::path cache_dir;  ///< Neural-Lander cache; empty: no cache
  /// A weight file (e.g. from `geaware train-residual`) flown as the Neural-Lander baseline
  /// instead of training one here; empty: trained (or taken from the cache).
  std::filesystem::path neural_weights;
  bool turbulence = true;           ///< false: no near-ground turbulence, whatever the world says
  /// Hover at the first point before every trajectory [s]: the runner starts the truth in its
  /// own hover there, and a controller with an imperfect model needs ≈ 2 s to settle; the
  /// paper's flights start from a settled hover.
  double start_hover_s = 3.0;
  CalibrationSweeps calibration = CalibrationSweeps::defaults();
  NeuralSettings neural;
  /// The values of a controller-parameters file (`--controller-params`,
  /// docs/controller-params.md), applied to every configuration flown (control::applyParameters:
  /// the calibration's, the Neural-Lander's collection flights', each row's); empty: the
  /// compiled defaults.
  std::optional<control::ControllerParams> controller_values;
  HoverSettings hover_settings;
  /// Collect decimated time series of each experiment's and hover curve's first seed (for the
  /// report).
  bool collect_series = false;
  /// Stage messages and the flight counter; null: silent.
  Progress* progress = nullptr;
};

/// Ratios the paper headlines and the acceptance criteria, each with its threshold.
struct AcceptanceCheck {
  std::string name;        ///< e.g. "exp 5 / exp 1, RMSE all"
  std::string criterion;   ///< e.g. "≤ 0.45"
  double value = 0.0;      ///< ours
  std::string paper;       ///< the paper's value, when it has one
  bool pass = false;
};

struct HoverSeries {
  control::TorqueCompensation torque = control::TorqueCompensation::kNone;
  FlightSeries series;
};

struct CampaignResult {
  ControllerCalibration calibration;
  std::optional<NeuralBaseline> neural;         ///< when experiment 3 was flown
  std::vector<ExperimentSummary> experiments;   ///< in the order asked for
  std::vector<HoverCurve> hover;                ///< in HoverSettings::torques order
  /// First-seed time series, by experiment number (collect_series).
  std::map<int, FlightSeries> series;
  std::vector<HoverSeries> hover_series;
  std::vector<AcceptanceCheck> checks;          ///< those the flown experiments allow
  int seeds = 0;
  int threads = 1;
  double calibration_s = 0.0;  ///< wall time of each stage [s]
  double neural_s = 0.0;
  double flights_s = 0.0;
  double wall_s = 0.0;
  std::size_t flights = 0;
  double simulated_s = 0.0;    ///< total simulated time of the campaign's flights [s]

  /// The summary of experiment `number`, or null when it was not flown.
  [[nodiscard]] const ExperimentSummary* experiment(int number) const noexcept;
  /// The hover curve of one torque compensation, or null.
  [[nodiscard]] const HoverCurve* hoverCurve(control::TorqueCompensation t) const noexcept;
};

/// Runs the campaign. Throws std::invalid_argument for bad options (unknown experiment,
/// seeds < 1), and whatever a stage throws (identification, an invalid scenario).
[[nodiscard]] CampaignResult runCampaign(const CampaignOptions& options);

/// The acceptance checks that the experiments in `r` allow (computed by runCampaign).
[[nodiscard]] std::vector<AcceptanceCheck> acceptanceChecks(const CampaignResult& r);

// The text and JSON summaries: experiments/campaign_summary.hpp.

}  // namespace geaware::experiments
