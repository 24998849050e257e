// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The four motors, their ESCs and the battery. Rotor speed follows a
// first-order lag toward the ESC's steady speed for the throttle,
//   ṅ = (n_ss − n)/τ,   n_ss = √(c2·t² + c1·t + c0)·V/V_nom  clamped to the speed limits,
// discretised exactly over a step with the target held: n(s) = n_ss + (n0 − n_ss)·e^(−s/τ).
// The plant evaluates n(s) and ṅ(s) at the RK4 stage times, so the rigid body sees the same
// exact speed trajectory as the motor state.
//
// Torques on the body from the motors (the aerodynamic k_I·n² torque is the aerodynamics'):
//   reaction of the rotor's angular acceleration   τ = Σ yaw_i·J_R·ṅ_i·z_B   (FACTS: M_i = k_I·n² +
//   J_R·ṅ) gyroscopic torque of the spinning rotors        τ = −ω × Σ J_R·Ω_i·d_i·z_B
// with Ω_i the speed in rad/s and d_i = −yaw_i the spin direction (a rotor spinning about +z
// pushes the body about −z). ṅ in rpm/s is converted to rad/s² (model::kRpmToRadPerSec).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "geaware/model/units.hpp"
#include "geaware/sim/truth_params.hpp"
#include "geaware/sim/wrench.hpp"

namespace geaware::sim {

/// Motor torques on the body, body frame [N·m] (force zero): the reaction to the rotors'
/// angular acceleration and the gyroscopic torque of their spin, each switchable. Inline: the
/// plant calls it at every RK4 stage.
[[nodiscard]] inline Wrench motorTorques(double J_R_kgm2, const std::array<double, 4>& yaw_sign,
                                         const std::array<double, 4>& n_rpm,
                                         const std::array<double, 4>& n_dot_rpm_per_s,
                                         const Eigen::Vector3d& w_B, bool reaction,
                                         bool gyroscopic) noexcept {
  Wrench w;
  if (reaction) {
    double tz = 0.0;
    for (std::size_t i = 0; i < 4; ++i) tz += yaw_sign[i] * n_dot_rpm_per_s[i];
    w.torque_B.z() = J_R_kgm2 * model::kRpmToRadPerSec * tz;
  }
  if (gyroscopic) {
    // Total rotor angular momentum along z_B, h = Σ J_R·Ω_i·d_i with d_i = −yaw_i; the torque
    // on the body is −ω × h·z_B = h·(−ω_y, ω_x, 0).
    double h = 0.0;
    for (std::size_t i = 0; i < 4; ++i) h -= yaw_sign[i] * n_rpm[i];
    h *= J_R_kgm2 * model::kRpmToRadPerSec;
    w.torque_B.x() += -h * w_B.y();
    w.torque_B.y() += h * w_B.x();
  }
  return w;
}

/// The ESC/link dead time: the throttle a motor acts on at time t is the latest command issued
/// at or before t − dead time (before any command that old: the first command received). With
/// a fixed step dt and a dead time of k·dt a command reaches the motors exactly k steps later.
/// The ring is sized at construction for commands every `step_s` (ceil(dead/step) + 2 entries);
/// a caller stepping faster than that loses the oldest pending commands first (counted). No
/// allocation in apply().
class ThrottleDelay {
 public:
  /// dead_time_s > 0 and step_s > 0, both finite (validated by the plant).
  ThrottleDelay(double dead_time_s, double step_s);

  /// Record `command` issued at t_s (non-decreasing times) and return the command that reaches
  /// the motors at t_s.
  [[nodiscard]] const std::array<double, 4>& apply(double t_s,
                                                   const std::array<double, 4>& command) noexcept;

  [[nodiscard]] double deadTime_s() const noexcept { return dead_time_s_; }
  [[nodiscard]] long overflowed() const noexcept { return overflowed_; }

 private:
  struct Entry {
    double t_s = 0.0;
    std::array<double, 4> command{};
  };
  [[nodiscard]] std::size_t slot(std::size_t k) const noexcept { return (head_ + k) % ring_.size(); }

  double dead_time_s_;
  std::vector<Entry> ring_;  // pending commands, oldest at head_
  std::size_t head_ = 0;
  std::size_t count_ = 0;
  long overflowed_ = 0;
};

class Motors {
 public:
  /// Requires validated parameters. Rotors start at `initial_rpm` (clamped to the limits).
  explicit Motors(const TruthParams& params, const std::array<double, 4>& initial_rpm = {});

  /// Fix the ESC targets for the next step of length dt from the throttles (each clamped to
  /// [0, 1]; non-finite throttles must be rejected by the caller). Updates the battery's
  /// terminal voltage from the current drawn at the start of the step. No allocation.
  void beginStep(const std::array<double, 4>& throttle, double dt_s) noexcept;

  /// Rotor speeds and their rates at time s ∈ [0, dt] into the step begun last [rpm, rpm/s].
  /// Inline: the plant calls it at every RK4 stage.
  void speedsAt(double s, std::array<double, 4>& n_rpm,
                std::array<double, 4>& n_dot_rpm_per_s) const noexcept {
    const double decay = s == 0.0           ? 1.0
                         : s == 0.5 * dt_s_ ? decay_half_
                         : s == dt_s_       ? decay_full_
                                            : std::exp(-s * inv_time_constant_);
    for (std::size_t i = 0; i < 4; ++i) {
      n_rpm[i] = n_ss_rpm_[i] + (n_rpm_[i] - n_ss_rpm_[i]) * decay;
      n_dot_rpm_per_s[i] = (n_ss_rpm_[i] - n_rpm[i]) * inv_time_constant_;
    }
  }

  /// Finish the step begun last: speeds become n(dt), the battery discharges. No allocation.
  void endStep() noexcept;

  /// motorTorques() with this motor set's J_R and spin signs.
  [[nodiscard]] Wrench reactionWrench(const std::array<double, 4>& n_rpm,
                                      const std::array<double, 4>& n_dot_rpm_per_s,
                                      const Eigen::Vector3d& w_B, bool reaction,
                                      bool gyroscopic) const noexcept {
    return motorTorques(motor_.J_R_kgm2, yaw_sign_, n_rpm, n_dot_rpm_per_s, w_B, reaction,
                        gyroscopic);
  }

  /// ESC steady speed for a throttle at a given battery terminal voltage [rpm].
  /// A fault: motor i's ESC reaches `scale` ∈ [0, 1] of the speed its throttle asks for from the
  /// next step on (0: the motor stops; experiments/faults.hpp). Default 1. No allocation.
  void setSpeedScale(std::size_t i, double scale) noexcept { speed_scale_[i & 3u] = std::clamp(scale, 0.0, 1.0); }
  [[nodiscard]] double speedScale(std::size_t i) const noexcept { return speed_scale_[i & 3u]; }
  [[nodiscard]] double steadySpeedRpm(double throttle, double voltage_V) const noexcept;

  /// The throttle that holds rotor speed n in steady state, with the battery at its present
  /// charge and the sag the four rotors at that speed would cause [-] (clamped to [0, 1]).
  [[nodiscard]] double throttleForSteadySpeed(double n_rpm) const noexcept;

  [[nodiscard]] const std::array<double, 4>& speedsRpm() const noexcept { return n_rpm_; }
  [[nodiscard]] double voltageV() const noexcept { return voltage_V_; }  ///< terminal voltage
  [[nodiscard]] double currentA() const noexcept { return current_A_; }  ///< current drawn
  [[nodiscard]] double chargeUsedAh() const noexcept { return charge_used_Ah_; }

 private:
  [[nodiscard]] double openCircuitVoltage() const noexcept;
  [[nodiscard]] double currentAt(const std::array<double, 4>& n_rpm,
                                 double voltage_V) const noexcept;

  MotorParams motor_;
  BatteryParams battery_;
  std::array<double, 4> k_I_{};  // per-rotor aerodynamic torque coefficient (power draw)
  std::array<double, 4> yaw_sign_{};
  std::array<double, 4> n_rpm_{};     // speeds at the start of the step
  std::array<double, 4> n_ss_rpm_{};  // targets of the current step
  std::array<double, 4> speed_scale_{1.0, 1.0, 1.0, 1.0};  // faults: see setSpeedScale
  double dt_s_ = 0.0;
  double decay_half_ =
      1.0;  // e^(−dt/2τ) and e^(−dt/τ) for the step length dt_s_ (RK4's stage times)
  double decay_full_ = 1.0;
  double voltage_V_;
  double current_A_ = 0.0;
  double charge_used_Ah_;
  double inv_time_constant_;    // 1/τ [1/s]
  double inv_capacity_;         // 1/capacity [1/Ah]
  double inv_nominal_voltage_;  // 1/V_nom [1/V]
};

}  // namespace geaware::sim
