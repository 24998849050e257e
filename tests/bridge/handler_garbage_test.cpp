// SPDX-License-Identifier: BSD-3-Clause
// The bridge's message handlers fed garbage (issue 16 item 3, the bridge's part), without DDS:
// BridgeCore's on*() handlers, tick() and command() called directly with 10⁵ seeded events —
// messages of random bytes (malformed), valid messages of a real flight with fields replaced by
// NaN, ±∞, huge, negative or zero values, replays of old messages (out of order, duplicated),
// time stamps far in the past or future, and ticks whose time goes back, stands still or jumps.
// After every tick the throttles must be finite and in [0, 1] and actuator_motors must carry a
// finite normalised thrust in [0, 1] for the four motors (NaN, "stopped", only for the unused
// ones); nothing may allocate. The handlers are noexcept: an exception inside one would call
// std::terminate, so the test finishing is the proof that none is thrown. Afterwards the same
// bridge, reset, must fly a valid flight again.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <vector>

#include "geaware/bridge/bridge_core.hpp"
#include "geaware/bridge/px4_codec.hpp"
#include "geaware/bridge/ranger_zones.hpp"
#include "geaware/bridge/sitl_core.hpp"
#include "geaware/experiments/scenario_file.hpp"
#include "geaware_test/allocation_counter.hpp"

namespace geaware::bridge {
namespace {

experiments::FlightScenario scenario(const char* file) {
  const char* root = std::getenv("GEAWARE_SOURCE_DIR");
  const std::filesystem::path dir = root != nullptr ? root : ".";
  return experiments::loadScenarioFile(dir / "config/scenarios" / file);
}

/// The messages of the first seconds of a real flight (the simulator flying the bridge's own
/// commands), in the order they were sent, with the control ticks' times.
struct Recording {
  std::vector<Px4SensorCombined> imu;
  std::vector<Px4Odometry> odometry;
  std::vector<Px4EscStatus> esc;
  std::vector<Px4DistanceSensor> distance;
  std::vector<Px4BatteryStatus> battery;
  std::vector<std::uint64_t> ticks_us;
};

/// Flies `s` for max_s through the messages (as bridge_alloc_test does); the messages are kept
/// when `rec` is given. Returns the flight and counts the active ticks.
experiments::FlightResult fly(const experiments::FlightScenario& s, BridgeCore& bridge, double max_s,
                              const BridgeSettings& settings, Recording* rec, long* active) {
  SitlCore sim(s);
  Px4SensorCombined imu{};
  Px4Odometry odo{};
  Px4EscStatus esc{};
  Px4DistanceSensor zone{};
  Px4BatteryStatus battery{};
  Px4ActuatorMotors motors{};
  const double imu_period = 1.0 / s.sensors.imu.rate_Hz;
  for (;;) {
    const double t = sim.time_s();
    const sim::SensorReadings& r = sim.sense();
    if (r.imu) {
      encodeImu(*r.imu, imu_period, imu);
      bridge.onImu(imu);
      if (rec != nullptr) rec->imu.push_back(imu);
    }
    if (r.mocap) {
      encodePose(*r.mocap, t, odo);
      bridge.onOdometry(odo);
      if (rec != nullptr) rec->odometry.push_back(odo);
    }
    if (r.rotors) {
      encodeEsc(*r.rotors, settings.motors, esc);
      bridge.onEsc(esc);
      if (rec != nullptr) rec->esc.push_back(esc);
    }
    if (r.ranger) {
      for (int z = 0; z < r.ranger->side * r.ranger->side; ++z) {
        encodeRangerZone(*r.ranger, z, 4.0, zone);
        bridge.onDistance(zone);
        if (rec != nullptr) rec->distance.push_back(zone);
      }
    }
    if (sim.controlTickDue()) {
      encodeBattery(t, sim.batteryVoltage_V(), battery);
      bridge.onBattery(battery);
      const TickOutput& o = bridge.tick(toMicroseconds(t));
      bridge.command(toMicroseconds(t), motors);
      if (active != nullptr && o.active) ++*active;
      if (rec != nullptr) {
        rec->battery.push_back(battery);
        rec->ticks_us.push_back(toMicroseconds(t));
      }
      sim.setThrottle(decodeMotors(motors, settings.thr_mdl_fac, settings.motors));
    }
    if (sim.lastStep() || t >= max_s || !sim.step()) break;
  }
  return sim.finish(0.0);
}

constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();
constexpr float kInff = std::numeric_limits<float>::infinity();

/// One float of garbage: NaN, ±∞, ±FLT_MAX, a denormal, 0, −1 or a value over 16 decades.
float garbageFloat(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 8);
  std::uniform_real_distribution<float> u(-1.0F, 1.0F);
  switch (kind(rng)) {
    case 0: return kNaNf;
    case 1: return kInff;
    case 2: return -kInff;
    case 3: return u(rng) < 0 ? -std::numeric_limits<float>::max() : std::numeric_limits<float>::max();
    case 4: return std::numeric_limits<float>::denorm_min();
    case 5: return 0.0F;
    case 6: return -1.0F;
    default: return u(rng) * std::pow(10.0F, 8.0F * u(rng));
  }
}

/// A time stamp of garbage: 0, the largest, far in the future or the past of `now_us`, or near it.
std::uint64_t garbageTime(std::mt19937_64& rng, std::uint64_t now_us) {
  std::uniform_int_distribution<int> kind(0, 5);
  std::uniform_int_distribution<std::uint64_t> any;
  std::uniform_int_distribution<std::uint64_t> near(0, 2'000'000);
  switch (kind(rng)) {
    case 0: return 0;
    case 1: return std::numeric_limits<std::uint64_t>::max();
    case 2: return any(rng);
    case 3: return now_us > 10'000'000 ? now_us - 10'000'000 : 0;  // stale by 10 s
    case 4: return now_us + near(rng);                             // future
    default: return now_us > near(rng) ? now_us - near(rng) : 0;   // recent past
  }
}

/// Every byte random: a malformed message. The C struct's bool fields get 0 or 1 (another byte
/// in a bool is not a value the decoder could ever be handed by the DDS library).
template <class T>
void randomBytes(std::mt19937_64& rng, T& m) {
  std::array<unsigned char, sizeof(T)> bytes{};
  std::uniform_int_distribution<int> byte(0, 255);
  for (auto& b : bytes) b = static_cast<unsigned char>(byte(rng));
  std::memcpy(&m, bytes.data(), sizeof(T));
}

template <std::size_t N>
void garble(std::mt19937_64& rng, float (&a)[N]) {
  std::bernoulli_distribution hit(0.5);
  for (float& v : a) {
    if (hit(rng)) v = garbageFloat(rng);
  }
}

/// Checks one tick's output and its actuator_motors; counts violations.
struct Checker {
  long bad_throttle = 0;
  long bad_command = 0;
  long ticks = 0;
  long active = 0;  ///< ticks on which the controller ran (not the hover fallback)
  void check(const TickOutput& o, const Px4ActuatorMotors& m, const MotorMap& map) {
    ++ticks;
    active += o.active ? 1 : 0;
    for (double u : o.throttle) {
      if (!(std::isfinite(u) && u >= 0.0 && u <= 1.0)) ++bad_throttle;
    }
    for (int k = 0; k < 12; ++k) {
      bool used = false;
      for (int i : map.px4_index) used = used || i == k;
      const float c = m.control[k];
      if (used ? !(std::isfinite(c) && c >= 0.0F && c <= 1.0F) : !std::isnan(c)) ++bad_command;
    }
  }
};

/// The garbage run: `events` seeded events on a bridge that has just flown `rec`.
void feedGarbage(BridgeCore& bridge, const Recording& rec, const BridgeSettings& settings,
                 std::uint64_t seed, int events, Checker& checker, long& allocations) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> what(0, 11);
  std::bernoulli_distribution coin(0.5);
  auto pick = [&rng](const auto& v) -> const auto& {
    return v[std::uniform_int_distribution<std::size_t>(0, v.size() - 1)(rng)];
  };
  Px4SensorCombined imu{};
  Px4Odometry odo{};
  Px4EscStatus esc{};
  Px4DistanceSensor zone{};
  Px4BatteryStatus battery{};
  Px4ActuatorMotors motors{};
  std::uint64_t now_us = rec.ticks_us.back();
  for (int e = 0; e < events; ++e) {
    // Prepare the message outside the count (the "DDS library's" side), deliver it inside.
    const int w = what(rng);
    switch (w) {
      case 0: randomBytes(rng, imu); break;
      case 1: randomBytes(rng, odo); break;
      case 2: randomBytes(rng, esc); break;
      case 3: randomBytes(rng, zone); break;
      case 4:
        randomBytes(rng, battery);
        battery.connected = coin(rng);
        battery.is_powering_off = coin(rng);
        battery.is_required = coin(rng);
        break;
      case 5:  // a recorded IMU sample, laced
        imu = pick(rec.imu);
        garble(rng, imu.gyro_rad);
        garble(rng, imu.accelerometer_m_s2);
        if (coin(rng)) imu.timestamp = garbageTime(rng, now_us);
        break;
      case 6:  // a recorded pose, laced (position, attitude, frame, time)
        odo = pick(rec.odometry);
        garble(rng, odo.position);
        if (coin(rng)) garble(rng, odo.q);
        if (coin(rng)) odo.pose_frame = static_cast<std::uint8_t>(rng());
        if (coin(rng)) odo.timestamp = garbageTime(rng, now_us);
        if (coin(rng)) odo.timestamp_sample = garbageTime(rng, now_us);
        break;
      case 7:  // recorded rotor speeds, laced
        esc = pick(rec.esc);
        for (auto& r : esc.esc) {
          if (coin(rng)) r.esc_rpm = static_cast<std::int32_t>(rng());
        }
        if (coin(rng)) esc.esc_count = static_cast<std::uint8_t>(rng());
        if (coin(rng)) esc.timestamp = garbageTime(rng, now_us);
        break;
      case 8:  // a recorded ranger zone, laced (range, field of view, ray, id, time)
        zone = pick(rec.distance);
        if (coin(rng)) zone.current_distance = garbageFloat(rng);
        if (coin(rng)) zone.h_fov = zone.v_fov = garbageFloat(rng);
        if (coin(rng)) garble(rng, zone.q);
        if (coin(rng)) zone.device_id = static_cast<std::uint32_t>(rng());
        if (coin(rng)) zone.signal_quality = static_cast<std::int8_t>(rng());
        if (coin(rng)) zone.timestamp = garbageTime(rng, now_us);
        break;
      case 9:  // a recorded battery voltage, laced
        battery = pick(rec.battery);
        battery.voltage_v = garbageFloat(rng);
        break;
      default: break;  // 10, 11: a replayed message or a tick
    }
    const long before = geaware_test::allocationCount();
    switch (w) {
      case 0: case 5: bridge.onImu(imu); break;
      case 1: case 6: bridge.onOdometry(odo); break;
      case 2: case 7: bridge.onEsc(esc); break;
      case 3: case 8: bridge.onDistance(zone); break;
      case 4: case 9: bridge.onBattery(battery); break;
      case 10:  // out of order and duplicated: an old valid message, delivered twice
        for (int k = 0; k < 2; ++k) {
          bridge.onImu(pick(rec.imu));
          bridge.onOdometry(pick(rec.odometry));
          bridge.onEsc(pick(rec.esc));
          bridge.onDistance(pick(rec.distance));
        }
        break;
      default: break;
    }
    allocations += geaware_test::allocationCount() - before;
    if (w >= 9 || e % 4 == 0) {
      // A tick: usually one control period on, sometimes back in time, repeated, or far ahead.
      const int how = std::uniform_int_distribution<int>(0, 9)(rng);
      now_us = how < 6 ? now_us + 5000 : garbageTime(rng, now_us);
      const long b = geaware_test::allocationCount();
      const TickOutput& o = bridge.tick(now_us);
      bridge.command(now_us, motors);
      allocations += geaware_test::allocationCount() - b;
      checker.check(o, motors, settings.motors);
    }
  }
}

void runGarbage(const char* scenario_file, const BridgeSettings& settings, std::uint64_t seed) {
  const experiments::FlightScenario s = scenario(scenario_file);
  BridgeCore bridge(s, settings);
  Recording rec;
  long active = 0;
  // 3 s of a real flight first: the estimator and controller are running when the garbage starts.
  const experiments::FlightResult before = fly(s, bridge, 3.0, settings, &rec, &active);
  ASSERT_FALSE(before.crash.has_value());
  ASSERT_GT(active, 400);
  Checker checker;
  long allocations = 0;
  feedGarbage(bridge, rec, settings, seed, 100'000, checker, allocations);
  EXPECT_EQ(checker.bad_throttle, 0) << "non-finite or out-of-range throttles";
  EXPECT_EQ(checker.bad_command, 0) << "non-finite or out-of-range actuator_motors controls";
  EXPECT_EQ(allocations, 0);
  // The garbage reached the controller, not only the hover fallback.
  EXPECT_GT(checker.ticks, 25'000);
  EXPECT_GT(checker.active, checker.ticks / 2) << checker.active << " of " << checker.ticks;
  // The same bridge, reset (as the node does for a new flight), flies a valid flight again.
  bridge.reset();
  long active_after = 0;
  const experiments::FlightResult after = fly(s, bridge, 3.0, settings, nullptr, &active_after);
  EXPECT_FALSE(after.crash.has_value()) << after.crash_description;
  EXPECT_GT(active_after, 400);
}

TEST(BridgeHandlerGarbage, PaperExperimentFiveNeverCommandsGarbage) {
  runGarbage("lemniscate_low.yaml", BridgeSettings{}, 1);
}

TEST(BridgeHandlerGarbage, RecommendedAsBuiltWithThrustModelAndMotorMapNeverCommandsGarbage) {
  BridgeSettings settings;
  settings.thr_mdl_fac = 0.35;
  settings.motors.px4_index = {2, 0, 3, 1};
  runGarbage("lemniscate_low_recommended.yaml", settings, 2);
}

}  // namespace
}  // namespace geaware::bridge
