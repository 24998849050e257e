// SPDX-License-Identifier: BSD-3-Clause
// The bridge's estimator and controller on PX4 messages: the controller side of the flight
// runner (src/experiments/flight.cpp, sense() and controlTick()) fed from messages.
#include "geaware/bridge/bridge_core.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace geaware::bridge {
namespace {

estimation::DisturbanceObserverParams observerParamsOf(const control::ControllerParams& c) {
  estimation::DisturbanceObserverParams p;
  p.rate_hz = c.rate_hz;
  p.filter_cutoff_hz = c.filter_cutoff_hz;
  return p;
}

}  // namespace

template <class T, int N>
bool BridgeCore::Queue<T, N>::push(const T& v) noexcept {
  if (size == N) return false;
  items[static_cast<std::size_t>((head + size) % N)] = v;
  ++size;
  return true;
}

template <class T, int N>
void BridgeCore::Queue<T, N>::pop() noexcept {
  head = (head + 1) % N;
  --size;
}

BridgeCore::BridgeCore(const experiments::FlightScenario& s, const BridgeSettings& settings)
    : s_(s),
      settings_(settings),
      vehicle_(s.vehicle),
      eskf_(std::make_unique<estimation::Eskf>(s.eskf)),
      lattice_(s.lattice.value_or(estimation::LatticeHeightParams::forVehicle(s.vehicle))),
      ranger_(s.sensors.ranger.mount_B),
      duration_s_(s.trajectory->duration()),
      frames_(std::make_unique<Queue<RangerEvent, 4>>()) {
  observer_.emplace(vehicle_, observerParamsOf(s.controller));
  controller_.emplace(vehicle_, s.controller, s.residual);
}

void BridgeCore::reset() {
  eskf_ = std::make_unique<estimation::Eskf>(s_.eskf);
  observer_.emplace(vehicle_, observerParamsOf(s_.controller));
  controller_.emplace(vehicle_, s_.controller, s_.residual);
  ranger_ = RangerAssembler(s_.sensors.ranger.mount_B);
  imu_.clear();
  poses_.clear();
  escs_.clear();
  frames_->clear();
  started_ = false;
  last_imu_us_ = 0;
  have_telemetry_ = false;
  have_height_ = false;
  height_t_s_ = -1.0;
  battery_V_ = std::numeric_limits<double>::quiet_NaN();
  out_ = TickOutput{};
}

void BridgeCore::onImu(const Px4SensorCombined& m) noexcept {
  last_imu_us_ = std::max(last_imu_us_, m.timestamp);
  noteArrival(m.timestamp);
  if (!imu_.push(decodeImu(m))) ++dropped_;
}

void BridgeCore::onOdometry(const Px4Odometry& m) noexcept {
  const DecodedPose d = decodePose(m);
  if (!d.valid) {
    ++dropped_;
    return;
  }
  noteArrival(m.timestamp);
  if (!poses_.push({m.timestamp, d.pose})) ++dropped_;
}

void BridgeCore::onEsc(const Px4EscStatus& m) noexcept {
  noteArrival(m.timestamp);
  if (!escs_.push(decodeEsc(m, settings_.motors))) ++dropped_;
}

void BridgeCore::onDistance(const Px4DistanceSensor& m) noexcept {
  noteArrival(m.timestamp);
  if (!ranger_.add(m)) return;
  if (frames_->size == 4) {
    ++dropped_;
    return;
  }
  // Assemble in place: no 2 kB temporary on the stack for every frame.
  RangerEvent& e = frames_->items[static_cast<std::size_t>((frames_->head + frames_->size) % 4)];
  e.t_us = toMicroseconds(ranger_.frame().t_s);
  e.frame = ranger_.frame();
  ++frames_->size;
}

void BridgeCore::onBattery(const Px4BatteryStatus& m) noexcept {
  const double v = static_cast<double>(m.voltage_v);
  battery_V_ = m.connected && std::isfinite(v) && v > 0.0 ? v : std::numeric_limits<double>::quiet_NaN();
}

void BridgeCore::applyImu(const model::ImuSample& s) noexcept { (void)eskf_->addImu(s); }

void BridgeCore::applyRanger(const model::RangerFrame& f) noexcept {
  if (!eskf_->initialised()) return;
  const estimation::LatticeHeight lh = lattice_.estimate(f, eskf_->state().q_WB);
  if (!lh.valid) return;
  height_m_ = lh.height_m;
  height_t_s_ = f.t_s;
  have_height_ = true;
}

/// The queued samples stamped up to t in time order; at equal stamps IMU, pose, telemetry,
/// ranger (the order of the runner's sense()).
void BridgeCore::applyUpTo(std::uint64_t t_us) noexcept {
  constexpr std::uint64_t kNone = std::numeric_limits<std::uint64_t>::max();
  for (;;) {
    const std::uint64_t ti = imu_.size > 0 ? toMicroseconds(imu_.front().t_s) : kNone;
    const std::uint64_t tp = poses_.size > 0 ? poses_.front().delivered_us : kNone;
    const std::uint64_t te = escs_.size > 0 ? toMicroseconds(escs_.front().t_s) : kNone;
    const std::uint64_t tr = frames_->size > 0 ? frames_->front().t_us : kNone;
    const std::uint64_t t = std::min(std::min(ti, tp), std::min(te, tr));
    if (t == kNone || t > t_us) return;
    if (ti == t) {
      applyImu(imu_.front());
      imu_.pop();
    } else if (tp == t) {
      (void)eskf_->addMocap(poses_.front().pose);
      poses_.pop();
    } else if (te == t) {
      telemetry_rpm_ = escs_.front().n_rpm;
      have_telemetry_ = telemetry_rpm_.allFinite();
      escs_.pop();
    } else {
      applyRanger(frames_->front().frame);
      frames_->pop();
    }
  }
}

double BridgeCore::hoverThrottle() const noexcept {
  const double h = have_height_ ? height_m_ : s_.trajectory->sample(0.0).p_W.z();
  const double n = vehicle_.hoverSpeedRpm(std::max(h, 0.0));
  return vehicle_.throttleCurve().throttle(n, battery_V_);
}

void BridgeCore::runController(double t_s) noexcept {
  const double t_traj = t_s - toSeconds(t0_us_) - s_.start_hover_s;
  out_.t_traj_s = t_traj;
  in_.t_s = t_s;
  in_.reference = s_.trajectory->sample(t_traj);
  in_.battery_voltage_V = battery_V_;
  out_.active = eskf_->initialised() && have_telemetry_;
  if (!out_.active) {
    out_.throttle.fill(hoverThrottle());
    out_.controller_flags = 0;
    return;
  }
  const estimation::EskfOutput eo = eskf_->output();
  in_.estimate = eo.estimate;
  in_.gyro_B = eo.gyro_B;
  in_.accel_B = eo.accel_B;
  in_.height_valid = have_height_ && t_s - height_t_s_ <= settings_.max_height_age_s + 1e-6;
  in_.height_m = height_m_;
  in_.rotor_speeds_rpm = telemetry_rpm_;
  const estimation::DisturbanceEstimate d =
      observer_->update({in_.t_s, in_.gyro_B, in_.accel_B, in_.rotor_speeds_rpm, in_.estimate.q_WB});
  in_.external_accel_W = d.a_ext_W;
  in_.external_accel_valid = d.valid;
  const control::ControllerOutput o = controller_->update(in_);
  out_.throttle = o.throttle;
  out_.controller_flags = o.flags;
}

const TickOutput& BridgeCore::tick(std::uint64_t t_us) noexcept {
  if (!started_) {
    started_ = true;
    t0_us_ = t_us;
  }
  tick_us_ = t_us;
  applyUpTo(t_us);
  runController(toSeconds(t_us));
  return out_;
}

void BridgeCore::command(std::uint64_t now_us, Px4ActuatorMotors& m) const noexcept {
  encodeMotors(toSeconds(now_us), toSeconds(tick_us_), out_.throttle, settings_.thr_mdl_fac,
               settings_.motors, m);
}

}  // namespace geaware::bridge
