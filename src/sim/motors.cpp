// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/sim/motors.hpp"

#include <algorithm>
#include <cmath>

#include "geaware/model/motor.hpp"
#include "geaware/model/units.hpp"

namespace geaware::sim {

ThrottleDelay::ThrottleDelay(double dead_time_s, double step_s)
    : dead_time_s_(dead_time_s),
      ring_(static_cast<std::size_t>(std::ceil(dead_time_s / step_s - 1e-9)) + 2) {}

const std::array<double, 4>& ThrottleDelay::apply(double t_s,
                                                  const std::array<double, 4>& command) noexcept {
  if (count_ == ring_.size()) {  // full: the oldest pending command is lost
    head_ = slot(1);
    --count_;
    ++overflowed_;
  }
  ring_[slot(count_)] = Entry{t_s, command};
  ++count_;
  // The command in force at t − dead is the latest one issued at or before then: drop every
  // older one (a tolerance absorbs the round-off of accumulated simulation time).
  const double due_s = t_s - dead_time_s_ + 1e-9;
  while (count_ >= 2 && ring_[slot(1)].t_s <= due_s) {
    head_ = slot(1);
    --count_;
  }
  return ring_[head_].command;
}

Motors::Motors(const TruthParams& params, const std::array<double, 4>& initial_rpm)
    : motor_(params.motor),
      battery_(params.battery),
      voltage_V_(params.battery.nominal_voltage_V),
      charge_used_Ah_(params.battery.initial_charge_used_Ah),
      inv_time_constant_(1.0 / params.motor.time_constant_s),
      inv_capacity_(1.0 / params.battery.capacity_Ah),
      inv_nominal_voltage_(1.0 / params.battery.nominal_voltage_V) {
  const RotorGeometry g = params.rotorGeometry();
  for (std::size_t i = 0; i < 4; ++i) {
    k_I_[i] = g.k_I_Nm_per_rpm2[i];
    yaw_sign_[i] = params.yaw_sign[i];
    n_rpm_[i] = std::clamp(std::isfinite(initial_rpm[i]) ? initial_rpm[i] : 0.0,
                           motor_.min_speed_rpm, motor_.max_speed_rpm);
    n_ss_rpm_[i] = n_rpm_[i];
  }
  if (battery_.enabled) {
    // Settle the terminal voltage for the initial speeds (a fixed point; a few passes suffice
    // because R_int·I ≪ V).
    voltage_V_ = openCircuitVoltage();
    for (int k = 0; k < 4; ++k) {
      current_A_ = currentAt(n_rpm_, voltage_V_);
      voltage_V_ = openCircuitVoltage() - battery_.internal_resistance_ohm * current_A_;
    }
  }
}

double Motors::openCircuitVoltage() const noexcept {
  // Linear discharge curve; past the rated capacity the pack is held at its empty voltage (a
  // runner should end the flight long before: the model is not meant for deep discharge).
  const double used = std::clamp(charge_used_Ah_ * inv_capacity_, 0.0, 1.0);
  return battery_.full_voltage_V - (battery_.full_voltage_V - battery_.empty_voltage_V) * used;
}

double Motors::currentAt(const std::array<double, 4>& n_rpm, double voltage_V) const noexcept {
  // Mechanical power of each rotor, aerodynamic torque × speed: P = k_I·n²·Ω.
  double power_W = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    const double n = std::abs(n_rpm[i]);
    power_W += k_I_[i] * n * n * n * model::kRpmToRadPerSec;
  }
  return battery_.idle_current_A + power_W / (battery_.efficiency * std::max(voltage_V, 1e-3));
}

double Motors::steadySpeedRpm(double throttle, double voltage_V) const noexcept {
  const double t = std::clamp(throttle, 0.0, 1.0);
  const auto& c = motor_.throttle;
  double n = std::sqrt(std::max((c.c2_rpm2 * t + c.c1_rpm2) * t + c.c0_rpm2, 0.0));
  if (battery_.enabled) n *= voltage_V / battery_.nominal_voltage_V;
  return std::clamp(n, motor_.min_speed_rpm, motor_.max_speed_rpm);
}

double Motors::throttleForSteadySpeed(double n_rpm) const noexcept {
  double scale = 1.0;
  if (battery_.enabled) {
    const std::array<double, 4> n{n_rpm, n_rpm, n_rpm, n_rpm};
    double v = openCircuitVoltage();
    for (int k = 0; k < 8; ++k)
      v = openCircuitVoltage() - battery_.internal_resistance_ohm * currentAt(n, v);
    scale = v / battery_.nominal_voltage_V;
  }
  return model::ThrottleCurve(motor_.throttle).throttle(n_rpm / scale);
}

void Motors::beginStep(const std::array<double, 4>& throttle, double dt_s) noexcept {
  if (battery_.enabled) {
    // Explicit in the current: the speeds (hence the load) at the start of the step and the
    // voltage of the previous step. The electrical dynamics are much faster than 1 ms.
    current_A_ = currentAt(n_rpm_, voltage_V_);
    voltage_V_ = openCircuitVoltage() - battery_.internal_resistance_ohm * current_A_;
  }
  // steadySpeedRpm() for the four rotors, with the voltage scale computed once.
  const auto& c = motor_.throttle;
  const double scale = battery_.enabled ? voltage_V_ * inv_nominal_voltage_ : 1.0;
  for (std::size_t i = 0; i < 4; ++i) {
    const double t = std::clamp(throttle[i], 0.0, 1.0);
    const double n = std::sqrt(std::max((c.c2_rpm2 * t + c.c1_rpm2) * t + c.c0_rpm2, 0.0));
    n_ss_rpm_[i] = std::clamp(n * scale, motor_.min_speed_rpm, motor_.max_speed_rpm) * speed_scale_[i];
  }
  if (dt_s != dt_s_) {
    // The decays at RK4's stage times, computed once per step length (a fixed-step run pays
    // for the exponentials once).
    dt_s_ = dt_s;
    decay_half_ = std::exp(-0.5 * dt_s / motor_.time_constant_s);
    decay_full_ = std::exp(-dt_s / motor_.time_constant_s);
  }
}

void Motors::endStep() noexcept {
  std::array<double, 4> n_dot{};
  std::array<double, 4> n_end{};
  speedsAt(dt_s_, n_end, n_dot);
  n_rpm_ = n_end;
  if (battery_.enabled) charge_used_Ah_ += current_A_ * dt_s_ / 3600.0;
}

}  // namespace geaware::sim
