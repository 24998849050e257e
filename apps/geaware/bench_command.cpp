// SPDX-License-Identifier: BSD-3-Clause
// `geaware bench`: parse the options into experiments::CampaignOptions, run the campaign, print.
// Thin: the campaign, its text, JSON and report live in the experiments layer.

#include "commands.hpp"
#include "numbers.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "geaware/experiments/beyond_suite.hpp"
#include "geaware/experiments/campaign.hpp"
#include "geaware/experiments/campaign_report.hpp"
#include "geaware/experiments/campaign_summary.hpp"
#include "geaware/experiments/fault_suite.hpp"
#include "geaware/experiments/robustness.hpp"
#include "geaware/experiments/suite_sweep.hpp"
#include "geaware/experiments/sweep.hpp"
#include "geaware/experiments/world_setup.hpp"
#include "geaware/io/config_error.hpp"
#include "geaware/io/controller_params_file.hpp"
#include "geaware/io/output_file.hpp"
#include "geaware/io/truth_file.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "progress.hpp"

namespace geaware::cli {
namespace {

struct BenchOptions {
  std::string suite = "table";  ///< "table" (the paper's campaign), "robustness", "faults", "beyond"
  std::vector<std::string> cases;        ///< robustness, faults: the cases; beyond: the scenarios (empty: all)
  std::vector<std::string> controllers;  ///< robustness, faults, beyond: the configurations (empty: all)
  std::string sweep;  ///< robustness, faults, beyond: the suite's sweep file (empty: the shipped one)
  bool seeds_given = false;       ///< --seeds on the command line (a suite: replaces its sweep file's)
  bool first_seed_given = false;  ///< --first-seed likewise
  std::string vehicle;
  std::string truth;
  std::string controller_params;  ///< --controller-params FILE (empty: the compiled defaults)
  int seeds = 5;
  std::uint64_t first_seed = 1;
  std::vector<std::string> only;
  int jobs = 0;
  std::string json;
  std::string report;
  std::string cache;  ///< empty: the per-user default (defaultCacheDir)
  std::string neural_weights;  ///< the Neural-Lander baseline's weights (empty: trained here)
  bool no_cache = false;
  bool truth_mismatch = false;
  bool no_turbulence = false;
  std::string ground_effect = "paper";  ///< form the calibration identifies F_G and M_G in
  bool check = false;
  bool png = false;
  bool quiet = false;
};

/// The items of `all` named in `names`, in the order named; a UsageError naming `option` and
/// the valid names for an unknown one, or the name for one named twice.
template <class T, class NameOf>
std::vector<T> pick(const std::vector<T>& all, const std::vector<std::string>& names,
                    const std::string& option, NameOf name_of) {
  std::vector<T> out;
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string& n = names[k];
    if (std::find(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(k), n) !=
        names.begin() + static_cast<std::ptrdiff_t>(k)) {
      throw UsageError(option + " '" + n + "': named twice");
    }
    const auto it = std::find_if(all.begin(), all.end(), [&](const T& t) { return name_of(t) == n; });
    if (it == all.end()) {
      std::string valid;
      for (const auto& t : all) valid += (valid.empty() ? "" : ", ") + name_of(t);
      throw UsageError(option + " '" + n + "': expected one of " + valid);
    }
    out.push_back(*it);
  }
  return out;
}

/// The configurations named by --controllers, in the order named (all without it).
std::vector<experiments::SuiteController> pickControllers(const BenchOptions& o,
                                                          const std::vector<experiments::SuiteController>& all) {
  if (o.controllers.empty()) return all;
  return pick(all, o.controllers, "--controllers", [](const experiments::SuiteController& k) { return k.name; });
}

/// The exit status of a run whose results are in: 3 with --check when a check failed, else 0.
template <class Check>
int exitStatus(const BenchOptions& o, const std::vector<Check>& checks) {
  return o.check && std::any_of(checks.begin(), checks.end(), [](const Check& c) { return !c.pass; }) ? 3 : 0;
}

/// The per-user cache directory of the Neural-Lander weights: $XDG_CACHE_HOME/geaware, else
/// $HOME/.cache/geaware (the XDG base directory specification's default); empty without either.
std::string defaultCacheDir() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg != nullptr && xdg[0] == '/') return (std::filesystem::path(xdg) / "geaware").string();
  const char* home = std::getenv("HOME");
  if (home != nullptr && home[0] != '\0') return (std::filesystem::path(home) / ".cache" / "geaware").string();
  return {};
}

/// The inputs and outputs of a run, to check before any work (docs/reliability.md); `sweep`:
/// the suite's sweep file (empty: none).
io::OutputChecks benchFiles(const BenchOptions& o, const std::string& sweep) {
  io::OutputChecks files;
  files.input("--sweep", sweep);
  files.input("--vehicle", o.vehicle);
  files.input("--truth", truthInputFile(o.truth));
  files.input("--controller-params", o.controller_params);
  files.input("--neural-weights", o.neural_weights);
  files.output("--json", o.json);
  files.directory("--report", o.report);
  return files;
}

/// Every input and output checked before any work (benchFiles); returns the cache directory to
/// use: --cache (an error when it cannot be written), else the per-user default, which falls
/// back to no cache with a warning when it cannot be written; empty with --no-cache.
std::string checkFiles(const BenchOptions& o, const std::string& sweep = {}) {
  io::OutputChecks files = benchFiles(o, sweep);
  if (!o.no_cache && !o.cache.empty()) files.directory("--cache", o.cache);
  files.check();
  if (o.no_cache || !o.cache.empty()) return o.no_cache ? std::string() : o.cache;
  const std::string cache = defaultCacheDir();
  try {
    if (cache.empty()) throw io::OutputError("neither XDG_CACHE_HOME nor HOME is set");
    (void)io::checkOutputDirectory("the cache directory", cache);
  } catch (const io::OutputError& e) {
    std::cerr << "geaware: warning: no cache for the Neural-Lander weights (" << e.what()
              << "); the network is trained and not saved (give --cache DIR to keep it)\n";
    return {};
  }
  return cache;
}

/// The vehicle file the belief starts from: --vehicle, or the built-in one.
model::VehicleParams benchVehicle(const BenchOptions& o) {
  return o.vehicle.empty() ? io::builtinVehicle() : io::loadVehicleFile(o.vehicle);
}

/// The world the rigs and flights run in: --truth, or the default world of `vehicle`.
sim::World benchWorld(const BenchOptions& o, const model::VehicleParams& vehicle) {
  return o.truth.empty() ? experiments::defaultWorld(vehicle, o.vehicle.empty(), o.vehicle)
                         : io::resolveTruth(o.truth, {});
}

/// What a warning of a long grid (warnOfLongSweep) advises.
constexpr const char* kLongAdvice = "bench keeps its flights in memory until all are flown (`geaware sweep` flies "
                                    "the same file resumably, one record per flight)";

/// The suite's sweep file as shipped (docs/install.md): beside the running program
/// (<prefix>/bin/../share/geaware/config/sweeps), then this source tree's config/ (a program of
/// the build tree), then the configured install prefix's.
std::filesystem::path shippedSweepFile(const std::string& suite) {
  namespace fs = std::filesystem;
  const fs::path rel = fs::path("sweeps") / (suite + ".yaml");
  std::vector<fs::path> places;
  std::error_code ec;
  if (const fs::path exe = fs::read_symlink("/proc/self/exe", ec); !ec && !exe.empty()) {
    places.push_back((exe.parent_path() / GEAWARE_CONFIG_RELATIVE_DIR / rel).lexically_normal());
  }
  places.push_back(fs::path(GEAWARE_CONFIG_SOURCE_DIR) / rel);
  places.push_back(fs::path(GEAWARE_CONFIG_INSTALL_DIR) / rel);
  std::string tried;
  for (const auto& p : places) {
    if (fs::is_regular_file(p, ec)) return p;
    tried += (tried.empty() ? "" : ", ") + p.string();
  }
  throw UsageError("--suite " + suite + ": the suite's sweep file is not installed (looked for " + tried +
                   "); give it with --sweep FILE");
}

/// The suite's sweep file (--sweep, else the shipped one) and what it says, the files it names
/// read too; --vehicle, --truth and --controller-params replace the file's, and --seeds and
/// --first-seed its seeds when given.
struct SuiteSweep {
  std::filesystem::path file;
  experiments::SweepSpec spec;
};

SuiteSweep suiteSweep(const BenchOptions& o) {
  SuiteSweep s;
  s.file = o.sweep.empty() ? shippedSweepFile(o.suite) : std::filesystem::path(o.sweep);
  experiments::SweepSpec& spec = s.spec;
  spec = experiments::loadSweepFile(s.file);
  // The fingerprint (the key a sweep's calibration is memoised under) says what replaced what.
  if (!o.vehicle.empty() || !o.truth.empty()) {
    spec.vehicle = benchVehicle(o);
    spec.world = benchWorld(o, spec.vehicle);
    spec.world_reference = o.truth.empty() ? "default" : o.truth;
  }
  if (!o.controller_params.empty()) spec.controller_values = io::loadControllerParamsFile(o.controller_params);
  spec.fingerprint += "|vehicle=" + o.vehicle + "|truth=" + o.truth + "|params=" + o.controller_params;
  if (o.seeds_given) spec.seed_count = static_cast<std::uint64_t>(o.seeds);
  if (o.first_seed_given) spec.first_seed = o.first_seed;
  return s;
}

/// The options of a suite (`of`: experiments/suite_sweep.hpp) from its sweep file; a file the
/// suite cannot fly is a usage error naming the file, the items and what the suite expects.
template <class Options>
Options suiteOptions(const SuiteSweep& s, const std::string& suite, Options (*of)(const experiments::SweepSpec&)) {
  try {
    return of(s.spec);
  } catch (const io::ConfigError& e) {
    throw UsageError("--suite " + suite + " cannot fly this sweep file: " + e.what());
  }
}

/// What every suite prints once flown: the command line, the world and `text` on stdout (on
/// stderr with --json -), and `json` with the run's provenance to --json; returns the
/// provenance (the report pages carry it).
io::RunInfo printSuite(const BenchOptions& o, const std::string& sweep_file, const std::vector<std::uint64_t>& seeds,
                       const std::string& world, const std::string& text, io::Json json) {
  const io::RunInfo run = runInfo(seeds, {sweep_file, o.vehicle, truthInputFile(o.truth), o.controller_params});
  std::FILE* human = o.json == "-" ? stderr : stdout;
  fmt::print(human, "{}\nworld: {}\n{}", commandLine(), world, text);
  std::fflush(human);
  if (!o.json.empty()) writeJsonOutput(o.json, std::move(json), run);
  return run;
}

/// `--suite robustness` (experiments/robustness.hpp, docs/robustness.md).
int runRobustnessSuite(const BenchOptions& o) {
  const SuiteSweep sweep = suiteSweep(o);
  experiments::RobustnessOptions c = suiteOptions(sweep, o.suite, &experiments::robustnessOptionsOf);
  if (!o.cases.empty()) {
    c.cells = pick(c.cells, o.cases, "--cases",
                   [](const experiments::Perturbation& p) { return p.name; });
  }
  c.controllers = pickControllers(o, c.controllers);
  c.jobs = o.jobs;
  warnOfLongSweep(sweep.spec, c.cells.size(), c.controllers.size(), {}, kLongAdvice);
  c.cache_dir = checkFiles(o, sweep.file.string());
  TerminalProgress progress("geaware bench", o.quiet);
  c.progress = &progress;
  const experiments::RobustnessResult r = experiments::runRobustness(c);
  progress.end();
  const io::RunInfo run = printSuite(o, sweep.file.string(), r.seeds, c.world->source, experiments::formatRobustness(r),
                                     experiments::robustnessJson(r));
  if (!o.report.empty()) {
    const auto html = experiments::writeRobustnessReport(r, o.report, run, o.png);
    std::cerr << "geaware bench: wrote " << html.string() << (o.png ? " and robustness.png" : "")
              << "\n";
  }
  return exitStatus(o, r.checks);
}

/// `--suite faults` (experiments/fault_suite.hpp, docs/reliability.md "Fault campaign").
int runFaultSuite(const BenchOptions& o) {
  const SuiteSweep sweep = suiteSweep(o);
  experiments::FaultSuiteOptions c = suiteOptions(sweep, o.suite, &experiments::faultSuiteOptionsOf);
  if (!o.cases.empty()) {
    c.cases = pick(c.cases, o.cases, "--cases", [](const experiments::FaultCase& k) { return k.name; });
    if (c.cases.front().name != "none") {
      throw UsageError("--cases: the fault suite compares every case with \"none\": list it first");
    }
  }
  c.controllers = pickControllers(o, c.controllers);
  c.jobs = o.jobs;
  warnOfLongSweep(sweep.spec, c.cases.size(), c.controllers.size(), {}, kLongAdvice);
  benchFiles(o, sweep.file.string()).check();
  TerminalProgress progress("geaware bench", o.quiet);
  c.progress = &progress;
  const experiments::FaultSuiteResult r = experiments::runFaultSuite(c);
  progress.end();
  (void)printSuite(o, sweep.file.string(), r.seeds, c.world->source, experiments::formatFaultSuite(r),
                   experiments::faultSuiteJson(r));
  return exitStatus(o, r.checks);
}

/// `--suite beyond` (experiments/beyond_suite.hpp, docs/controller.md "The beyond suite").
int runBeyondSuite(const BenchOptions& o) {
  // Everything is read first (the files the sweep file names among them), then the outputs are
  // checked against all of it, before any flight.
  const SuiteSweep sweep = suiteSweep(o);
  const experiments::SweepSpec& spec = sweep.spec;
  const std::filesystem::path& file = sweep.file;
  if (spec.cases.size() != 1) {
    throw UsageError(fmt::format("--sweep {}: {} perturbation cases; the beyond suite flies one world (give a "
                                 "file with one case, or fly it with `geaware sweep`)",
                                 file.string(), spec.cases.size()));
  }
  (void)pick(spec.scenarios, o.cases, "--cases", [](const experiments::SweepScenario& s) { return s.name; });
  warnOfLongSweep(spec, 1, pickControllers(o, spec.controllers).size(), o.cases, kLongAdvice);
  benchFiles(o, file.string()).check();

  experiments::BeyondOptions c;
  c.scenarios = o.cases;
  c.controllers = o.controllers;
  c.jobs = o.jobs;
  c.collect_series = !o.report.empty();
  TerminalProgress progress("geaware bench", o.quiet);
  c.progress = &progress;
  const experiments::BeyondResult r = experiments::runBeyond(spec, c);
  progress.end();
  const io::RunInfo run =
      printSuite(o, file.string(), r.seeds, spec.world.source, experiments::formatBeyond(r), experiments::beyondJson(r));
  if (!o.report.empty()) {
    const auto html = experiments::writeBeyondReport(r, o.report, run, o.png);
    std::cerr << "geaware bench: wrote " << html.string() << " and a page per scenario"
              << (o.png ? " and beyond.png" : "") << "\n";
  }
  return exitStatus(o, r.checks);
}

int runBench(const BenchOptions& o) {
  if (o.truth_mismatch) {
    throw UsageError(
        "--truth-mismatch moved into the truth file: give --truth a truth file whose "
        "truth.per_flight_variation holds the bounds, e.g. --truth config/truths/ideal_varied.yaml "
        "(today's --truth-mismatch; docs/truth-file.md)");
  }
  if (o.suite == "robustness") return runRobustnessSuite(o);
  if (o.suite == "faults") return runFaultSuite(o);
  if (o.suite == "beyond") return runBeyondSuite(o);
  experiments::CampaignOptions c;
  c.vehicle = benchVehicle(o);
  c.world = benchWorld(o, c.vehicle);
  if (!o.controller_params.empty()) c.controller_values = io::loadControllerParamsFile(o.controller_params);
  c.seeds = o.seeds;
  c.first_seed = o.first_seed;
  c.jobs = o.jobs;
  if (!o.only.empty()) {
    c.experiments.clear();
    c.hover = false;
    for (const auto& e : o.only) {
      if (e == "hover") {
        c.hover = true;
      } else {
        c.experiments.push_back(std::stoi(e));
      }
    }
  }
  c.cache_dir = checkFiles(o);
  c.neural_weights = o.neural_weights;
  c.turbulence = !o.no_turbulence;
  c.calibration.tables = o.ground_effect == "table";
  c.collect_series = !o.report.empty();
  TerminalProgress progress("geaware bench", o.quiet);
  c.progress = &progress;
  const experiments::CampaignResult r = experiments::runCampaign(c);
  progress.end();
  std::vector<std::uint64_t> seeds;
  for (int k = 0; k < o.seeds; ++k) seeds.push_back(o.first_seed + static_cast<std::uint64_t>(k));
  const io::RunInfo run = runInfo(seeds, {o.vehicle, truthInputFile(o.truth), o.controller_params});

  std::FILE* human = o.json == "-" ? stderr : stdout;
  fmt::print(human, "{}\n", commandLine());
  if (c.calibration.tables) {
    fmt::print(human, "calibration: F_G and M_G identified as tables (--ground-effect table)\n");
  }
  fmt::print(human, "world: {}\n", c.world->source);
  if (o.no_turbulence) fmt::print(human, "truth overrides: no near-ground turbulence\n");
  fmt::print(human, "{}", experiments::formatCampaign(r));
  std::fflush(human);

  if (!o.json.empty()) writeJsonOutput(o.json, experiments::campaignJson(r), run);
  if (!o.report.empty()) {
    const auto html = experiments::writeCampaignReport(r, o.report, run, o.png);
    std::cerr << "geaware bench: wrote " << html.string() << (o.png ? " and bench.png" : "") << "\n";
  }
  return exitStatus(o, r.checks);
}

}  // namespace

Runner addBenchCommand(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  auto* cmd = app.add_subcommand(
      "bench",
      "The paper's experiments: calibrate on the virtual rigs, train the Neural-Lander baseline, "
      "fly Table I and the hover experiment over seeds, compare with the paper");
  cmd->add_option("--suite", o->suite,
                  "'table': the paper's Table I and hover experiment; 'robustness': every Table I "
                  "configuration, indi:indi and recommended in worlds changed after the "
                  "calibration (docs/robustness.md); 'faults': the paper's configuration, INDI and "
                  "recommended with a motor, sensor, battery or gust fault mid-flight (docs/reliability.md); "
                  "'beyond': the paper's configuration, INDI and recommended past the paper: a table edge, "
                  "a step, a ramp, a ceiling, a wall, 5 m/s low, a landing, a take-off, learning in flight "
                  "(docs/controller.md). The last three fly the grid of their shipped sweep file, "
                  "config/sweeps/SUITE.yaml, or of --sweep FILE")
      ->check(CLI::IsMember({"table", "robustness", "faults", "beyond"}))
      ->capture_default_str();
  cmd->add_option("--cases", o->cases,
                  "robustness, faults: fly only these of the sweep file's cases, comma separated (default: all; "
                  "names in docs/robustness.md, e.g. none,mass+10%); beyond: only these scenarios (e.g. "
                  "landing,takeoff)")
      ->delimiter(',');
  cmd->add_option("--controllers", o->controllers,
                  "robustness, faults, beyond: fly only these of the sweep file's configurations, comma separated "
                  "(default: all; e.g. model:model_indi,recommended)")
      ->delimiter(',');
  cmd->add_option("--sweep", o->sweep,
                  "robustness, faults, beyond: the suite's sweep file (docs/sweeps.md; default: the shipped "
                  "config/sweeps/robustness.yaml, faults.yaml, beyond.yaml): its cases, controllers, scenarios "
                  "and seeds (--seeds and --first-seed replace them); beyond flies its one case's world")
      ->check(CLI::ExistingFile);
  addVehicleOption(cmd, o->vehicle,
                   "vehicle YAML file (default: the built-in paper quadrotor); the controller gets it "
                   "with the parameters identified on the virtual rigs; without --truth the world is "
                   "its ideal world");
  cmd->add_option("--controller-params", o->controller_params,
                  "controller-parameters YAML file (docs/controller-params.md): its gains, rate, "
                  "cut-off and limits in every configuration flown, and its additions' settings "
                  "where a configuration switches them on (default: the compiled defaults)");
  addTruthOption(cmd, o->truth,
                 "the world the rigs and flights run in: a truth file (docs/truth-file.md; any "
                 "vehicle file is one) or a built-in world (ideal, as_built) (default: as_built with "
                 "the built-in vehicle)");
  cmd->add_option("--seeds", o->seeds,
                  "flights per experiment or hover curve; per suite cell, replacing the sweep file's (the "
                  "shipped files': 5)")
      ->capture_default_str()
      ->check(wholeIn(1, 1000));
  cmd->add_option("--first-seed", o->first_seed,
                  "seeds are first-seed … first-seed + seeds − 1 (a suite: replaces the sweep file's)")
      ->check(seed())
      ->capture_default_str();
  cmd->add_option("--only", o->only,
                  "fly only these: Table I experiments 1–8 (the paper's), 9–10 (recommended) "
                  "and/or 'hover'")
      ->check(CLI::IsMember({"1", "2", "3", "4", "5", "6", "7", "8", "9", "10", "hover"}));
  cmd->add_option("--jobs", o->jobs, "parallel flights (0: one per core); results do not depend on it")
      ->capture_default_str()
      ->check(wholeIn(0, 256));
  cmd->add_option("--json", o->json, "write the results as JSON ('-': stdout, the summary goes to stderr)");
  cmd->add_option("--report", o->report, "write an HTML report into DIR (bench.html; robustness.html; beyond.html "
                  "and a page per scenario)");
  cmd->add_option("--cache", o->cache,
                  "directory of the cached Neural-Lander weights (default: $XDG_CACHE_HOME/geaware, "
                  "else ~/.cache/geaware; without it, or when it cannot be written, a warning and no cache)");
  cmd->add_flag("--no-cache", o->no_cache, "always retrain the Neural-Lander network, save nothing");
  cmd->add_option("--neural-weights", o->neural_weights,
                  "fly this weight file as the Neural-Lander baseline (e.g. from `geaware train-residual` on your "
                  "logs) instead of training one (--suite table)")
      ->check(CLI::ExistingFile);
  // Moved into the truth file (truth.per_flight_variation): kept, hidden, to say where.
  cmd->add_flag("--truth-mismatch", o->truth_mismatch)->group("");
  cmd->add_flag("--no-turbulence", o->no_turbulence, "switch off the truth's near-ground turbulence");
  cmd->add_option("--ground-effect", o->ground_effect,
                  "form in which the calibration identifies F_G and M_G for the controllers: 'paper' (closed "
                  "forms) or 'table' (values at the swept heights)")
      ->check(CLI::IsMember({"paper", "table"}))
      ->capture_default_str();
  cmd->add_flag("--check", o->check, "exit with status 3 when an acceptance check fails");
  cmd->add_flag("--png", o->png, "with --report: also the whole page as DIR/bench.png (Chromium; "
                                 "robustness.png, beyond.png for those suites)");
  cmd->add_flag("--quiet", o->quiet, "no progress on stderr");
  cmd->parse_complete_callback([o, cmd]() {
    o->seeds_given = cmd->count("--seeds") > 0;
    o->first_seed_given = cmd->count("--first-seed") > 0;
    if (o->first_seed > std::numeric_limits<std::uint64_t>::max() - static_cast<std::uint64_t>(o->seeds - 1)) {
      throw CLI::ValidationError("--first-seed", "--first-seed " + std::to_string(o->first_seed) + " + --seeds " +
                                                     std::to_string(o->seeds) + " - 1 is above 2^64 - 1");
    }
    if (o->png && o->report.empty()) throw CLI::ValidationError("--png", "--png needs --report DIR");
    if (o->suite != "table" &&
        (!o->only.empty() || o->no_turbulence || o->ground_effect != "paper")) {
      throw CLI::ValidationError("--suite", "--only, --no-turbulence and --ground-effect apply to "
                                            "--suite table only");
    }
    if (o->suite == "table" && (!o->cases.empty() || !o->controllers.empty())) {
      throw CLI::ValidationError("--cases", "--cases and --controllers need --suite robustness, faults or beyond");
    }
    if (o->suite == "table" && !o->sweep.empty()) {
      throw CLI::ValidationError("--sweep", "--sweep applies to --suite robustness, faults and beyond");
    }
    if (o->suite == "beyond" && (!o->cache.empty() || o->no_cache)) {
      throw CLI::ValidationError("--cache", "--cache and --no-cache apply to --suite table and robustness "
                                            "(a sweep file's neural controllers are trained by the sweep, uncached)");
    }
    if (o->suite != "table" && !o->neural_weights.empty()) {
      throw CLI::ValidationError("--neural-weights", "applies to --suite table (the robustness suite trains its "
                                                     "own network per world; the fault and beyond suites fly none)");
    }
    if (o->suite == "faults" && (!o->report.empty() || !o->cache.empty() || o->no_cache)) {
      throw CLI::ValidationError("--suite", "--report and --cache apply to --suite table and robustness "
                                            "(the fault suite flies no neural network and has no report page yet)");
    }
  });
  return [o]() { return runBench(*o); };
}

}  // namespace geaware::cli
