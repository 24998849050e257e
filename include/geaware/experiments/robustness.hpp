// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The robustness suite (issue 10, item 4; `geaware bench --suite robustness`;
// docs/robustness.md). The controller's belief is calibrated ONCE on the unperturbed world (the
// campaign's calibrateController: the rigs, the scale, the hover and drag flights in that world;
// and the Neural-Lander training when a `neural` configuration is flown); then the world changes, one cell at a time, as a real vehicle's does
// after its calibration: mass, thrust coefficient, motor spread, CoG, in-flight cushion, mocap
// latency the estimator does not know, room air. Two cells change the physics itself (another
// ground-effect law family, sim::GroundEffectLaw) and re-run the rigs and the identification
// (and the training) in that world. Each cell is flown with every Table I configuration,
// indi:indi and `recommended`, at 0.12 m / 1 m/s (exps 1–5's lemniscate) and 0.18 m / 3 m/s
// (exps 6–7's), over seeds, on the flight pool (results identical whatever the thread count).
// That grid is the suite's sweep file's, config/sweeps/robustness.yaml (robustnessOptionsOf,
// experiments/suite_sweep.hpp): another sweep file flies another grid.
//
// The result is a list of suite cells (case × controller × height/speed), the JSON schema that
// every suite shares (suiteJson): {"geaware_version", "suite", "recommended", "cells": [{"case",
// "controller", "height_m", "speed_mps", "seeds", "flights", "strikes", "rmse_all_cm" (null when
// every flight struck), "guard_active_s", …}]}. A struck flight ranks below every finished one;
// RMSE comparisons between two controllers use the seeds on which both finished
// (comparePaired).

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "geaware/control/controller_params.hpp"
#include "geaware/experiments/calibration.hpp"
#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/neural_baseline.hpp"
#include "geaware/experiments/progress.hpp"
#include "geaware/io/json.hpp"
#include "geaware/io/provenance.hpp"
#include "geaware/model/vehicle_params.hpp"
#include "geaware/report/page.hpp"
#include "geaware/sim/rotor_aerodynamics.hpp"
#include "geaware/sim/world.hpp"
#include "geaware/traj/lemniscate.hpp"

namespace geaware::experiments {

// --- The cells -------------------------------------------------------------------------------

/// What a cell changes in the world after the calibration.
enum class PerturbationKind {
  kNone,               ///< the unperturbed world
  kMass,               ///< truth mass × (1 + value)
  kThrustCoefficient,  ///< truth k_T × (1 + value), every motor
  kMotorSpread,        ///< motor i's k_T × (1 ± value), signs +, −, +, − in mixer order
  kCogOffset,          ///< truth CoG moved by value metres along body x
  kInFlightCushion,    ///< truth in-flight cushion scale × value
  kMocapLatency,       ///< true mocap latency + value seconds; the stamped latency unchanged
  kGusts,              ///< room air on, gust σ = value m/s per axis
  kGroundEffectLaw,    ///< the truth's law family `law` (rigs and identification re-run)
};

struct Perturbation {
  std::string name;  ///< the JSON "case", e.g. "mass+10%"
  PerturbationKind kind = PerturbationKind::kNone;
  double value = 0.0;  ///< see PerturbationKind (relative, m, factor, s or m/s)
  sim::GroundEffectLaw law = sim::GroundEffectLaw::kCalibrated;  ///< kGroundEffectLaw

  /// Whether the belief is re-calibrated in the changed world (the law families).
  [[nodiscard]] bool recalibrates() const noexcept {
    return kind == PerturbationKind::kGroundEffectLaw;
  }
  /// One line saying what changes, e.g. "truth mass × 1.10 (payload, battery)".
  [[nodiscard]] std::string meaning() const;
};

/// The named cases a sweep file lists by name (`- name: mass+10%`, docs/sweeps.md), "none" first:
/// mass −10, −5, +5, +10 %; k_T ±5 %; motor spread ±5 %; CoG 1 cm; in-flight cushion 0.5×, 0.8×,
/// 1.2×; mocap latency +20 ms; gusts 0.3 m/s; per-rotor Cheeseman–Bennett; per-rotor
/// Sanchez-Cuevas. The suite's grid (which of them it flies, with which controllers, heights and
/// seeds) is its sweep file's, config/sweeps/robustness.yaml (experiments/suite_sweep.hpp).
[[nodiscard]] std::vector<Perturbation> robustnessCells();

/// Changes the world of `s` (its truth, sensors and disturbances; never its vehicle, controller
/// or residual: the belief) as `p` says. Throws std::invalid_argument when s.truth is empty.
void applyPerturbation(const Perturbation& p, FlightScenario& s);

/// A configuration flown by the suite.
struct SuiteController {
  std::string name;  ///< control::configurationName: "model:model_indi", "recommended", …
  control::ControllerParams params;
};

/// A height and speed of a suite: a lemniscate flown over flat ground (a scenario of the suite's
/// sweep file).
struct SuiteCondition {
  std::string name;                   ///< the scenario's name in the sweep file, e.g. "lem-0.12m-1mps"
  traj::LemniscateParams lemniscate;  ///< the path flown
  /// The Table I row whose lemniscate has this one's shape (extents, laps, ramps, centre, yaw;
  /// at any height and speed), the first of them; 0: none.
  int experiment = 0;

  [[nodiscard]] double height_m() const noexcept { return lemniscate.height_m; }
  [[nodiscard]] double speed_mps() const noexcept { return lemniscate.peak_speed_mps; }
  /// "exp 1's lemniscate", or "lemniscate NAME" when it is no Table I row's shape.
  [[nodiscard]] std::string describe() const;
};

/// The condition that flies `lemniscate`, with its Table I row found by shape.
[[nodiscard]] SuiteCondition suiteCondition(const traj::LemniscateParams& lemniscate, std::string name = {});

// --- Running it ------------------------------------------------------------------------------

struct RobustnessOptions {
  /// The vehicle file (nominal): the belief starts from it (calibrateController).
  model::VehicleParams vehicle;
  /// The unperturbed world (truth, per-flight variation, sensors, disturbances; a truth file,
  /// docs/truth-file.md); empty: sim::idealWorld(vehicle).
  std::optional<sim::World> world;
  /// The grid: cases, configurations, heights/speeds (at distinct heights) and seeds; the
  /// suite's own is its sweep file's (robustnessOptionsOf, experiments/suite_sweep.hpp).
  std::vector<Perturbation> cells;
  std::vector<SuiteController> controllers;
  std::vector<SuiteCondition> conditions;
  int seeds = 5;
  std::uint64_t first_seed = 1;
  int jobs = 0;                     ///< flight threads; 0: the hardware's
  std::filesystem::path cache_dir;  ///< Neural-Lander cache; empty: no cache
  double start_hover_s = 3.0;       ///< as the campaign (CampaignOptions::start_hover_s) [s]
  CalibrationSweeps calibration = CalibrationSweeps::defaults();
  NeuralSettings neural;
  /// The values of a controller-parameters file (`--controller-params`,
  /// docs/controller-params.md), applied to every configuration flown (control::applyParameters:
  /// the calibration's, the Neural-Lander's collection flights', each row's); empty: the
  /// compiled defaults.
  std::optional<control::ControllerParams> controller_values;
  Progress* progress = nullptr;  ///< stages and the flight counter; null: silent
};

/// One flight of a cell.
struct SuiteFlight {
  std::uint64_t seed = 0;
  bool struck = false;
  double strike_t_s = 0.0;  ///< plant time of the strike (struck only) [s]
  double rmse_all_cm = 0.0;  ///< up to the strike when struck (not comparable then) [cm]
  double rmse_xy_cm = 0.0;
  double rmse_z_cm = 0.0;
  double max_cm = 0.0;
  std::optional<double> guard_active_s;  ///< empty: the controller has no guard [s]
};

/// A flight's result as a suite flight (metrics in cm, the strike, the guard's time).
[[nodiscard]] SuiteFlight toSuiteFlight(std::uint64_t seed, const FlightResult& fr);

/// One cell of a suite: a case × a controller × a height/speed, over seeds.
struct SuiteCell {
  std::string case_name;
  std::string controller;
  double height_m = 0.0;
  double speed_mps = 0.0;
  std::vector<SuiteFlight> flights;  ///< in seed order

  [[nodiscard]] int strikes() const noexcept;
  /// Mean over the flights that finished; NaN when every flight struck [cm].
  [[nodiscard]] double meanFinished(double SuiteFlight::*metric) const noexcept;
  /// Mean guard time per flight; empty when the controller has no guard [s].
  [[nodiscard]] std::optional<double> guardActiveS() const noexcept;
};

/// The calibration of one world (the unperturbed one, or a law family's).
struct SuiteCalibration {
  std::string world;  ///< "none" or the case name
  ControllerCalibration calibration;
  std::optional<NeuralBaseline> neural;
};

/// A check of the issue on the suite's result, reported as it is.
struct SuiteCheck {
  std::string name;
  std::string criterion;
  std::string value;  ///< what we measured, e.g. "31 of 32 cells"
  bool pass = false;
};

struct RobustnessResult {
  std::vector<Perturbation> cases;
  std::vector<std::string> controllers;
  std::vector<SuiteCondition> conditions;
  std::vector<std::uint64_t> seeds;
  std::vector<SuiteCell> cells;  ///< case-major, then condition, then controller
  std::vector<SuiteCalibration> calibrations;
  std::vector<SuiteCheck> checks;
  std::string recommended;  ///< the ACC:TORQUE pair `recommended` stands for
  int threads = 1;
  std::size_t flights = 0;
  double simulated_s = 0.0;
  double calibration_s = 0.0;  ///< wall times [s]
  double neural_s = 0.0;
  double flights_s = 0.0;
  double wall_s = 0.0;

  /// The cell, or null.
  [[nodiscard]] const SuiteCell* cell(const std::string& case_name, const std::string& controller,
                                      double height_m) const noexcept;
};

/// Runs the suite. Throws std::invalid_argument for bad options (seeds < 1, no cell, no
/// controller, a duplicate name), and whatever a stage throws.
[[nodiscard]] RobustnessResult runRobustness(const RobustnessOptions& options);

// --- Comparing and summarising ---------------------------------------------------------------

/// Two controllers' flights of one case and height, seed by seed.
struct PairedComparison {
  int seeds = 0;          ///< seeds both flew
  int both_finished = 0;
  int only_a_struck = 0;  ///< a struck, b finished
  int only_b_struck = 0;
  int both_struck = 0;
  double a_rmse_all_cm = 0.0;  ///< means over the seeds both finished; NaN when none [cm]
  double b_rmse_all_cm = 0.0;

  /// a ranks at or above b: a struck on no seed on which b finished, and over the seeds both
  /// finished a's mean all-RMSE is at most factor × b's (true when there are none).
  [[nodiscard]] bool atMost(double factor = 1.0) const noexcept;
};

/// Compares a and b on the seeds both flew (matched by seed number).
[[nodiscard]] PairedComparison comparePaired(const SuiteCell& a, const SuiteCell& b);

/// The checks of `recommended` (those the flown cells and controllers allow):
/// 0 strikes in every cell; all-RMSE ≤ exp 2's configuration's (indi:none) and ≤ indi:indi's in
/// ≥ 90 % of the cells and ≤ half of it in "none"; ≤ model:model_indi's wherever that one
/// finishes; the guard never active in "none".
[[nodiscard]] std::vector<SuiteCheck> robustnessChecks(const RobustnessResult& r);

/// Text summary: per height/speed a table case × controller (all-RMSE of the finished flights,
/// strikes), the checks, the wall times.
[[nodiscard]] std::string formatRobustness(const RobustnessResult& r);

/// The suite document: {"geaware_version", "suite": "robustness", "recommended", "seeds",
/// "cases", "controllers", "cells", "checks", "calibrations", "timing"} (NaN as null).
[[nodiscard]] io::Json robustnessJson(const RobustnessResult& r);

/// One cell in the shared suite schema.
[[nodiscard]] io::Json suiteCellJson(const SuiteCell& c);

/// A suite's checks in its JSON: [{"name", "criterion", "value", "pass"}, …].
[[nodiscard]] io::Json suiteChecksJson(const std::vector<SuiteCheck>& checks);
/// A suite's checks as a report table (check, criterion, measured, result).
[[nodiscard]] report::Table suiteChecksTable(const std::vector<SuiteCheck>& checks);

/// The report page: the checks, then per height/speed two heat maps (strikes, all-RMSE) case ×
/// controller, and the calibrations.
[[nodiscard]] report::Page robustnessPage(const RobustnessResult& r, const io::RunInfo& run);

/// Writes DIR/robustness.html (creating DIR) and, with `png`, DIR/robustness.png; returns the
/// HTML path. Throws std::runtime_error when it cannot be written.
std::filesystem::path writeRobustnessReport(const RobustnessResult& r,
                                            const std::filesystem::path& dir,
                                            const io::RunInfo& run, bool png = false);

}  // namespace geaware::experiments
