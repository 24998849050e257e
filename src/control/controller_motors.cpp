// SPDX-License-Identifier: BSD-3-Clause
// The controller's motor side after the control law (docs/controller.md §4, docs/reliability.md
// §7): the yaw torque's rotor-inertia lag, the shared throttle PI correction, the per-rotor speed
// loop and the motor-failure monitor with its flight termination.
#include "geaware/control/controller.hpp"
#include "geaware/model/units.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace geaware::control {

double Controller::allocatedYawTorque(const ControllerInput& in, double tau_z) noexcept {
  // The rotors' yaw response to a steady-torque command is (1 + s·τ_R)/(1 + s·τ_motor): the
  // J_R·ṅ lead. Lagging the command by 1/(1 + s·τ_R) (backward Euler) leaves the motor lag only.
  if (!(params_.compensate_rotor_inertia && J_R_kgm2_ > 0.0)) return tau_z;
  const double n_mean = std::max(in.rotor_speeds_rpm.mean(), throttle_curve_.minSpeedRpm());
  const double tau_r = J_R_kgm2_ * model::kRpmToRadPerSec / (2.0 * k_I_Nm_per_rpm2_ * n_mean);
  if (!mem_.have_yaw_lag_) {
    mem_.yaw_torque_lagged_Nm_ = tau_z;
    mem_.have_yaw_lag_ = true;
  }
  mem_.yaw_torque_lagged_Nm_ += dt_s_ / (tau_r + dt_s_) * (tau_z - mem_.yaw_torque_lagged_Nm_);
  // Never beyond the largest yaw torque the rotors make (two at n_max, two at n_min; the
  // allocation cuts any command beyond it): a 1e298 N·m command from a garbage reference kept the
  // lag, and with it the yaw command, saturated for minutes.
  const double n_max = throttle_curve_.maxSpeedRpm(), n_min = throttle_curve_.minSpeedRpm();
  const double tau_z_max = 2.0 * k_I_Nm_per_rpm2_ * (n_max * n_max - n_min * n_min);
  mem_.yaw_torque_lagged_Nm_ = std::clamp(mem_.yaw_torque_lagged_Nm_, -tau_z_max, tau_z_max);
  return mem_.yaw_torque_lagged_Nm_;
}

double Controller::thrustCorrection(const Eigen::Vector4d& n_sq_des,
                                    const Eigen::Vector4d& n_sq_meas) noexcept {
  // T_a^E = (Σk_T·n_des² − Σk_T·n²)/m (docs/paper-facts.md).
  const double thrust_acc_error = k_T_N_per_rpm2_ * (n_sq_des.sum() - n_sq_meas.sum()) / mass_kg_;
  const double i_limit = params_.thrust_pi_ki > 0.0 ? params_.thrust_pi_limit / params_.thrust_pi_ki : 0.0;
  mem_.thrust_pi_integral_ = std::clamp(mem_.thrust_pi_integral_ + thrust_acc_error * dt_s_, -i_limit, i_limit);
  return std::clamp(params_.thrust_pi_kp * thrust_acc_error +
                        params_.thrust_pi_ki * mem_.thrust_pi_integral_,
                    -params_.thrust_pi_limit, params_.thrust_pi_limit);
}

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
