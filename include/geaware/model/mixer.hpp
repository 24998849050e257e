// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The X-quadrotor mixer of the paper (eq. 2):
//   [T; τ_B] = M·N²,  M = diag(k_T, (√2·b/4)·k_TX, (√2·b/4)·k_TY, k_I)·A,
//   A = [[1,1,1,1], [−1,1,1,−1], [−1,1,−1,1], [−1,−1,1,1]],
// with N² the squared rotor speeds [rpm²]. The rows of A fix the rotor layout (body frame x
// forward, y left, z up): rotor 1 front-right, 2 rear-left, 3 front-left, 4 rear-right; rotors
// 1 and 2 spin counter-clockwise seen from above (reaction torque −z), 3 and 4 clockwise.

#include <array>
#include <cmath>

#include <Eigen/Core>

#include "geaware/model/vehicle_params.hpp"

namespace geaware::model {

/// Arm of the X layout: the distance of each rotor centre from the body x and y axes, √2·b/4,
/// for the distance b between diagonal rotor axes [m]. The roll and pitch rows of the mixer
/// carry it (M = diag(k_T, arm·k_TX, arm·k_TY, k_I)·A).
[[nodiscard]] inline double mixerArm_m(double diagonal_rotor_distance_m) noexcept {
  return std::sqrt(2.0) * diagonal_rotor_distance_m / 4.0;
}

class Mixer {
 public:
  /// Requires validated parameters.
  explicit Mixer(const VehicleParams& params);

  /// The sign pattern A of the X configuration.
  [[nodiscard]] static const Eigen::Matrix4d& allocationPattern() noexcept;

  /// Rotor centres in the body frame [m], at (±√2·b/4, ±√2·b/4, 0) in the order of A's columns.
  [[nodiscard]] static std::array<Eigen::Vector3d, 4> rotorPositions_B(double b_m) noexcept;

  /// Spin sign of each rotor about body z (+1: reaction torque along +z).
  [[nodiscard]] static const Eigen::Vector4d& yawSigns() noexcept;

  /// [T; τ_B] from squared rotor speeds [N, N·m].
  [[nodiscard]] Eigen::Vector4d wrench(const Eigen::Vector4d& n_sq_rpm2) const noexcept {
    return M_ * n_sq_rpm2;
  }

  /// Squared rotor speeds M⁻¹·[T; τ_B] [rpm²]; may be negative for an infeasible wrench.
  [[nodiscard]] Eigen::Vector4d squaredSpeeds(const Eigen::Vector4d& wrench) const noexcept {
    return M_inv_ * wrench;
  }

  /// N_base = diag(k_T, k_TX, k_TY, k_I)⁻¹·M·N² (paper eq. 4): the composite rotor speeds
  /// behind thrust, roll, pitch and yaw torque [rpm², m·rpm², m·rpm², rpm²].
  [[nodiscard]] Eigen::Vector4d baseSpeeds(const Eigen::Vector4d& n_sq_rpm2) const noexcept {
    return base_ * n_sq_rpm2;
  }

  [[nodiscard]] const Eigen::Matrix4d& matrix() const noexcept { return M_; }
  [[nodiscard]] const Eigen::Matrix4d& inverse() const noexcept { return M_inv_; }

 private:
  Eigen::Matrix4d M_;
  Eigen::Matrix4d M_inv_;
  Eigen::Matrix4d base_;
};

}  // namespace geaware::model
