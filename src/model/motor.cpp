// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/model/motor.hpp"

#include <algorithm>
#include <cmath>

#include "geaware/model/units.hpp"

namespace geaware::model {

double rotorReactionTorque(const RotorParams& p, double n_rpm, double n_dot_rpm_per_s) noexcept {
  return p.k_I_Nm_per_rpm2 * n_rpm * n_rpm + p.J_R_kgm2 * n_dot_rpm_per_s * kRpmToRadPerSec;
}

double freeAirHoverSpeedRpm(double mass_kg, double k_T_N_per_rpm2) noexcept {
  return std::sqrt(mass_kg * kGravity / (4.0 * k_T_N_per_rpm2));
}

ThrottleCurve::ThrottleCurve(const ThrottleCurveParams& p)
    : p_(p),
      n_min_rpm_(std::sqrt(p.c0_rpm2)),
      n_max_rpm_(std::sqrt(p.c2_rpm2 + p.c1_rpm2 + p.c0_rpm2)) {}

double ThrottleCurve::speedRpm(double throttle) const noexcept {
  const double t = std::clamp(throttle, 0.0, 1.0);
  return std::sqrt((p_.c2_rpm2 * t + p_.c1_rpm2) * t + p_.c0_rpm2);
}

double ThrottleCurve::voltageScale(double voltage_V) const noexcept {
  if (!(p_.reference_voltage_V > 0.0) || !(voltage_V > 0.0) || !std::isfinite(voltage_V)) return 1.0;
  const double ratio = std::clamp(voltage_V / p_.reference_voltage_V, 0.5, 1.5);
  return p_.voltage_exponent == 1.0 ? ratio : std::pow(ratio, p_.voltage_exponent);
}

double ThrottleCurve::throttle(double n_rpm) const noexcept {
  if (!(n_rpm > n_min_rpm_)) return 0.0;  // also catches NaN: no throttle rather than NaN
  if (n_rpm >= n_max_rpm_) return 1.0;
  const double n = n_rpm;
  // Root of c2·t² + c1·t − q = 0, q = n² − c0, in the form that stays exact as c2 → 0:
  // t = 2q / (c1 + √(c1² + 4·c2·q)).
  const double q = n * n - p_.c0_rpm2;
  const double disc = std::max(p_.c1_rpm2 * p_.c1_rpm2 + 4.0 * p_.c2_rpm2 * q, 0.0);
  return std::clamp(2.0 * q / (p_.c1_rpm2 + std::sqrt(disc)), 0.0, 1.0);
}

}  // namespace geaware::model
