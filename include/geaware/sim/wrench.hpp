// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A force and a torque acting on the vehicle, both in the body frame, the torque about the
// centre of mass. Every physical contribution of the simulator produces one; the plant sums them.

#include <Eigen/Core>

namespace geaware::sim {

struct Wrench {
  Eigen::Vector3d force_B = Eigen::Vector3d::Zero();   ///< [N], body frame
  Eigen::Vector3d torque_B = Eigen::Vector3d::Zero();  ///< [N·m], body frame, about the CoM

  Wrench& operator+=(const Wrench& o) noexcept {
    force_B += o.force_B;
    torque_B += o.torque_B;
    return *this;
  }
};

}  // namespace geaware::sim
