// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The simulator's true state. Only sim/ and the experiment runner (for metrics) read it; the
// controller sees it only through simulated sensors.

#include <array>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace geaware::sim {

struct PlantState {
  double t_s = 0.0;                                        ///< simulation time [s]
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();           ///< geometric centre (rotor-plane centre) [m]
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();           ///< velocity of the geometric centre [m/s]
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();///< attitude, body → world
  Eigen::Vector3d w_B = Eigen::Vector3d::Zero();           ///< body rates [rad/s]
  std::array<double, 4> n_rpm{};                           ///< rotor speeds [rpm], mixer order
  Eigen::Vector3d a_W = Eigen::Vector3d::Zero();           ///< last acceleration [m/s²] (for the IMU)
  Eigen::Vector3d w_dot_B = Eigen::Vector3d::Zero();       ///< last angular acceleration [rad/s²]
};

}  // namespace geaware::sim
