// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Height-dependent rotor drag of the paper (eq. 18): f_D = −R·D(h)·Rᵀ·v, D(h) = diag(d_x, d_y, 0)
// interpolated linearly in h from a table measured per height, held constant outside the table
// (below its first height: the lowest measurement; above its last: the high-altitude value).

#include <vector>

#include <Eigen/Core>

#include "geaware/model/vehicle_params.hpp"

namespace geaware::model {

class RotorDragModel {
 public:
  /// Requires a validated table (same sizes, at least one row, strictly increasing heights).
  explicit RotorDragModel(const DragTableParams& table);

  /// (d_x, d_y) at height h [N/(m/s)].
  [[nodiscard]] Eigen::Vector2d coefficients(double h_m) const noexcept;

  /// The high-altitude coefficients, the table's last row [N/(m/s)].
  [[nodiscard]] Eigen::Vector2d highAltitudeCoefficients() const noexcept;

  /// Drag force in the world frame [N]: −R·diag(d_x, d_y, 0)·Rᵀ·v.
  [[nodiscard]] static Eigen::Vector3d force_W(const Eigen::Matrix3d& R_WB,
                                               const Eigen::Vector3d& v_W,
                                               const Eigen::Vector2d& d_N_per_mps) noexcept;

  /// The thrust-scaled form of Faessler et al. 2017 used as high-altitude reference (paper
  /// eq. 17): −R·D'·√T·Rᵀ·v, with D' = diag(d'_x, d'_y, 0) [N/(m/s)/√N].
  [[nodiscard]] static Eigen::Vector3d thrustScaledForce_W(const Eigen::Matrix3d& R_WB,
                                                           const Eigen::Vector3d& v_W,
                                                           const Eigen::Vector2d& d_prime,
                                                           double thrust_N) noexcept;

 private:
  std::vector<double> heights_m_;
  std::vector<Eigen::Vector2d> d_;
};

}  // namespace geaware::model
