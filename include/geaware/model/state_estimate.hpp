// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The state estimate a controller flies on: what estimation/ produces and control/ reads (never
// the simulator's truth). A plain value type in model/ so that neither layer includes the other.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace geaware::model {

/// Position, velocity and attitude estimate in the world frame.
struct StateEstimate {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();             ///< position [m]
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();             ///< velocity [m/s]
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();  ///< attitude, body → world
};

}  // namespace geaware::model
