// SPDX-License-Identifier: BSD-3-Clause
// `geaware sitl` and `geaware bridge` (docs/bridge.md): parse, load the scenario, run the node of
// the bridge layer, print its report. Built with -DGEAWARE_BRIDGE=ON.

#include "commands.hpp"
#include "numbers.hpp"

#include <fmt/format.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "geaware/bridge/nodes.hpp"
#include "geaware/bridge/px4_codec.hpp"
#include "geaware/experiments/flight_summary.hpp"
#include "geaware/experiments/scenario_file.hpp"
#include "geaware/io/controller_params_file.hpp"
#include "geaware/io/output_file.hpp"

namespace geaware::cli {
namespace {

std::atomic<bool> g_stop{false};
extern "C" void onSignal(int /*signal*/) { g_stop.store(true); }

void installSignalHandlers() {
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
}

struct NetOptions {
  std::uint32_t domain = 0;
  std::string interface_address = "127.0.0.1";
  std::vector<std::string> peers{"127.0.0.1"};
  bool multicast = false;
  std::string px4_namespace;
  bool real_time = false;
  double thr_mdl_fac = 0.0;
  std::vector<int> motor_map;  ///< empty: the vehicle file's rotor_layout
};

void addNetOptions(CLI::App* cmd, NetOptions& o) {
  cmd->add_option("--domain", o.domain, "DDS domain ID (ROS_DOMAIN_ID)")->capture_default_str()->check(CLI::Range(0, 232));
  cmd->add_option("--interface", o.interface_address,
                  "network interface for DDS, by address or name (a vehicle: its companion link)")
      ->capture_default_str();
  cmd->add_option("--peer", o.peers, "unicast discovery peer address (repeatable)")->capture_default_str();
  cmd->add_flag("--multicast", o.multicast, "allow multicast discovery (off: unicast to --peer only)");
  cmd->add_option("--px4-namespace", o.px4_namespace,
                  "PX4's uXRCE-DDS namespace (topics rt/NS/fmu/...; default none: rt/fmu/...)");
  cmd->add_flag("--real-time", o.real_time,
                "real time instead of lockstep on rt/clock (a real vehicle; sitl paces itself by the wall clock)");
  cmd->add_option("--thr-mdl-fac", o.thr_mdl_fac,
                  "PX4's THR_MDL_FAC on the vehicle: actuator_motors carries f*u^2 + (1-f)*u for throttle u")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--motor-map", o.motor_map,
                  "PX4 motor number (1..12) of geaware's rotors 1..4 (front right, rear left, front left, "
                  "rear right) (default: the vehicle file's rotor_layout.rotorN.px4_motor; without it "
                  "1 2 3 4, PX4's quadrotor x)")
      ->expected(4)
      ->check(CLI::Range(1, 12));
}

bridge::DdsSettings ddsOf(const NetOptions& o) {
  bridge::DdsSettings d;
  d.domain_id = o.domain;
  d.interface_address = o.interface_address;
  d.peers = o.peers;
  d.multicast = o.multicast;
  d.px4_namespace = o.px4_namespace;
  return d;
}

bridge::MotorMap motorMapOf(const NetOptions& o, const model::VehicleParams& vehicle) {
  if (o.motor_map.empty()) return bridge::motorMapOf(vehicle.rotor_layout);
  bridge::MotorMap m;
  for (std::size_t i = 0; i < 4; ++i) m.px4_index[i] = o.motor_map[i] - 1;
  if (!m.valid()) throw UsageError("--motor-map: each PX4 motor number at most once");
  return m;
}

void printNotice(const std::string& who, const std::string& line) {
  std::fprintf(stderr, "geaware %s: %s\n", who.c_str(), line.c_str());
  std::fflush(stderr);
}

// ---- sitl ---------------------------------------------------------------------------------

struct SitlCliOptions {
  NetOptions net;
  std::string scenario, json;
  double command_timeout_s = 1.0;
  double wait_bridge_s = 30.0;
};

int runSitlCommand(const SitlCliOptions& o) {
  const experiments::FlightScenario s = experiments::loadScenarioFile(o.scenario);
  io::OutputChecks files;
  files.input("--scenario", o.scenario);
  files.output("--json", o.json);
  files.check();
  const io::RunInfo run = runInfo({s.seed}, {o.scenario});
  bridge::SitlOptions so;
  so.dds = ddsOf(o.net);
  so.lockstep = !o.net.real_time;
  so.command_timeout_s = o.command_timeout_s;
  so.wait_bridge_s = o.wait_bridge_s;
  so.thr_mdl_fac = o.net.thr_mdl_fac;
  so.motors = motorMapOf(o.net, s.vehicle);
  installSignalHandlers();
  const bridge::SitlReport r =
      bridge::runSitl(s, so, g_stop, [](const std::string& l) { printNotice("sitl", l); });
  std::FILE* human = o.json == "-" ? stderr : stdout;
  fmt::print(human, "scenario {} through the DDS bridge ({}), seed {}, {} motor commands\n{}",
             o.scenario, so.lockstep ? "lockstep" : "real time", s.seed, r.commands,
             experiments::formatFlight(r.result));
  std::fflush(human);
  if (!r.message.empty()) printNotice("sitl", r.message);
  if (!o.json.empty()) writeJsonOutput(o.json, experiments::flightJson(s, r.result), run);
  return r.bridge_lost ? 3 : 0;
}

// ---- bridge -------------------------------------------------------------------------------

struct BridgeCliOptions {
  NetOptions net;
  std::string scenario, controller, controller_params;  // controller empty: the scenario's
  double input_timeout_s = 0.2;
  double max_height_age_s = 0.05;
  int flights = 0;
  bool exit_on_stale = false;
  bool stats = false;
};

int runBridgeCommand(const BridgeCliOptions& o) {
  experiments::FlightScenario s = experiments::loadScenarioFile(o.scenario);
  // The scenario's configuration and its controller_params file's values, unless --controller
  // names another configuration (whose additions then take that configuration's settings).
  if (!o.controller.empty() && !control::parseConfiguration(o.controller, s.controller)) {
    throw UsageError("--controller '" + o.controller + "': expected recommended or ACC:TORQUE");
  }
  if (!o.controller_params.empty()) s.controller = io::withControllerParamsFile(s.controller, o.controller_params);
  if (s.controller.acceleration == control::AccelerationCompensation::kNeural) {
    throw UsageError("--controller neural:…: the bridge does not load a residual network");
  }
  bridge::BridgeOptions bo;
  bo.dds = ddsOf(o.net);
  bo.lockstep = !o.net.real_time;
  bo.core.motors = motorMapOf(o.net, s.vehicle);
  bo.core.thr_mdl_fac = o.net.thr_mdl_fac;
  bo.core.max_height_age_s = o.max_height_age_s;
  bo.input_timeout_s = o.input_timeout_s;
  bo.flights = o.flights;
  bo.exit_on_stale = o.exit_on_stale;
  installSignalHandlers();
  const bridge::BridgeReport r =
      bridge::runBridge(s, bo, g_stop, [](const std::string& l) { printNotice("bridge", l); });
  fmt::print("bridge: {} motor commands, {} flights completed{}, {} samples dropped, {} late\n", r.ticks,
             r.flights_completed, r.stale_mid_flight ? ", inputs lost mid-flight" : "", r.dropped_samples,
             r.late_samples);
  if (o.stats) {
    fmt::print("loop latency (message in -> command out) over {} ticks: p50 {:.1f} us, p99 {:.1f} us, max {:.1f} us\n",
               r.ticks, r.latency_p50_us, r.latency_p99_us, r.latency_max_us);
  }
  std::fflush(stdout);
  return r.stale_mid_flight && o.exit_on_stale ? 3 : 0;
}

const char* kBridgeFooter =
    "Topics (PX4 uXRCE-DDS names as ROS 2 sees them, types px4_msgs::msg::dds_::<Name>_, XCDR1):\n"
    "  in:  rt/fmu/out/sensor_combined, vehicle_odometry, esc_status, distance_sensor, battery_status;\n"
    "       rt/clock (rosgraph_msgs Clock) in lockstep\n"
    "  out: rt/fmu/in/offboard_control_mode (direct_actuator), rt/fmu/in/actuator_motors\n"
    "Rates: one command per clock tick in lockstep (the simulator's control rate), else the\n"
    "controller's rate_hz (200 Hz by default). Timeouts: --input-timeout (default 0.2 s) without\n"
    "any input stops the commands; before the estimator has a pose and rotor telemetry the bridge\n"
    "sends the nominal hover throttle. SIGINT/SIGTERM stop it cleanly. docs/bridge.md, docs/vehicle.md.";

}  // namespace

Runner addSitlCommand(CLI::App& app) {
  auto o = std::make_shared<SitlCliOptions>();
  auto* cmd = app.add_subcommand("sitl", "Fly a scenario's truth simulator as a DDS vehicle for `geaware bridge`");
  cmd->add_option("--scenario", o->scenario, "flight scenario YAML file (docs/scenario-file.md)")
      ->required()
      ->check(CLI::ExistingFile);
  addNetOptions(cmd, o->net);
  cmd->add_option("--command-timeout", o->command_timeout_s,
                  "no motor command for this long: the bridge is lost, stop (exit status 3) [s]")
      ->capture_default_str()
      ->check(positive());
  cmd->add_option("--wait-bridge", o->wait_bridge_s, "lockstep: wait this long for a bridge [s]")
      ->capture_default_str()
      ->check(positive());
  cmd->add_option("--json", o->json, "write the flight summary as one JSON object ('-': stdout)");
  cmd->footer(
      "Publishes rt/fmu/out/{sensor_combined,vehicle_odometry,esc_status,distance_sensor,battery_status}\n"
      "and rt/clock, subscribes rt/fmu/in/actuator_motors. Lockstep: each control tick's samples are\n"
      "acknowledged by the bridge before the tick's clock is published, and the plant advances only\n"
      "when the command for that tick arrived.");
  return [o]() { return runSitlCommand(*o); };
}

Runner addBridgeCommand(CLI::App& app) {
  auto o = std::make_shared<BridgeCliOptions>();
  auto* cmd = app.add_subcommand("bridge", "Run the estimator and controller against a PX4 vehicle (or geaware sitl) over DDS");
  cmd->add_option("--scenario", o->scenario,
                  "flight scenario YAML file: the vehicle, the trajectory, ESKF and sensor settings "
                  "(its truth is not read)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--controller", o->controller,
                  "recommended or ACC:TORQUE, as for fly (default: the scenario's controller, with its "
                  "controller_params file)");
  cmd->add_option("--controller-params", o->controller_params, "controller-parameters YAML file")
      ->check(CLI::ExistingFile);
  addNetOptions(cmd, o->net);
  cmd->add_option("--input-timeout", o->input_timeout_s,
                  "no input (clock or sensor) for this long: stop sending commands and report it [s]")
      ->capture_default_str()
      ->check(positive());
  cmd->add_option("--max-height-age", o->max_height_age_s, "older ranger heights are not used [s]")
      ->capture_default_str()
      ->check(positive());
  cmd->add_option("--flights", o->flights, "exit after this many flights ran to their end (0: until stopped)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000000));
  cmd->add_flag("--exit-on-stale", o->exit_on_stale,
                "exit when the inputs go stale (status 3 if mid-flight) instead of waiting for the vehicle");
  cmd->add_flag("--stats", o->stats, "print the loop latency p50/p99 (message in -> command out)");
  cmd->footer(kBridgeFooter);
  return [o]() { return runBridgeCommand(*o); };
}

}  // namespace geaware::cli
