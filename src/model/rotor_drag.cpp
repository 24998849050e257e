// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/model/rotor_drag.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace geaware::model {

RotorDragModel::RotorDragModel(const DragTableParams& table) : heights_m_(table.heights_m) {
  d_.reserve(heights_m_.size());
  for (std::size_t i = 0; i < heights_m_.size(); ++i) {
    d_.emplace_back(table.d_x_N_per_mps[i], table.d_y_N_per_mps[i]);
  }
}

Eigen::Vector2d RotorDragModel::coefficients(double h_m) const noexcept {
  if (!(h_m > heights_m_.front())) {
    // Below the table (or NaN): the lowest measurement; a NaN height yields NaN coefficients.
    return std::isnan(h_m) ? Eigen::Vector2d::Constant(std::nan("")) : d_.front();
  }
  if (h_m >= heights_m_.back()) return d_.back();
  // Tables hold a handful of heights: a linear scan beats a binary search here.
  std::size_t i = 1;
  while (heights_m_[i] < h_m) ++i;
  const double w = (h_m - heights_m_[i - 1]) / (heights_m_[i] - heights_m_[i - 1]);
  return (1.0 - w) * d_[i - 1] + w * d_[i];
}

Eigen::Vector2d RotorDragModel::highAltitudeCoefficients() const noexcept { return d_.back(); }

Eigen::Vector3d RotorDragModel::force_W(const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& v_W,
                                        const Eigen::Vector2d& d_N_per_mps) noexcept {
  const Eigen::Vector3d v_B = R_WB.transpose() * v_W;
  return -R_WB * Eigen::Vector3d(d_N_per_mps.x() * v_B.x(), d_N_per_mps.y() * v_B.y(), 0.0);
}

Eigen::Vector3d RotorDragModel::thrustScaledForce_W(const Eigen::Matrix3d& R_WB,
                                                    const Eigen::Vector3d& v_W,
                                                    const Eigen::Vector2d& d_prime,
                                                    double thrust_N) noexcept {
  return force_W(R_WB, v_W, d_prime * std::sqrt(std::max(thrust_N, 0.0)));
}

}  // namespace geaware::model
