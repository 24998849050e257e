// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/bridge/frames.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace geaware::bridge {
namespace {

/// ENU → NED as a rotation: 180° about (1, 1, 0)/√2.
const Eigen::Quaterniond& qNedEnu() noexcept {
  static const Eigen::Quaterniond q(0.0, std::sqrt(0.5), std::sqrt(0.5), 0.0);
  return q;
}
/// FRD → FLU (and FLU → FRD): 180° about x.
const Eigen::Quaterniond& qFluFrd() noexcept {
  static const Eigen::Quaterniond q(0.0, 1.0, 0.0, 0.0);
  return q;
}

Eigen::Quaterniond canonical(const Eigen::Quaterniond& q) noexcept {
  Eigen::Quaterniond r = q.normalized();
  if (r.w() < 0.0) r.coeffs() = -r.coeffs();
  return r;
}

}  // namespace

Eigen::Vector3d enuToNed(const Eigen::Vector3d& v) noexcept { return {v.y(), v.x(), -v.z()}; }
Eigen::Vector3d nedToEnu(const Eigen::Vector3d& v) noexcept { return {v.y(), v.x(), -v.z()}; }
Eigen::Vector3d fluToFrd(const Eigen::Vector3d& v) noexcept { return {v.x(), -v.y(), -v.z()}; }
Eigen::Vector3d frdToFlu(const Eigen::Vector3d& v) noexcept { return {v.x(), -v.y(), -v.z()}; }

Eigen::Quaterniond enuFluToNedFrd(const Eigen::Quaterniond& q_enu_flu) noexcept {
  // q_NED_FRD = q_NED_ENU ⊗ q_ENU_FLU ⊗ q_FLU_FRD
  return canonical(qNedEnu() * q_enu_flu * qFluFrd());
}

Eigen::Quaterniond nedFrdToEnuFlu(const Eigen::Quaterniond& q_ned_frd) noexcept {
  return canonical(qNedEnu().conjugate() * q_ned_frd * qFluFrd().conjugate());
}

bool MotorMap::valid() const noexcept {
  for (std::size_t i = 0; i < px4_index.size(); ++i) {
    if (px4_index[i] < 0 || px4_index[i] > 11) return false;
    for (std::size_t j = 0; j < i; ++j) {
      if (px4_index[j] == px4_index[i]) return false;
    }
  }
  return true;
}

double normalisedThrustFromThrottle(double throttle, double thr_mdl_fac) noexcept {
  if (std::isnan(throttle)) return throttle;
  const double u = std::clamp(throttle, 0.0, 1.0);
  const double f = std::clamp(thr_mdl_fac, 0.0, 1.0);
  return std::clamp(f * u * u + (1.0 - f) * u, 0.0, 1.0);
}

double throttleFromNormalisedThrust(double c_in, double thr_mdl_fac) noexcept {
  if (std::isnan(c_in)) return c_in;
  const double c = std::clamp(c_in, 0.0, 1.0);
  const double f = std::clamp(thr_mdl_fac, 0.0, 1.0);
  if (f < 1e-9) return c;
  // f·u² + (1 − f)·u − c = 0, the root in [0, 1] (PX4's FunctionMotors does the same).
  const double b = 1.0 - f;
  const double u = (-b + std::sqrt(b * b + 4.0 * f * c)) / (2.0 * f);
  return std::clamp(u, 0.0, 1.0);
}

std::uint64_t toMicroseconds(double t_s) noexcept {
  if (!(t_s > 0.0) || !std::isfinite(t_s)) return 0;
  const double us = std::round(t_s * 1e6);
  if (us >= static_cast<double>(std::numeric_limits<std::uint64_t>::max())) return 0;
  return static_cast<std::uint64_t>(us);
}

double toSeconds(std::uint64_t t_us) noexcept { return static_cast<double>(t_us) * 1e-6; }

}  // namespace geaware::bridge
