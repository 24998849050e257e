// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Control allocation of the X quadrotor (controller step 5): squared rotor speeds
// N² = M⁻¹·[T; τ_B] inside the rotor-speed range, with priorities when the wrench does not fit.
// Thrust first (equal speeds, clipped to the range), then roll/pitch, then yaw: each added
// scaled by the largest s ∈ [0, 1] that keeps every rotor inside [n_min², n_max²] given what is
// already allocated. A pure function of its arguments; no allocation, no exceptions.

#include <Eigen/Core>

namespace geaware::control {

/// Squared rotor speeds and which demands had to be cut.
struct RotorAllocation {
  Eigen::Vector4d n_sq_rpm2 = Eigen::Vector4d::Zero();  ///< per rotor, mixer order [rpm²]
  bool thrust_saturated = false;      ///< thrust clipped to the range
  bool roll_pitch_saturated = false;  ///< roll/pitch torque scaled down to fit
  bool yaw_saturated = false;         ///< yaw torque scaled down to fit
};

/// Allocates thrust [N] and body torque [N·m] with the mixer inverse `M_inv`
/// (model::Mixer::inverse()) into squared speeds within [min_speed_rpm², max_speed_rpm²].
[[nodiscard]] RotorAllocation allocateRotorSpeeds(const Eigen::Matrix4d& M_inv, double thrust_N,
                                                  const Eigen::Vector3d& tau_B,
                                                  double min_speed_rpm,
                                                  double max_speed_rpm) noexcept;

}  // namespace geaware::control
