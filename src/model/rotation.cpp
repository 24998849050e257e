// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/model/rotation.hpp"

#include <cmath>

namespace geaware::model {

Eigen::Vector3d logMap(const Eigen::Quaterniond& q_in) noexcept {
  // Shorter path: q and −q are the same rotation; pick w ≥ 0 so |θ| ≤ π.
  const Eigen::Quaterniond q = q_in.w() < 0.0 ? Eigen::Quaterniond(-q_in.coeffs()) : q_in;
  const double s = q.vec().norm();
  if (s < 1e-9) return 2.0 * q.vec() / q.w();  // θ ≈ 2·v for tiny angles (w ≈ 1)
  return 2.0 * std::atan2(s, q.w()) / s * q.vec();
}

Eigen::Quaterniond expMap(const Eigen::Vector3d& theta) noexcept {
  const double a = theta.norm();
  if (a < 1e-9)
    return Eigen::Quaterniond(1.0, 0.5 * theta.x(), 0.5 * theta.y(), 0.5 * theta.z()).normalized();
  const Eigen::Vector3d v = std::sin(0.5 * a) / a * theta;
  return {std::cos(0.5 * a), v.x(), v.y(), v.z()};
}

double angleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) noexcept {
  const Eigen::Quaterniond e = a.conjugate() * b;
  return 2.0 * std::atan2(e.vec().norm(), std::abs(e.w()));
}

}  // namespace geaware::model
