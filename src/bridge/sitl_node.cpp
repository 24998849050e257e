// SPDX-License-Identifier: BSD-3-Clause
// `geaware sitl`: the truth simulator as a DDS vehicle (nodes.hpp).
#include <chrono>
#include <memory>
#include <thread>

#include <fmt/format.h>

#include "geaware/bridge/nodes.hpp"
#include "geaware/bridge/px4_codec.hpp"
#include "geaware/bridge/ranger_zones.hpp"
#include "geaware/bridge/sitl_core.hpp"

namespace geaware::bridge {
namespace {

using Clock = std::chrono::steady_clock;

struct SitlTopics {
  explicit SitlTopics(const DdsSettings& d, bool reliable)
      : participant(d),
        imu(makeWriter(participant, px4Topic(d, "out", "sensor_combined"),
                       &px4_msgs_msg_dds__SensorCombined__desc, {reliable, 64})),
        odometry(makeWriter(participant, px4Topic(d, "out", "vehicle_odometry"),
                            &px4_msgs_msg_dds__VehicleOdometry__desc, {reliable, 16})),
        esc(makeWriter(participant, px4Topic(d, "out", "esc_status"),
                       &px4_msgs_msg_dds__EscStatus__desc, {reliable, 16})),
        distance(makeWriter(participant, px4Topic(d, "out", "distance_sensor"),
                            &px4_msgs_msg_dds__DistanceSensor__desc, {reliable, 512})),
        battery(makeWriter(participant, px4Topic(d, "out", "battery_status"),
                           &px4_msgs_msg_dds__BatteryStatus__desc, {reliable, 4})),
        clock(makeWriter(participant, "rt/clock", &rosgraph_msgs_msg_dds__Clock__desc, {reliable, 4})),
        motors(makeReader(participant, px4Topic(d, "in", "actuator_motors"),
                          &px4_msgs_msg_dds__ActuatorMotors__desc, {false, 16})),
        waitset(dds_create_waitset(participant.id())),
        motors_ready(dds_create_readcondition(motors, DDS_ANY_STATE)) {
    dds_waitset_attach(waitset, motors_ready, 0);
  }

  /// Every writer has a reader and the motor commands have a writer.
  [[nodiscard]] bool bridgeMatched() const noexcept {
    for (dds_entity_t w : {imu, odometry, esc, distance, battery, clock}) {
      if (matchedReaders(w) < 1) return false;
    }
    return matchedWriters(motors) >= 1;
  }

  DdsParticipant participant;
  dds_entity_t imu, odometry, esc, distance, battery, clock, motors;
  dds_entity_t waitset, motors_ready;
  TakeBuffer<Px4ActuatorMotors, 16> commands;
};

/// Publishes what fell due at this step.
void publishReadings(SitlTopics& t, const sim::SensorReadings& r, double now_s, double imu_period_s,
                     const SitlOptions& o) {
  if (r.imu) {
    Px4SensorCombined m;
    encodeImu(*r.imu, imu_period_s, m);
    dds_write(t.imu, &m);
  }
  if (r.mocap) {
    Px4Odometry m;
    encodePose(*r.mocap, now_s, m);
    dds_write(t.odometry, &m);
  }
  if (r.rotors) {
    Px4EscStatus m;
    encodeEsc(*r.rotors, o.motors, m);
    dds_write(t.esc, &m);
  }
  if (r.ranger) {
    Px4DistanceSensor m;
    for (int z = 0; z < r.ranger->side * r.ranger->side; ++z) {
      encodeRangerZone(*r.ranger, z, o.ranger_max_range_m, m);
      dds_write(t.distance, &m);
    }
  }
}

/// Waits for the command answering tick_us (lockstep); false after the timeout or a stop.
bool awaitCommand(SitlTopics& t, std::uint64_t tick_us, const SitlOptions& o,
                  const std::atomic<bool>& stop, Px4ActuatorMotors& out) {
  auto& buf = t.commands;
  const auto deadline = Clock::now() + std::chrono::duration<double>(o.command_timeout_s);
  bool got = false;
  while (!got && !stop.load() && Clock::now() < deadline) {
    const int n = buf.take(t.motors);
    for (int i = 0; i < n; ++i) {
      if (buf[i].timestamp_sample == tick_us) {
        out = buf[i];
        got = true;
      }
    }
    if (!got) dds_waitset_wait(t.waitset, nullptr, 0, DDS_MSECS(20));
  }
  return got;
}

}  // namespace

SitlReport runSitl(const experiments::FlightScenario& s, const SitlOptions& o,
                   const std::atomic<bool>& stop, const Notify& notify) {
  SitlCore core(s);
  auto topics = std::make_unique<SitlTopics>(o.dds, o.lockstep);  // ≈ 2 kB of buffers
  SitlTopics& t = *topics;
  SitlReport report;
  const double imu_period_s = 1.0 / s.sensors.imu.rate_Hz;
  if (o.lockstep) {
    notify(fmt::format("waiting up to {} s for a bridge on domain {}", o.wait_bridge_s, o.dds.domain_id));
    const auto deadline = Clock::now() + std::chrono::duration<double>(o.wait_bridge_s);
    while (!t.bridgeMatched()) {
      if (stop.load() || Clock::now() > deadline) {
        report.bridge_lost = true;
        report.message = fmt::format("no bridge appeared on domain {} within {} s", o.dds.domain_id, o.wait_bridge_s);
        report.result = core.finish(0.0);
        return report;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    notify("bridge found; flying in lockstep");
  }
  bool warned_writers = false;
  const auto wall0 = Clock::now();
  Px4ActuatorMotors cmd;
  auto& latest = t.commands;
  auto last_command = wall0;
  bool commanded = false;
  for (;;) {
    const double now_s = core.time_s();
    if (!o.lockstep) std::this_thread::sleep_until(wall0 + std::chrono::duration<double>(now_s));
    publishReadings(t, core.sense(), now_s, imu_period_s, o);
    if (core.controlTickDue()) {
      if (!warned_writers && matchedWriters(t.motors) > 1) {
        // Two controllers on one vehicle: their commands would interleave.
        notify(fmt::format("{} writers of actuator_motors on domain {}: more than one bridge commands this vehicle",
                           matchedWriters(t.motors), o.dds.domain_id));
        warned_writers = true;
      }
      Px4BatteryStatus b;
      encodeBattery(now_s, core.batteryVoltage_V(), b);
      dds_write(t.battery, &b);
      if (o.lockstep) {
        dds_wait_for_acks(t.participant.publisher(), DDS_SECS(1));
        RosClock c;
        encodeClock(now_s, c);
        dds_write(t.clock, &c);
        if (!awaitCommand(t, toMicroseconds(now_s), o, stop, cmd)) {
          report.bridge_lost = !stop.load();
          report.message = stop.load() ? "stopped by a signal"
                                       : fmt::format("no motor command for t = {:.3f} s within {} s: the bridge is lost",
                                                     now_s, o.command_timeout_s);
          break;
        }
        core.setThrottle(decodeMotors(cmd, o.thr_mdl_fac, o.motors));
        ++report.commands;
      } else {
        const int n = latest.take(t.motors);
        if (n > 0) {
          core.setThrottle(decodeMotors(latest[n - 1], o.thr_mdl_fac, o.motors));
          report.commands += static_cast<std::uint64_t>(n);
          last_command = Clock::now();
          commanded = true;
        } else {
          core.setThrottle(core.throttle());
          if (commanded && Clock::now() - last_command > std::chrono::duration<double>(o.command_timeout_s)) {
            report.bridge_lost = true;
            report.message = fmt::format("no motor command for {} s at t = {:.3f} s: the bridge is lost",
                                         o.command_timeout_s, now_s);
            break;
          }
        }
      }
    }
    if (stop.load()) {
      report.message = "stopped by a signal";
      break;
    }
    if (core.lastStep() || !core.step()) break;
  }
  report.result = core.finish(std::chrono::duration<double>(Clock::now() - wall0).count());
  return report;
}

}  // namespace geaware::bridge
