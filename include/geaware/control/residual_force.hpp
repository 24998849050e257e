// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A learned model of the residual (unmodelled) force on the vehicle, for the Neural-Lander
// baseline (Shi et al. 2019). The controller only sees this interface; the network, its
// training and its weight file live in the Neural-Lander work.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace geaware::control {

/// Inputs of the residual-force model (Shi et al. 2019 use height, velocity, attitude and the
/// rotor-speed command).
struct ResidualFeatures {
  double height_m = 0.0;                                     ///< rotor-plane height [m]
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();             ///< velocity [m/s]
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();  ///< attitude
  Eigen::Vector4d rotor_speeds_rpm = Eigen::Vector4d::Zero();///< rotor speeds [rpm]
};

class ResidualForceModel {
 public:
  virtual ~ResidualForceModel() = default;
  /// Predicted residual force in the world frame [N]. Must not allocate; must be finite.
  [[nodiscard]] virtual Eigen::Vector3d predict_W(const ResidualFeatures& f) const noexcept = 0;
};

}  // namespace geaware::control
