// SPDX-License-Identifier: BSD-3-Clause
// `geaware bridge`: estimator and controller behind PX4's uXRCE-DDS topics (nodes.hpp).
#include <algorithm>
#include <chrono>
#include <memory>
#include <vector>

#include <fmt/format.h>

#include "geaware/bridge/nodes.hpp"
#include "geaware/bridge/px4_codec.hpp"

namespace geaware::bridge {
namespace {

using Clock = std::chrono::steady_clock;

/// The bridge's DDS side: readers of what PX4 publishes, writers of the commands, and buffers
/// the samples are taken into (preallocated).
struct BridgeTopics {
  BridgeTopics(const DdsSettings& d, bool reliable)
      : participant(d),
        imu(makeReader(participant, px4Topic(d, "out", "sensor_combined"),
                       &px4_msgs_msg_dds__SensorCombined__desc, {reliable, 64})),
        odometry(makeReader(participant, px4Topic(d, "out", "vehicle_odometry"),
                            &px4_msgs_msg_dds__VehicleOdometry__desc, {reliable, 16})),
        esc(makeReader(participant, px4Topic(d, "out", "esc_status"),
                       &px4_msgs_msg_dds__EscStatus__desc, {reliable, 16})),
        distance(makeReader(participant, px4Topic(d, "out", "distance_sensor"),
                            &px4_msgs_msg_dds__DistanceSensor__desc, {reliable, 512})),
        battery(makeReader(participant, px4Topic(d, "out", "battery_status"),
                           &px4_msgs_msg_dds__BatteryStatus__desc, {reliable, 4})),
        clock(makeReader(participant, "rt/clock", &rosgraph_msgs_msg_dds__Clock__desc, {reliable, 4})),
        offboard(makeWriter(participant, px4Topic(d, "in", "offboard_control_mode"),
                            &px4_msgs_msg_dds__OffboardControlMode__desc, {true, 1})),
        motors(makeWriter(participant, px4Topic(d, "in", "actuator_motors"),
                          &px4_msgs_msg_dds__ActuatorMotors__desc, {true, 1})),
        waitset(dds_create_waitset(participant.id())) {
    const dds_entity_t trigger = dds_create_readcondition(reliable ? clock : imu, DDS_ANY_STATE);
    dds_waitset_attach(waitset, trigger, 0);
  }

  /// Everything PX4 published since the last call, into the core; notes when each required
  /// input (IMU, odometry, rotor telemetry) last came. Returns whether anything came.
  bool drainSensors(BridgeCore& core, Clock::time_point now) noexcept {
    int got = 0;
    int n = imus.take(imu);
    for (int i = 0; i < n; ++i) core.onImu(imus[i]);
    if (n > 0) last_arrival[0] = now;
    got += n;
    n = poses.take(odometry);
    for (int i = 0; i < n; ++i) core.onOdometry(poses[i]);
    if (n > 0) last_arrival[1] = now;
    got += n;
    n = escs.take(esc);
    for (int i = 0; i < n; ++i) core.onEsc(escs[i]);
    if (n > 0) last_arrival[2] = now;
    got += n;
    while ((n = zones.take(distance)) > 0) {
      for (int i = 0; i < n; ++i) core.onDistance(zones[i]);
      got += n;
    }
    n = batteries.take(battery);
    for (int i = 0; i < n; ++i) core.onBattery(batteries[i]);
    got += n;
    return got > 0;
  }

  /// The name of the first required input older than `timeout`, or null.
  [[nodiscard]] const char* staleInput(Clock::time_point now, Clock::duration timeout) const noexcept {
    static constexpr const char* kNames[3] = {"sensor_combined", "vehicle_odometry", "esc_status"};
    for (int i = 0; i < 3; ++i) {
      if (now - last_arrival[i] > timeout) return kNames[i];
    }
    return nullptr;
  }
  Clock::time_point last_arrival[3]{};

  DdsParticipant participant;
  dds_entity_t imu, odometry, esc, distance, battery, clock, offboard, motors, waitset;
  TakeBuffer<Px4SensorCombined, 64> imus;
  TakeBuffer<Px4Odometry, 16> poses;
  TakeBuffer<Px4EscStatus, 16> escs;
  TakeBuffer<Px4DistanceSensor, 256> zones;
  TakeBuffer<Px4BatteryStatus, 4> batteries;
  TakeBuffer<RosClock, 4> clocks;
};

std::uint64_t microsecondsSince(Clock::time_point t0) noexcept {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - t0).count());
}

double percentile(std::vector<double>& v, double p) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(std::clamp(p * static_cast<double>(v.size() - 1), 0.0,
                                                     static_cast<double>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

/// One flight's bookkeeping in the loop.
struct LoopState {
  bool flying = false;          ///< commands are being sent
  std::uint64_t last_tick_us = 0;
  double last_t_traj_s = 0.0;
  Clock::time_point last_input;
};

}  // namespace

BridgeReport runBridge(const experiments::FlightScenario& s, const BridgeOptions& o,
                       const std::atomic<bool>& stop, const Notify& notify) {
  if (!o.core.motors.valid()) throw std::invalid_argument("motor map: each PX4 index 0..11 at most once");
  BridgeCore core(s, o.core);
  auto topics = std::make_unique<BridgeTopics>(o.dds, o.lockstep);  // ≈ 60 kB of buffers
  BridgeTopics& t = *topics;
  BridgeReport report;
  std::vector<double> latency_us;
  latency_us.reserve(o.max_latency_samples);
  const auto timeout = std::chrono::duration<double>(o.input_timeout_s);
  LoopState st;
  st.last_input = Clock::now();
  const std::uint64_t period_us = toMicroseconds(1.0 / s.controller.rate_hz);
  std::uint64_t next_tick_us = 0;
  Px4ActuatorMotors motors;
  Px4OffboardControlMode mode;
  notify(fmt::format("bridge on domain {}: waiting for {}", o.dds.domain_id,
                     o.lockstep ? "the simulator's clock (rt/clock)" : "sensor_combined"));
  while (!stop.load()) {
    dds_waitset_wait(t.waitset, nullptr, 0, DDS_MSECS(10));
    const auto t_in = Clock::now();
    // Clocks first: the simulator had its sensor samples acknowledged before it wrote a clock,
    // so they are in the readers by now.
    const int n_clock = o.lockstep ? t.clocks.take(t.clock) : 0;
    const bool got = t.drainSensors(core, t_in) || n_clock > 0;
    if (got) st.last_input = t_in;
    int ticks = 0;
    std::uint64_t tick_us[4];
    if (o.lockstep) {
      for (int i = 0; i < n_clock; ++i) tick_us[ticks++] = decodeClockUs(t.clocks[i]);
    } else if (got && core.lastImuUs() + period_us / 4 >= next_tick_us) {
      // Real time: tick on the vehicle's newest IMU time once a control period of it has passed
      // (every IMU sample when the IMU runs at the control rate).
      tick_us[ticks++] = core.lastImuUs();
      next_tick_us = core.lastImuUs() + period_us;
    }
    // A required input gone stale: no command from stale data (checked before the ticks).
    const char* stale = st.flying ? t.staleInput(t_in, std::chrono::duration_cast<Clock::duration>(timeout)) : nullptr;
    if (stale != nullptr) ticks = 0;
    for (int i = 0; i < ticks; ++i) {
      if (st.flying && tick_us[i] < st.last_tick_us) {
        notify(fmt::format("the vehicle's time went back ({:.3f} s → {:.3f} s): a new flight",
                           toSeconds(st.last_tick_us), toSeconds(tick_us[i])));
        core.reset();
      }
      if (!st.flying) {
        notify(fmt::format("inputs arrived (t = {:.3f} s): sending motor commands", toSeconds(tick_us[i])));
        for (auto& a : t.last_arrival) a = std::max(a, t_in);  // each input gets its timeout from now
      }
      st.flying = true;
      st.last_tick_us = tick_us[i];
      st.last_t_traj_s = core.tick(tick_us[i]).t_traj_s;
      core.command(tick_us[i], motors);
      encodeOffboardMode(toSeconds(tick_us[i]), mode);
      dds_write(t.offboard, &mode);
      dds_write(t.motors, &motors);
      ++report.ticks;
      if (latency_us.size() < latency_us.capacity()) {
        latency_us.push_back(static_cast<double>(microsecondsSince(t_in)));
      }
    }
    if (st.flying && (stale != nullptr || Clock::now() - st.last_input > timeout)) {
      st.flying = false;
      // The last tick falls within one control period of the end (the simulator stops at the
      // first plant step past it).
      const bool completed = st.last_t_traj_s >= core.trajectoryDuration_s() - 1.5 / s.controller.rate_hz;
      report.flights_completed += completed ? 1 : 0;
      report.stale_mid_flight = !completed;
      report.message = fmt::format(
          "no {} for {} s after t = {:.3f} s, trajectory time {:.3f} of {:.3f} s ({}): motor "
          "commands stopped",
          stale != nullptr ? stale : "input", o.input_timeout_s, toSeconds(st.last_tick_us), st.last_t_traj_s, core.trajectoryDuration_s(),
          completed ? "the trajectory had ended" : "mid-flight, the trajectory had not ended");
      notify(report.message);
      core.reset();
      next_tick_us = 0;
      if (o.exit_on_stale || (o.flights > 0 && report.flights_completed >= o.flights)) break;
    }
  }
  if (stop.load() && report.message.empty()) report.message = "stopped by a signal";
  report.dropped_samples = core.droppedSamples();
  report.late_samples = core.lateSamples();
  report.latency_p50_us = percentile(latency_us, 0.5);
  report.latency_p99_us = percentile(latency_us, 0.99);
  report.latency_max_us = latency_us.empty() ? 0.0 : *std::max_element(latency_us.begin(), latency_us.end());
  return report;
}

}  // namespace geaware::bridge
