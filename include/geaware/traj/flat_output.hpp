// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Flat outputs of a multicopter (paper eq. 19): position and yaw with their derivatives.
// World frame, z up; SI units.

#include <cmath>

#include <Eigen/Core>

namespace geaware::traj {

struct FlatOutput {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  ///< position [m]
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();  ///< velocity [m/s]
  Eigen::Vector3d a_W = Eigen::Vector3d::Zero();  ///< acceleration [m/s²]
  Eigen::Vector3d j_W = Eigen::Vector3d::Zero();  ///< jerk [m/s³]
  Eigen::Vector3d s_W = Eigen::Vector3d::Zero();  ///< snap [m/s⁴]
  double yaw_rad = 0.0;                           ///< ψ [rad]
  double yaw_rate_radps = 0.0;                    ///< ψ̇ [rad/s]
  double yaw_acc_radps2 = 0.0;                    ///< ψ̈ [rad/s²]

  /// True when every component is finite.
  [[nodiscard]] bool allFinite() const noexcept {
    return p_W.allFinite() && v_W.allFinite() && a_W.allFinite() && j_W.allFinite() &&
           s_W.allFinite() && std::isfinite(yaw_rad) && std::isfinite(yaw_rate_radps) &&
           std::isfinite(yaw_acc_radps2);
  }
};

}  // namespace geaware::traj
