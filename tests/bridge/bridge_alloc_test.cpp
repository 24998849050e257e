// SPDX-License-Identifier: BSD-3-Clause
// The bridge's part of the loop without DDS: the simulator's samples encoded as PX4 messages,
// decoded by BridgeCore, its command decoded as PX4 would, flown on the truth. It must fly the
// lemniscate like the in-process runner (same seed, same truth) and allocate nothing from a
// message in to the command out (operator new counted around those calls).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "geaware/bridge/bridge_core.hpp"
#include "geaware/bridge/px4_codec.hpp"
#include "geaware/bridge/ranger_zones.hpp"
#include "geaware/bridge/sitl_core.hpp"
#include "geaware/experiments/scenario_file.hpp"
#include "geaware_test/allocation_counter.hpp"

namespace geaware::bridge {
namespace {

experiments::FlightScenario lemniscateLow() {
  const char* root = std::getenv("GEAWARE_SOURCE_DIR");
  const std::filesystem::path dir = root != nullptr ? root : ".";
  return experiments::loadScenarioFile(dir / "config/scenarios/lemniscate_low.yaml");
}

struct MessageLoopResult {
  experiments::FlightResult flight;
  long allocations = 0;  ///< inside the bridge's part
  long active_ticks = 0;
};

/// Flies `s` through the messages; stops after max_s of simulated time.
MessageLoopResult flyThroughMessages(const experiments::FlightScenario& s, double max_s,
                                     const BridgeSettings& settings) {
  SitlCore sim(s);
  BridgeCore bridge(s, settings);
  MessageLoopResult out;
  Px4SensorCombined imu;
  Px4Odometry odo;
  Px4EscStatus esc;
  Px4DistanceSensor zone;
  Px4BatteryStatus battery;
  Px4ActuatorMotors motors;
  const double imu_period = 1.0 / s.sensors.imu.rate_Hz;
  for (;;) {
    const double t = sim.time_s();
    const sim::SensorReadings& r = sim.sense();
    // The simulator's side encodes (outside the count), the bridge's side decodes (counted).
    if (r.imu) encodeImu(*r.imu, imu_period, imu);
    if (r.mocap) encodePose(*r.mocap, t, odo);
    if (r.rotors) encodeEsc(*r.rotors, settings.motors, esc);
    long before = geaware_test::allocationCount();
    if (r.imu) bridge.onImu(imu);
    if (r.mocap) bridge.onOdometry(odo);
    if (r.rotors) bridge.onEsc(esc);
    out.allocations += geaware_test::allocationCount() - before;
    if (r.ranger) {
      for (int z = 0; z < r.ranger->side * r.ranger->side; ++z) {
        encodeRangerZone(*r.ranger, z, 4.0, zone);
        before = geaware_test::allocationCount();
        bridge.onDistance(zone);
        out.allocations += geaware_test::allocationCount() - before;
      }
    }
    if (sim.controlTickDue()) {
      encodeBattery(t, sim.batteryVoltage_V(), battery);
      before = geaware_test::allocationCount();
      bridge.onBattery(battery);
      const TickOutput& o = bridge.tick(toMicroseconds(t));
      bridge.command(toMicroseconds(t), motors);
      out.allocations += geaware_test::allocationCount() - before;
      out.active_ticks += o.active ? 1 : 0;
      sim.setThrottle(decodeMotors(motors, settings.thr_mdl_fac, settings.motors));
    }
    if (sim.lastStep() || t >= max_s || !sim.step()) break;
  }
  out.flight = sim.finish(0.0);
  return out;
}

TEST(BridgeLoop, FliesTheLowLemniscateLikeTheInProcessRunner) {
  const experiments::FlightScenario s = lemniscateLow();
  const experiments::FlightResult ref = experiments::runFlight(s);
  ASSERT_TRUE(ref.completed);
  BridgeSettings settings;
  settings.thr_mdl_fac = 0.35;  // any PX4 thrust model: the bridge and "PX4" invert each other
  const MessageLoopResult m = flyThroughMessages(s, 1e9, settings);
  EXPECT_TRUE(m.flight.completed) << m.flight.crash_description;
  EXPECT_FALSE(m.flight.crash.has_value());
  EXPECT_LE(m.flight.tracking.rmse_all_m, 1.5 * ref.tracking.rmse_all_m)
      << "in process " << ref.tracking.rmse_all_m;
  // Same stages in the same order: the flights differ only by float32 messages and integer rpm.
  EXPECT_NEAR(m.flight.tracking.rmse_all_m, ref.tracking.rmse_all_m, 0.1 * ref.tracking.rmse_all_m);
  EXPECT_GT(m.active_ticks, static_cast<long>(0.95 * static_cast<double>(m.flight.control_ticks)));
}

TEST(BridgeLoop, MessageInToCommandOutAllocatesNothing) {
  const experiments::FlightScenario s = lemniscateLow();
  const MessageLoopResult m = flyThroughMessages(s, 3.0, BridgeSettings{});
  EXPECT_GT(m.active_ticks, 500);
  EXPECT_EQ(m.allocations, 0);
}

}  // namespace
}  // namespace geaware::bridge
