// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The two processes of the DDS loop (docs/bridge.md): runSitl() is `geaware sitl`, the truth
// simulator publishing what PX4 publishes; runBridge() is `geaware bridge`, the estimator and
// controller answering with actuator_motors. In lockstep the simulator publishes a tick's
// sensor samples, waits until the bridge's reader has them (reliable acknowledgements), then
// publishes the tick's time on rt/clock and advances only when the command for that tick came.

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "geaware/bridge/bridge_core.hpp"
#include "geaware/bridge/dds_node.hpp"
#include "geaware/experiments/flight.hpp"

namespace geaware::bridge {

/// Status lines for the user (the command prints them on stderr).
using Notify = std::function<void(const std::string&)>;

struct SitlOptions {
  DdsSettings dds;
  bool lockstep = true;            ///< wait for each tick's command (else: real time)
  double command_timeout_s = 1.0;  ///< no command for this long: the bridge is lost [s]
  double wait_bridge_s = 30.0;     ///< how long to wait for the bridge to appear [s]
  double thr_mdl_fac = 0.0;        ///< the THR_MDL_FAC PX4 would apply [-]
  MotorMap motors;
  double ranger_max_range_m = 4.0;  ///< distance_sensor.max_distance [m]
};

struct SitlReport {
  experiments::FlightResult result;
  bool bridge_lost = false;     ///< stopped because commands stopped coming
  std::uint64_t commands = 0;   ///< actuator_motors messages applied
  std::string message;          ///< why it stopped, when it did not fly to the end
};

/// Flies the scenario's truth; `stop` (SIGINT/SIGTERM) ends it early.
[[nodiscard]] SitlReport runSitl(const experiments::FlightScenario& s, const SitlOptions& o,
                                 const std::atomic<bool>& stop, const Notify& notify);

struct BridgeOptions {
  DdsSettings dds;
  BridgeSettings core;
  bool lockstep = true;          ///< ticks on rt/clock (else: on its own timer at the control rate)
  double input_timeout_s = 0.2;  ///< no input for this long: stop sending commands [s]
  int flights = 0;               ///< exit after this many completed flights (0: run until stopped)
  bool exit_on_stale = false;    ///< exit when the inputs go stale (status 3 mid-flight)
  std::size_t max_latency_samples = 1u << 20;  ///< --stats memory bound
};

struct BridgeReport {
  int flights_completed = 0;
  bool stale_mid_flight = false;  ///< the inputs stopped before the trajectory ended
  std::uint64_t ticks = 0;        ///< commands sent
  std::uint64_t dropped_samples = 0;
  std::uint64_t late_samples = 0;  ///< arrived after their tick had run (lockstep: 0 expected)
  double latency_p50_us = 0.0;    ///< message in → command out, over the ticks [µs]
  double latency_p99_us = 0.0;
  double latency_max_us = 0.0;
  std::string message;
};

[[nodiscard]] BridgeReport runBridge(const experiments::FlightScenario& s, const BridgeOptions& o,
                                     const std::atomic<bool>& stop, const Notify& notify);

}  // namespace geaware::bridge
