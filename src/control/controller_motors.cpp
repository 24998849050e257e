// SPDX-License-Identifier: BSD-3-Clause
// The controller's motor side after the control law (docs/controller.md §4, docs/reliability.md
// §7): the per-rotor speed loop and the motor-failure monitor with its flight termination.
#include "geaware/control/controller.hpp"

#include <algorithm>
#include <cstdint>

namespace geaware::control {

Eigen::Vector4d Controller::rotorSpeedCorrection(const ControllerInput& in) noexcept {
  if (!(params_.rotor_speed_ki_per_s > 0.0)) return Eigen::Vector4d::Zero();
  // Last tick's command against the speed it produced, per motor, normalised by the top speed;
  // nothing before the first command. The integral is bounded (anti-windup by clamping).
  const double n_max = throttle_curve_.maxSpeedRpm();
  const double lim = params_.rotor_speed_limit_throttle;
  if (!(mem_.last_n_des_rpm_.minCoeff() > 0.0)) return mem_.rotor_speed_integral_;  // no command yet
  // Conditional integration: after a tick whose command was cut (allocation, thrust) or not
  // computed (bad input), the model restarts from the measured speeds and nothing is integrated,
  // so a command the rotors could not follow is never taken for a gain error.
  constexpr std::uint32_t kCut = kFlagThrustSaturated | kFlagRollPitchSaturated | kFlagYawSaturated |
                                 kFlagNonFiniteInput | kFlagReferenceInvalid;
  if ((mem_.last_flags_ & kCut) != 0) {
    mem_.rotor_speed_model_rpm_ = in.rotor_speeds_rpm;
    mem_.have_rotor_speed_model_ = true;
    return mem_.rotor_speed_integral_;
  }
  // The speed each rotor should have now: last tick's command through the motors' lag.
  if (!mem_.have_rotor_speed_model_) {
    mem_.rotor_speed_model_rpm_ = mem_.last_n_des_rpm_;
    mem_.have_rotor_speed_model_ = true;
  } else {
    mem_.rotor_speed_model_rpm_ += dt_s_ / (params_.rotor_speed_lag_s + dt_s_) *
                                   (mem_.last_n_des_rpm_ - mem_.rotor_speed_model_rpm_);
  }
  for (int i = 0; i < 4; ++i) {
    // A rotor at less than half its model is a failed motor or a telemetry dropout: the motor
    // monitor's business, not a gain to correct.
    if (in.rotor_speeds_rpm[i] < 0.5 * mem_.rotor_speed_model_rpm_[i]) continue;
    const double e = (mem_.rotor_speed_model_rpm_[i] - in.rotor_speeds_rpm[i]) / n_max;
    mem_.rotor_speed_integral_[i] =
        std::clamp(mem_.rotor_speed_integral_[i] + params_.rotor_speed_ki_per_s * e * dt_s_, -lim, lim);
  }
  return mem_.rotor_speed_integral_;
}

void Controller::monitorMotors(const ControllerInput& in, ControllerOutput& out) noexcept {
  // A rotor below half of last tick's command while that command was well above idle, for
  // longer than the motors' lag can explain (0.15 s ≈ 5 time constants of a 30 ms motor).
  const double n_min = throttle_curve_.minSpeedRpm();
  const double floor = n_min + 0.2 * (throttle_curve_.maxSpeedRpm() - n_min);
  for (int i = 0; i < 4; ++i) {
    const double cmd = mem_.last_n_des_rpm_[i];
    double& short_s = mem_.motor_short_s_[static_cast<std::size_t>(i)];
    short_s = (cmd > floor && in.rotor_speeds_rpm[i] < 0.5 * cmd) ? short_s + dt_s_ : 0.0;
    if (short_s >= 0.15) mem_.motor_failed_ = true;
  }
  mem_.last_n_des_rpm_ = out.n_des_rpm;
  if (mem_.motor_failed_) {
    out.flags |= kFlagMotorFailure;
    const Eigen::Vector3d z_B = in.estimate.q_WB.normalized().toRotationMatrix().col(2);
    if (z_B.z() < 0.5) mem_.terminated_ = true;  // tilt beyond 60°
  }
  if (mem_.terminated_) {
    out.flags |= kFlagTerminated;
    out.throttle.fill(0.0);
    out.n_des_rpm.setZero();
  }
  mem_.last_flags_ |= out.flags & (kFlagMotorFailure | kFlagTerminated);
}

}  // namespace geaware::control
