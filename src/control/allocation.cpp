// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/control/allocation.hpp"

#include <algorithm>

namespace geaware::control {

RotorAllocation allocateRotorSpeeds(const Eigen::Matrix4d& M_inv, double thrust_N,
                                    const Eigen::Vector3d& tau_B, double min_speed_rpm,
                                    double max_speed_rpm) noexcept {
  RotorAllocation out;
  const double lo = min_speed_rpm * min_speed_rpm;
  const double hi = max_speed_rpm * max_speed_rpm;
  Eigen::Vector4d& n_sq = out.n_sq_rpm2;

  // Thrust first: equal speeds, clipped to the range.
  n_sq = M_inv.col(0) * thrust_N;
  const double uniform = n_sq(0);
  if (uniform < lo || uniform > hi) {
    n_sq.setConstant(std::clamp(uniform, lo, hi));
    out.thrust_saturated = true;
  }
  // Then roll/pitch, then yaw: each scaled by the largest s ∈ [0, 1] that keeps every rotor
  // inside [lo, hi] given what is already allocated. Returns whether it had to scale.
  const auto addScaled = [&](const Eigen::Vector4d& delta) {
    double s = 1.0;
    for (int i = 0; i < 4; ++i) {
      if (delta(i) > 0.0) s = std::min(s, (hi - n_sq(i)) / delta(i));
      if (delta(i) < 0.0) s = std::min(s, (lo - n_sq(i)) / delta(i));
    }
    s = std::max(s, 0.0);
    n_sq += s * delta;
    return s < 1.0;
  };
  out.roll_pitch_saturated = addScaled(M_inv.col(1) * tau_B.x() + M_inv.col(2) * tau_B.y());
  out.yaw_saturated = addScaled(M_inv.col(3) * tau_B.z());
  n_sq = n_sq.cwiseMax(lo).cwiseMin(hi);  // guards rounding at the bounds
  return out;
}

}  // namespace geaware::control
