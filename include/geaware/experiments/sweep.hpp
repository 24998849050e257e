// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Sweeps (issue 15 item 3, docs/sweeps.md): truth perturbations × controllers × scenarios ×
// seeds, read from a YAML sweep file. Every flight has a key, a canonical string such as
//   case=mass+10%/ctl=recommended/scn=lem-0.12m-1mps/seed=3
// (the parts always in this order; the keys of a sweep in spec order: case, controller,
// scenario, seed), and its result record is a pure function of the spec and the key
// (runSweepFlight): the same bytes whatever thread, process or machine flies it. A run writes
// one file per key (DIR/flights/<sweepKeyFileName(key)>) and merges them into DIR/results.json
// (mergeSweep), which is therefore byte-identical however the flights were spread.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geaware/control/controller_params.hpp"
#include "geaware/experiments/fault_suite.hpp"
#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/robustness.hpp"
#include "geaware/model/vehicle_params.hpp"
#include "geaware/sim/terrain.hpp"
#include "geaware/sim/world.hpp"
#include "geaware/traj/trajectory.hpp"

namespace geaware::experiments {

/// Limits checked when the file is read, before any work.
inline constexpr std::size_t kSweepMaxCases = 1000;
inline constexpr std::size_t kSweepMaxControllers = 100;
inline constexpr std::size_t kSweepMaxScenarios = 1000;
inline constexpr std::size_t kSweepMaxFlights = 1'000'000;  ///< cases × controllers × scenarios × seeds
/// The longest file name of a flight's record (file systems allow 255 bytes; the temporary
/// file beside it adds 17) [bytes].
inline constexpr std::size_t kSweepMaxFileName = 200;

/// A flown trajectory and its surface.
struct SweepScenario {
  std::string name;  ///< the key's `scn=` part, e.g. "lem-0.12m-1mps"
  std::shared_ptr<const traj::Trajectory> trajectory;
  std::shared_ptr<const sim::Terrain> terrain;  ///< null: flat ground at z = 0
  std::shared_ptr<const sim::Obstacles> obstacles;  ///< ceilings and walls; null: none
  std::vector<sim::BeamRangerParams> beam_rangers;  ///< empty: the default set with obstacles
};

/// A parsed sweep file.
struct SweepSpec {
  std::string source;  ///< the file as named (errors)
  /// SHA-256 of the file's bytes and of every file it names, however deeply (scenario, height-map,
  /// vehicle, truth, controller-parameters files): identifies the sweep (memo, DIR).
  std::string fingerprint;
  /// SHA-256 of the sweep file's bytes alone (the fingerprint of builds before 2026-11-29,
  /// recognised in an old results directory).
  std::string file_sha256;
  model::VehicleParams vehicle;  ///< the belief's starting point (the vehicle file)
  sim::World world;              ///< the unperturbed world
  std::string world_reference;   ///< `world` as the file gives it ("default", a name, a path)
  bool calibrate = true;  ///< calibrateController in the unperturbed world (law cases: in theirs)
  double start_hover_s = 3.0;  ///< hover before the trajectory [s]
  /// A flight that would simulate longer is refused before it starts (FlightScenario::max_sim_s;
  /// file key max_sim_s) [s].
  double max_sim_s = 3600.0;
  std::vector<Perturbation> cases;
  /// Aligned with `cases`: what a `fault:` item breaks (a case of the fault suite: faults
  /// mid-flight, a mass error, the IMU's ranges; named as the item's `name` when it gives one);
  /// an empty FaultCase for the others.
  std::vector<FaultCase> case_faults;
  std::vector<SuiteController> controllers;
  std::optional<control::ControllerParams> controller_values;  ///< controller_params file
  std::vector<SweepScenario> scenarios;
  std::uint64_t first_seed = 1;
  std::uint64_t seed_count = 1;

  /// cases × controllers × scenarios × seeds.
  [[nodiscard]] std::size_t flights() const noexcept;
};

/// Reads a sweep file (format: docs/sweeps.md); relative paths inside it are resolved against
/// its folder. Throws io::ConfigError (file, line, key, expectation) — also for a list longer
/// than its limit or more than kSweepMaxFlights flights — or std::runtime_error when the file
/// cannot be read.
[[nodiscard]] SweepSpec loadSweepFile(const std::filesystem::path& file);
/// Parses sweep YAML; `source` names it in errors, `base_dir` resolves relative paths;
/// `max_sim_s_override`, when given, replaces the file's max_sim_s (for its scenarios too).
[[nodiscard]] SweepSpec parseSweepYaml(std::string_view yaml_text, const std::string& source,
                                       const std::filesystem::path& base_dir,
                                       std::optional<double> max_sim_s_override = {});

/// One flight of a sweep, by index.
struct SweepKey {
  std::size_t case_index = 0;
  std::size_t controller_index = 0;
  std::size_t scenario_index = 0;
  std::uint64_t seed = 0;
};

/// The canonical key text of `k`.
[[nodiscard]] std::string sweepKeyText(const SweepSpec& spec, const SweepKey& k);
/// Every key of the sweep, in spec order (case, controller, scenario, seed).
[[nodiscard]] std::vector<std::string> sweepKeys(const SweepSpec& spec);
/// The flight of `key`; throws std::invalid_argument naming the key and the part that is not
/// this sweep's.
[[nodiscard]] SweepKey parseSweepKey(const SweepSpec& spec, const std::string& key);
/// The file name of a key's record: the key with '/' written ',' and every byte other than
/// A–Z a–z 0–9 . + = - written _XX (hex), then ".json". Distinct keys, distinct names.
[[nodiscard]] std::string sweepKeyFileName(std::string_view key);

/// The flight of `k`, ready to fly: the (calibrated) belief, the perturbed world, the
/// controller, the trajectory and the seed. The calibrations are computed once per process
/// and sweep (memoised by the spec's fingerprint; thread-safe).
[[nodiscard]] FlightScenario sweepFlightScenario(const SweepSpec& spec, const SweepKey& k);
/// The problems of scenario `scenario_index` flown in the sweep's unperturbed world with its
/// first controller, uncalibrated (validate(…, kFile): rates, the trajectory's duration and
/// feasibility); loadSweepFile reports them at the scenario's line before any work.
[[nodiscard]] std::vector<ScenarioProblem> sweepScenarioProblems(const SweepSpec& spec,
                                                                 std::size_t scenario_index);
/// Calibrates (and trains, for a neural controller) every world that `keys` fly in, now, so
/// that their flights find them memoised; `progress` gets one message per world.
void prepareSweep(const SweepSpec& spec, const std::vector<std::string>& keys,
                  Progress* progress = nullptr);

/// A grid longer than this is warned of before it is flown (`bench` and `sweep`) [s of simulated
/// flight]: some 50 times the robustness suite's 1,120 flights.
inline constexpr double kSweepLongSimulatedS = 1.0e6;
/// The simulated seconds of `cases` × `controllers` × the seeds × the scenarios named in
/// `scenarios` (empty: all), each flight its start hover, trajectory and settling.
[[nodiscard]] double sweepSimulatedSeconds(const SweepSpec& spec, std::size_t cases, std::size_t controllers,
                                           const std::vector<std::string>& scenarios = {});

/// The flight's record: one line of JSON (no newline) with the key, its parts, the suite's
/// flight metrics (experiments::SuiteFlight) and the fault suite's `terminated` and
/// `non_finite_commands`, numbers in their shortest round-trip form.
[[nodiscard]] std::string sweepRecord(const SweepSpec& spec, const SweepKey& k, const FlightResult& r);
/// What case `i` changes (Perturbation::meaning, or the fault case's meaning).
[[nodiscard]] std::string sweepCaseMeaning(const SweepSpec& spec, std::size_t i);
/// Flies the key and returns its record (a pure function of spec and key).
[[nodiscard]] std::string runSweepFlight(const SweepSpec& spec, const std::string& key);

// --- The results directory -------------------------------------------------------------------

/// DIR/flights/<sweepKeyFileName(key)>.
[[nodiscard]] std::filesystem::path sweepFlightPath(const std::filesystem::path& dir,
                                                    const std::string& key);
/// Whether the key's record file exists and holds the record of `key` (parses, same key).
[[nodiscard]] bool sweepFlightDone(const std::filesystem::path& dir, const std::string& key);
/// The keys without a finished record, in spec order.
[[nodiscard]] std::vector<std::string> missingSweepKeys(const SweepSpec& spec,
                                                        const std::filesystem::path& dir);
/// Makes DIR and DIR/flights, and records the spec's fingerprint in DIR/sweep.sha256; throws
/// std::runtime_error when DIR holds another sweep's results (another fingerprint), and
/// io::OutputError, changing nothing, when DIR has no sweep.sha256 but holds a results.json or
/// a non-empty flights/ (not a sweep's: the merge would overwrite it, or merge it). In a DIR of
/// this sweep it removes the records' temporary files (`.<key>.json.geaware-XXXXXX`) older than an
/// hour, left by a run killed with SIGKILL; a younger one may be a concurrent writer's.
void prepareSweepDirectory(const SweepSpec& spec, const std::filesystem::path& dir);
/// Writes a key's record atomically (temporary file in DIR/flights, then rename).
void writeSweepFlight(const std::filesystem::path& dir, const std::string& key,
                      std::string_view record);
/// The merged document: {"geaware_version", "sweep": {cases, controllers, scenarios, seeds},
/// "flights", "records": [each record, in key order]} as io::dumpJson's text. Throws
/// std::runtime_error naming the number of missing keys and the first one.
[[nodiscard]] std::string mergeSweepText(const SweepSpec& spec, const std::filesystem::path& dir);
/// mergeSweepText written atomically to DIR/results.json; returns its path.
std::filesystem::path mergeSweep(const SweepSpec& spec, const std::filesystem::path& dir);

/// Called after each flight, one call at a time: done so far of total, the key.
using SweepProgress = std::function<void(std::size_t done, std::size_t total, const std::string& key)>;
/// Flies `keys` on `threads` threads (resolveThreads), each record written as soon as it is
/// flown. A flight that throws stops the others from starting; the first error is rethrown
/// with its key once every thread has finished. Returns the number of flights flown.
std::size_t runSweepKeys(const SweepSpec& spec, const std::filesystem::path& dir,
                         const std::vector<std::string>& keys, int threads,
                         const SweepProgress& progress = {});

}  // namespace geaware::experiments
