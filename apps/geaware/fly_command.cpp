// SPDX-License-Identifier: BSD-3-Clause
// `geaware fly`: parse the options into an experiments::FlightScenario, fly it, print the
// Table I metrics. Thin: the loop, the metrics, the log, the summary and the report live in the
// experiments layer.

#include "commands.hpp"
#include "numbers.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/flight_log.hpp"
#include "geaware/experiments/flight_setup.hpp"
#include "geaware/experiments/flight_summary.hpp"
#include "geaware/experiments/scenario_file.hpp"
#include "geaware/experiments/world_setup.hpp"
#include "geaware/io/controller_params_file.hpp"
#include "geaware/io/output_file.hpp"
#include "geaware/io/truth_file.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/io/vehicle_writer.hpp"
#include "progress.hpp"

namespace geaware::cli {
namespace {

struct FlyOptions {
  std::string scenario, vehicle, truth, trajectory, controller, out, json, report, neural_weights;
  std::string learned_vehicle;  ///< --learned-vehicle: the vehicle file with the F_G learned in flight
  std::string controller_params;  ///< --controller-params FILE (empty: the compiled defaults)
  double height_m = std::nan("");
  double speed_mps = std::nan("");
  double extent_x_m = 1.5;
  double extent_y_m = 0.8;
  int laps = 1;
  double height_swing_m = 0.0;
  double from_height_m = 1.5;
  double touchdown_speed_mps = 0.1;
  double flare_height_m = 0.3;
  std::uint64_t seed = 1;
  bool seed_given = false;  ///< --seed on the command line (it then replaces a scenario file's)
  bool no_turbulence = false;
  bool png = false;
  bool quiet = false;
  double start_hover_s = 1.0;
  double max_sim_s = std::nan("");  ///< NaN: the scenario file's, else FlightScenario's 3600 s
  double yaw_rate_gain = std::nan("");
  std::vector<std::string> ablate;
};

/// Parses "recommended" or "ACC:TORQUE" into the controller's configuration; false when malformed.
bool parseController(const std::string& text, control::ControllerParams& p) {
  return control::parseConfiguration(text, p);
}

/// CLI11 check of --controller (a malformed value is a usage error, exit status 2).
const CLI::Validator kControllerSpec(
    [](std::string& text) -> std::string {
      control::ControllerParams p;
      if (parseController(text, p)) return {};
      return "--controller '" + text +
             "': expected 'recommended' or ACC:TORQUE with ACC one of none, indi, neural, model "
             "and TORQUE one of none, model, indi, model_indi (e.g. model:model_indi), optionally "
             "followed by +proximity (ceiling and wall feed-forward; recommended has it), then by "
             "+rotors (per-rotor ground effect from the ranger), then by +learn or +learn0 (F_G "
             "learned in flight)";
    },
    "recommended|ACC:TORQUE[+proximity][+rotors][+learn|+learn0]");

experiments::TrajectoryOptions flightPlan(const FlyOptions& o) {
  experiments::TrajectoryOptions p;
  p.lemniscate = o.trajectory == "lemniscate";
  if (!p.lemniscate) p.kind = o.trajectory;
  p.touchdown_speed_mps = o.touchdown_speed_mps;
  p.flare_height_m = o.flare_height_m;
  p.height_m = o.height_m;
  p.speed_mps = o.speed_mps;
  p.extent_x_m = o.extent_x_m;
  p.extent_y_m = o.extent_y_m;
  p.laps = o.laps;
  p.height_swing_m = o.height_swing_m;
  p.from_height_m = o.from_height_m;
  return p;
}

experiments::FlightScenario scenarioOf(const FlyOptions& o) {
  experiments::FlightScenario s;
  std::optional<sim::World> world;
  if (!o.truth.empty()) world = io::resolveTruth(o.truth, {});
  if (!o.scenario.empty()) {
    // The scenario file fixes vehicle, trajectory, controller, terrain, disturbances and seed;
    // the options that would contradict it are refused at parse time. --truth replaces its
    // world, --controller its configuration (the gains of its controller_params stay), --seed
    // its seed.
    s = experiments::loadScenarioFile(o.scenario, world ? &*world : nullptr,
                                      std::isnan(o.max_sim_s) ? std::nullopt : std::optional<double>(o.max_sim_s));
    if (!o.controller.empty()) (void)parseController(o.controller, s.controller);  // checked by kControllerSpec
    if (o.seed_given) s.seed = o.seed;
  } else {
    s.vehicle = o.vehicle.empty() ? io::builtinVehicle() : io::loadVehicleFile(o.vehicle);
    experiments::applyWorld(
        s, world ? *world : experiments::defaultWorld(s.vehicle, o.vehicle.empty(), o.vehicle));
    (void)parseController(o.controller, s.controller);  // checked by kControllerSpec
    experiments::TrajectoryOptions plan = flightPlan(o);
    // Landing and take-off: the gear holds the rotor plane at the vehicle file's lowest height
    // above the default flat ground at z = 0.
    plan.touchdown_height_m = s.vehicle.min_rotor_plane_height_m;
    s.trajectory = experiments::makeTrajectory(plan);
    s.seed = o.seed;
    if (o.no_turbulence) s.disturbances.turbulence = false;
  }
  if (!o.controller_params.empty()) {
    s.controller = io::withControllerParamsFile(s.controller, o.controller_params);
  }
  if (std::isfinite(o.yaw_rate_gain)) s.controller.k_w_per_s.z() = o.yaw_rate_gain;
  s.start_hover_s = o.start_hover_s;
  if (!std::isnan(o.max_sim_s)) s.max_sim_s = o.max_sim_s;
  for (const auto& a : o.ablate) {
    if (a == "motor_reaction") s.plant.motor_reaction = false;
    if (a == "gyroscopic") s.plant.gyroscopic = false;
  }
  const bool neural = s.controller.acceleration == control::AccelerationCompensation::kNeural;
  if (neural && o.neural_weights.empty()) {
    throw UsageError("controller neural:" + std::string(control::toString(s.controller.torque)) +
                     ": the Neural-Lander baseline needs a trained residual network; pass "
                     "--neural-weights FILE (a weight file written by neural::saveWeights — the "
                     "`geaware bench` campaign trains one from simulated flights and caches it)");
  }
  if (!neural && !o.neural_weights.empty()) {
    throw UsageError("--neural-weights is only used with acceleration compensation neural");
  }
  if (neural) s.residual = experiments::loadResidualNetwork(o.neural_weights);
  experiments::applyTouchdown(s);  // after --controller: a landing flies without the guard
  return s;
}

std::string title(const FlyOptions& o, const experiments::FlightScenario& s) {
  std::string t = o.scenario.empty() ? experiments::describe(flightPlan(o)) : "scenario " + o.scenario;
  return t + ", controller " + experiments::controllerName(s.controller);
}

/// Every output checked before the flight: writable, not a directory or special file, not one
/// of the inputs (also those the scenario file names: io::inputFilesRead), not each other.
void checkFiles(const FlyOptions& o) {
  io::OutputChecks files;
  files.input("--scenario", o.scenario);
  files.input("--vehicle", o.vehicle);
  files.input("--truth", truthInputFile(o.truth));
  files.input("--neural-weights", o.neural_weights);
  files.input("--controller-params", o.controller_params);
  files.output("--out", o.out, false);
  files.output("--json", o.json);
  files.output("--learned-vehicle", o.learned_vehicle, false);  // a file: stdout carries the summary
  files.directory("--report", o.report);
  files.check();
}

/// --learned-vehicle: the flight's vehicle file (or the built-in one) with F_G replaced by the
/// table the controller learned and, once excited enough to be learned, the leveling torque
/// scaled by the scale learned; every other value and comment kept (io::writeVehicleFile).
/// False, with a message and nothing written, when no knot of F_G was learned: the table would
/// be only the learner's start (with +learn0, no ground effect at all), which the file would
/// present as learned.
bool writeLearnedVehicle(const FlyOptions& o, const experiments::FlightScenario& s,
                         const experiments::FlightResult& r, const io::RunInfo& run) {
  if (o.learned_vehicle.empty() || !r.learned_ground_effect) return true;
  const experiments::LearnedGroundEffect& g = *r.learned_ground_effect;
  if (std::none_of(g.learned.begin(), g.learned.end(), [](bool b) { return b; })) {
    std::cerr << fmt::format(
        "geaware: error: --learned-vehicle {}: not written: F_G was learned at none of its {} knots ({} samples "
        "used; the learner takes samples in slow, level flight within its heights, docs/controller.md)\n",
        o.learned_vehicle, g.heights_m.size(), g.samples);
    return false;
  }
  io::VehicleUpdate update;
  update.setTable("ground_effect.additional_thrust", g.heights_m, g.f_g);
  if (g.leveling_learned) {
    const model::HeightTableParams& table = s.vehicle.leveling_torque.table;
    if (table.empty()) {
      update.set("ground_effect.leveling_torque.scale_m4", g.leveling_scale * s.vehicle.leveling_torque.scale_m4);
    } else {
      std::vector<double> values = table.values;
      for (double& v : values) v *= g.leveling_scale;
      update.setTable("ground_effect.leveling_torque", table.heights_m, std::move(values));
    }
  }
  // Which knots were learned: the others hold the learner's extension of them (or its start),
  // which the file must not present as measured.
  std::size_t learned_knots = 0;
  double lowest_m = 0.0, highest_m = 0.0;
  for (std::size_t i = 0; i < g.learned.size(); ++i) {
    if (!g.learned[i]) continue;
    if (learned_knots++ == 0) lowest_m = g.heights_m[i];
    highest_m = g.heights_m[i];
  }
  const std::string coverage =
      learned_knots == g.heights_m.size()
          ? fmt::format("learned at all {} knots", learned_knots)
          : fmt::format("learned at {} of {} knots, {} m; the others hold the learner's extension, not "
                        "measurements",
                        learned_knots, g.heights_m.size(),
                        lowest_m == highest_m ? fmt::format("{:g}", lowest_m)
                                              : fmt::format("{:g}–{:g}", lowest_m, highest_m));
  update.provenance = fmt::format("a flight learning F_G ({}) and the leveling scale (geaware fly, {} samples, seed {})",
                                  coverage, g.samples, run.seeds.empty() ? 0 : run.seeds.front());
  if (o.vehicle.empty()) {
    (void)io::writeVehicleFile(io::builtinVehicleYaml(), "built-in vehicle", o.learned_vehicle, update);
  } else {
    (void)io::writeVehicleFile(o.vehicle, o.learned_vehicle, update);
  }
  std::cerr << fmt::format("geaware: wrote the learned F_G ({}) into {}; the leveling torque {}\n",
                           coverage, o.learned_vehicle,
                           g.leveling_learned
                               ? fmt::format("scaled by {:.4g} (learned from {} samples)", g.leveling_scale,
                                             g.leveling_samples)
                               : fmt::format("as the file's (its scale was not excited enough to learn: {} samples)",
                                             g.leveling_samples));
  return true;
}

/// Refuses, before it starts, a flight whose simulated duration exceeds --max-sim-s.
void checkDuration(const experiments::FlightScenario& s) {
  const double trajectory_s = s.trajectory->duration();
  const double sim_s = s.start_hover_s + trajectory_s + s.settle_s;
  if (sim_s <= s.max_sim_s) return;
  throw std::runtime_error(fmt::format(
      "the flight would simulate {:.6g} s (start hover {:.6g} s + trajectory {:.6g} s + settle {:.6g} s), "
      "more than --max-sim-s {:.6g} s; fly faster or a shorter path, or raise --max-sim-s",
      sim_s, s.start_hover_s, trajectory_s, s.settle_s, s.max_sim_s));
}

int runFly(const FlyOptions& o) {
  const experiments::FlightScenario s = scenarioOf(o);
  if (!o.learned_vehicle.empty() && s.controller.learn_ground_effect == control::GroundEffectLearning::kOff) {
    throw UsageError("--learned-vehicle needs a controller that learns F_G in flight (--controller "
                     "…+learn or …+learn0)");
  }
  checkFiles(o);
  checkDuration(s);
  const io::RunInfo run =
      runInfo({s.seed}, {o.scenario, o.vehicle, truthInputFile(o.truth), o.neural_weights,
                         o.controller_params});
  experiments::ObserverList observers;
  std::unique_ptr<experiments::CsvFlightLog> log;
  if (!o.out.empty()) {
    log = std::make_unique<experiments::CsvFlightLog>(o.out, s.vehicle, io::provenanceComment(run));
    observers.add(log.get());
  }
  std::unique_ptr<experiments::SeriesCollector> series;
  if (!o.report.empty()) {
    series = std::make_unique<experiments::SeriesCollector>(experiments::expectedTicks(s), 1);
    observers.add(series.get());
  }
  TerminalProgress progress("geaware fly", o.quiet);
  experiments::FlightProgressObserver flight_progress(
      progress, s.start_hover_s + s.trajectory->duration() + s.settle_s);
  observers.add(&flight_progress);
  const experiments::FlightResult r = experiments::runFlight(s, &observers);
  progress.end();

  // With --json - the summary goes to stderr, so that stdout is the JSON object alone.
  std::FILE* human = o.json == "-" ? stderr : stdout;
  std::string variations = o.truth.empty() ? "" : ", truth " + o.truth;
  if (o.no_turbulence) variations += ", no turbulence";
  if (!o.controller_params.empty()) variations += ", controller parameters " + o.controller_params;
  if (std::isfinite(o.yaw_rate_gain)) variations += fmt::format(", K^ω_z = {}/s", o.yaw_rate_gain);
  for (const auto& a : o.ablate) variations += ", truth without " + a;
  fmt::print(human, "{}, seed {}{}\n{}", title(o, s), s.seed, variations, experiments::formatFlight(r));
  std::fflush(human);
  if (log) std::cerr << fmt::format("geaware: wrote {} rows to {}\n", log->rows(), o.out);
  if (!o.json.empty()) writeJsonOutput(o.json, experiments::flightJson(s, r), run);
  const bool learned_written = writeLearnedVehicle(o, s, r, run);
  if (series) {
    const auto html =
        experiments::writeFlightReport(o.report, series->series(), r, title(o, s), run, o.png);
    std::cerr << "geaware: wrote " << html.string() << (o.png ? " and flight.png" : "") << "\n";
  }
  return learned_written ? 0 : 1;
}

void addFlightOptions(CLI::App* cmd, FlyOptions& o) {
  cmd->add_option("--trajectory", o.trajectory,
                  "lemniscate, hover-descent, landing (from --from-height down onto the landing gear, "
                  "with ground contact and the land detector) or takeoff (from standing on the gear to "
                  "--height)")
      ->check(CLI::IsMember({"lemniscate", "hover-descent", "landing", "takeoff"}));
  cmd->add_option("--height", o.height_m,
                  "flight height of the lemniscate / final height of the descent, rotor plane "
                  "above the ground [m]")
      ->check(positive());
  cmd->add_option("--speed", o.speed_mps,
                  "lemniscate: peak speed; hover-descent: descent rate (default 0.1); landing: "
                  "cruise descent rate (default 0.5); takeoff: climb rate (default 0.5) [m/s]")
      ->check(positive());
  cmd->add_option("--extent-x", o.extent_x_m, "lemniscate half extent along x [m]")
      ->capture_default_str()
      ->check(positive());
  cmd->add_option("--extent-y", o.extent_y_m, "lemniscate half extent along y [m]")
      ->capture_default_str()
      ->check(positive());
  cmd->add_option("--laps", o.laps, "lemniscate laps")->capture_default_str()->check(wholeIn(1, 1000));
  cmd->add_option("--height-swing", o.height_swing_m,
                  "lemniscate: the height rises by this much from --height to the middle of each lap "
                  "and back, z = H + S·(1 − cos θ)/2 (0: level) [m]")
      ->capture_default_str()
      ->check(nonNegative());
  cmd->add_option("--from-height", o.from_height_m, "hover-descent and landing start height [m]")
      ->capture_default_str()
      ->check(positive());
  cmd->add_option("--touchdown-speed", o.touchdown_speed_mps,
                  "landing: the reference's sinking speed when the gear meets the ground [m/s]")
      ->capture_default_str()
      ->check(positive());
  cmd->add_option("--flare-height", o.flare_height_m,
                  "landing: height above the gear's at which the descent slows to the touchdown speed [m]")
      ->capture_default_str()
      ->check(positive());
  cmd->add_option("--controller", o.controller,
                  "recommended (geaware's: model:model_indi with disturbance feed-forward, "
                  "integral action and a clearance guard; docs/controller.md) or ACC:TORQUE, ACC "
                  "in none|indi|neural|model, TORQUE in none|model|indi|model_indi (the paper's: "
                  "model:model_indi), optionally followed by +proximity (ceiling and wall "
                  "feed-forward, in recommended), +rotors (per-rotor ground effect) and +learn or "
                  "+learn0 (F_G learned in flight); replaces a scenario file's")
      ->check(kControllerSpec);
  cmd->add_option("--seed", o.seed, "seed of sensors and disturbances; replaces a scenario file's")->capture_default_str()->check(seed());
  cmd->add_flag("--no-turbulence", o.no_turbulence, "switch off the near-ground turbulence");
}

void addOutputOptions(CLI::App* cmd, FlyOptions& o) {
  cmd->add_option("--controller-params", o.controller_params,
                  "controller-parameters YAML file (docs/controller-params.md): gains, rate, "
                  "filter cut-off, limits and the settings of the additions --controller switches "
                  "on; replaces a scenario file's controller_params (default: the compiled "
                  "defaults, config/controller-params/default.yaml)");
  cmd->add_option("--yaw-rate-gain", o.yaw_rate_gain,
                  "override K^ω_z, the controller's yaw-rate gain (default: the paper's 16) "
                  "[1/s]; see docs/closed-loop.md on the yaw channel")
      ->check(positive());
  cmd->add_option("--start-hover", o.start_hover_s,
                  "hover at the first point before the trajectory starts [s]")
      ->capture_default_str()
      ->check(nonNegative());
  cmd->add_option("--max-sim-s", o.max_sim_s,
                  "refuse, before it starts, a flight whose simulated duration (start hover, "
                  "trajectory, settling) is longer (default: the scenario file's max_sim_s, else 3600) [s]")
      ->check(positive());
  cmd->add_option("--out", o.out,
                  "CSV log, one row per control tick (readable by `geaware identify flight`)");
  cmd->add_option("--json", o.json, "write the summary as one JSON object ('-': stdout)");
  cmd->add_option("--learned-vehicle", o.learned_vehicle,
                  "with --controller …+learn or …+learn0: write the vehicle file (--vehicle's, or the "
                  "built-in one) with F_G as the table learned in flight and, once learned, the "
                  "leveling torque scaled by the scale learned");
  cmd->add_option("--ablate", o.ablate,
                  "switch off a physical effect of the truth, for diagnosis only: "
                  "motor_reaction (J_R·ṅ), gyroscopic")
      ->check(CLI::IsMember({"motor_reaction", "gyroscopic"}));
  cmd->add_option("--report", o.report, "write an HTML report (flight.html) into DIR");
  cmd->add_flag("--png", o.png, "with --report: also the whole page as DIR/flight.png (Chromium)");
  cmd->add_option("--neural-weights", o.neural_weights,
                  "Neural-Lander weight file, for acceleration compensation neural")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--quiet", o.quiet, "no progress on stderr");
}

}  // namespace

Runner addFlyCommand(CLI::App& app) {
  auto o = std::make_shared<FlyOptions>();
  auto* cmd = app.add_subcommand(
      "fly", "Fly a trajectory in the simulator in closed loop and report the tracking error");
  addVehicleOption(cmd, o->vehicle,
                   "the vehicle the controller believes in (default: the built-in paper quadrotor)");
  addTruthOption(cmd, o->truth,
                 "the world flown in: a truth file (docs/truth-file.md; any vehicle file is one) or a "
                 "built-in world (ideal, as_built); replaces a scenario file's truth (default: as_built "
                 "with the built-in vehicle, the ideal world of --vehicle FILE otherwise)");
  auto* scenario = cmd->add_option("--scenario", o->scenario,
                                   "flight scenario YAML file (docs/scenario-file.md); replaces "
                                   "--vehicle, --trajectory…, --no-turbulence (--controller, --seed "
                                   "and --truth replace its own)")
                       ->check(CLI::ExistingFile);
  addFlightOptions(cmd, *o);
  addOutputOptions(cmd, *o);
  // Either a scenario file or the trajectory options, never both.
  for (const char* name : {"--trajectory", "--height", "--vehicle", "--speed",
                           "--extent-x", "--extent-y", "--laps", "--height-swing", "--from-height",
                           "--touchdown-speed", "--flare-height", "--no-turbulence"}) {
    scenario->excludes(cmd->get_option(name));
  }
  // Combinations CLI11 cannot express: usage errors (exit status 2) at parse time.
  cmd->parse_complete_callback([o, cmd]() {
    o->seed_given = cmd->count("--seed") > 0;
    const bool landing = o->trajectory == "landing";
    if (o->scenario.empty() &&
        (o->trajectory.empty() || (!landing && !std::isfinite(o->height_m)) || o->controller.empty())) {
      throw CLI::ValidationError("geaware fly", "give --scenario FILE, or --trajectory, --height and --controller "
                                                "(a landing: --trajectory landing and --controller)");
    }
    if (landing && std::isfinite(o->height_m)) {
      throw CLI::ValidationError("--height", "--trajectory landing descends onto the landing gear: give "
                                             "--from-height (the start), not --height");
    }
    if (o->trajectory != "lemniscate" && cmd->count("--height-swing") > 0) {
      throw CLI::ValidationError("--height-swing", "--height-swing is for --trajectory lemniscate");
    }
    if (!landing && (cmd->count("--touchdown-speed") > 0 || cmd->count("--flare-height") > 0)) {
      throw CLI::ValidationError("--touchdown-speed", "--touchdown-speed and --flare-height are for --trajectory landing");
    }
    if (o->trajectory == "lemniscate" && !std::isfinite(o->speed_mps)) {
      throw CLI::ValidationError("--speed", "--trajectory lemniscate needs --speed V (peak speed) [m/s]");
    }
    if (o->png && o->report.empty()) throw CLI::ValidationError("--png", "--png needs --report DIR");
    if (!o->learned_vehicle.empty() && !o->scenario.empty()) {
      throw CLI::ValidationError("--learned-vehicle",
                                 "--learned-vehicle is for flights set up by options (--vehicle), not --scenario");
    }
  });
  return [o]() { return runFly(*o); };
}

}  // namespace geaware::cli
