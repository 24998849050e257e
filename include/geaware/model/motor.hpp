// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Motor and ESC models of the paper's supplementary section 3: single-rotor thrust and torque,
// and the quadratic throttle curve with its inverse.

#include "geaware/model/vehicle_params.hpp"

namespace geaware::model {

/// Thrust of one rotor, T_i = k_T·n_i² [N], n in rpm.
[[nodiscard]] inline double rotorThrust(const RotorParams& p, double n_rpm) noexcept {
  return p.k_T_N_per_rpm2 * n_rpm * n_rpm;
}

/// The rotor speed at which four rotors carry m·g out of ground effect, √(m·g/(4·k_T)) [rpm].
[[nodiscard]] double freeAirHoverSpeedRpm(double mass_kg, double k_T_N_per_rpm2) noexcept;

/// Reaction-torque magnitude of one rotor, M_i = k_I·n_i² + J_R·ṅ_i [N·m]. J_R is in kg·m², so
/// ṅ (given in rpm/s) is converted to rad/s² here. The spin sign is applied by the mixer.
[[nodiscard]] double rotorReactionTorque(const RotorParams& p, double n_rpm,
                                         double n_dot_rpm_per_s) noexcept;

/// ESC throttle curve n(t) = √(c2·t² + c1·t + c0) and its inverse, at the reference battery
/// voltage, and scaled by (V/V_ref)^p at another (ThrottleCurveParams). Validated parameters make
/// n² non-negative and strictly increasing on t ∈ [0, 1]; both directions clamp to that range.
class ThrottleCurve {
 public:
  explicit ThrottleCurve(const ThrottleCurveParams& p);

  /// Rotor speed at throttle t; t is clamped to [0, 1] [rpm].
  [[nodiscard]] double speedRpm(double throttle) const noexcept;

  /// Throttle that gives rotor speed n; n is clamped to [minSpeedRpm, maxSpeedRpm], and a NaN
  /// speed gives 0 (idle rather than an undefined command) [-].
  [[nodiscard]] double throttle(double n_rpm) const noexcept;

  [[nodiscard]] double minSpeedRpm() const noexcept { return n_min_rpm_; }  ///< n(0) [rpm]
  [[nodiscard]] double maxSpeedRpm() const noexcept { return n_max_rpm_; }  ///< n(1) [rpm]

  /// (V/V_ref)^p, the factor the battery voltage V puts on every speed of the curve [-]. Exactly
  /// 1 when the curve has no voltage dependence (V_ref = 0), when V is not a measurement (NaN,
  /// ±inf, ≤ 0) and at V = V_ref; V/V_ref is held to [0.5, 1.5] (a reading outside is no battery
  /// this curve was identified with).
  [[nodiscard]] double voltageScale(double voltage_V) const noexcept;
  /// speedRpm(throttle)·voltageScale(V) [rpm].
  [[nodiscard]] double speedRpm(double throttle, double voltage_V) const noexcept {
    return speedRpm(throttle) * voltageScale(voltage_V);
  }
  /// The throttle that gives rotor speed n at battery voltage V: throttle(n / voltageScale(V)),
  /// bit for bit throttle(n) at V_ref or without a voltage [-].
  [[nodiscard]] double throttle(double n_rpm, double voltage_V) const noexcept {
    return throttle(n_rpm / voltageScale(voltage_V));
  }

 private:
  ThrottleCurveParams p_;
  double n_min_rpm_;
  double n_max_rpm_;
};

}  // namespace geaware::model
