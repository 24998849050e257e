// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Subcommands of the geaware CLI. Each registers its options on the app and returns the
// function that runs it; the work itself lives in the libraries. One convention for all:
// `--json -` puts only the JSON document on stdout (human text goes to stderr then), every JSON
// document carries its provenance, usage errors exit with status 2, bad input with 1.

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "geaware/io/provenance.hpp"

namespace geaware::experiments {
struct SweepSpec;
}  // namespace geaware::experiments

namespace geaware::cli {

using Runner = std::function<int()>;

/// A usage error found after parsing (a combination of options CLI11 cannot express): main
/// prints it and exits with status 2.
class UsageError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// The command line this process was started with, shell-quoted (for the provenance of every
/// output); set once by main before any command runs.
[[nodiscard]] const std::string& commandLine();

/// What this run was given: the command line, `seeds` and the files in `inputs` (empty paths
/// are left out).
[[nodiscard]] io::RunInfo runInfo(std::vector<std::uint64_t> seeds, std::vector<std::string> inputs);

/// Writes `doc` with "provenance" (io::provenanceJson(run)) added to `path` ("-": stdout).
void writeJsonOutput(const std::string& path, io::Json doc, const io::RunInfo& run);

/// `--vehicle FILE` (an existing file) on `cmd`; `what` says what the file is used for here.
CLI::Option* addVehicleOption(CLI::App* cmd, std::string& path,
                              const std::string& what = "vehicle YAML file (default: the built-in "
                                                        "paper quadrotor)");

/// `--truth FILE` on `cmd`: a truth file (docs/truth-file.md; a vehicle file is one) or the
/// name of a built-in world (io::builtinTruthNames); `what` says what it replaces here.
CLI::Option* addTruthOption(CLI::App* cmd, std::string& reference, const std::string& what);
/// The file behind a --truth reference, for the provenance; empty for a built-in name.
[[nodiscard]] std::string truthInputFile(const std::string& reference);

/// `geaware model`: the controller-side ground-effect model tabulated over heights.
Runner addModelCommand(CLI::App& app);
/// `geaware fly`: one closed-loop flight (experiments/flight.hpp): the Table I metrics, the
/// crash, the real-time factor; optionally the CSV log, JSON and a report. docs/closed-loop.md.
Runner addFlyCommand(CLI::App& app);
/// `geaware bench`: the paper's experiments (experiments/campaign.hpp): calibration, the
/// Neural-Lander baseline, Table I and the hover experiment over seeds. docs/results.md.
Runner addBenchCommand(CLI::App& app);
/// `geaware sweep SPEC.yaml --out DIR`: the flights of a sweep file, one record file per flight,
/// merged into DIR/results.json (experiments/sweep.hpp). docs/sweeps.md.
Runner addSweepCommand(CLI::App& app);
/// Warns on stderr, before any flight and even with --quiet, of a grid of more than
/// experiments::kSweepLongSimulatedS of simulated flight: `cases` × `controllers` × the scenarios
/// named (empty: all) × the seeds of `spec`, with how many flights and hours; `advice` follows.
void warnOfLongSweep(const experiments::SweepSpec& spec, std::size_t cases, std::size_t controllers,
                     const std::vector<std::string>& scenarios, const std::string& advice);
/// `geaware identify {rotor,platform,flight,correlations} LOG.csv`: identification from rig and
/// flight logs (ident/identify.hpp). docs/identification.md.
Runner addIdentifyCommand(CLI::App& app);
/// `geaware logs inspect LOG`: topics, rates, gaps and channel health of a flight log
/// (io/log_inspect.hpp). docs/identification.md.
Runner addLogsCommand(CLI::App& app);
/// `geaware train-residual LOGS… --out weights.yaml`: the Neural-Lander baseline trained on flight
/// logs (experiments/neural_baseline.hpp). docs/neural-lander.md.
Runner addTrainCommand(CLI::App& app);
/// `geaware rig {platform,rotor,calibrate}`: the virtual test rigs on the truth simulator and the
/// calibration of the truth against the paper's measurements. docs/sim-aerodynamics.md.
Runner addRigCommand(CLI::App& app);
/// `geaware sitl` and `geaware bridge` (built with -DGEAWARE_BRIDGE=ON): the truth simulator
/// as a DDS vehicle, and the estimator + controller over PX4's uXRCE-DDS topics. docs/bridge.md.
Runner addSitlCommand(CLI::App& app);
Runner addBridgeCommand(CLI::App& app);

}  // namespace geaware::cli
