// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/model/ground_effect.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Geometry>

#include "geaware/model/units.hpp"

namespace geaware::model {

GroundEffectModel::GroundEffectModel(const VehicleParams& params)
    : mass_kg_(params.mass_kg),
      inertia_kgm2_(params.inertia_kgm2),
      min_height_m_(params.min_rotor_plane_height_m),
      induced_velocity_sq_(params.forward_fade_induced_velocity_mps * params.forward_fade_induced_velocity_mps),
      thrust_(params.additional_thrust),
      leveling_(params.leveling_torque) {
  // The tables' vectors are not needed twice: the HeightTables own the knots.
  if (!thrust_.table.empty()) {
    thrust_table_ = HeightTable(std::move(thrust_.table.heights_m), std::move(thrust_.table.values));
    thrust_.table = {};
  }
  if (!leveling_.table.empty()) {
    leveling_table_ =
        HeightTable(std::move(leveling_.table.heights_m), std::move(leveling_.table.values));
    leveling_.table = {};
  }
}

double GroundEffectModel::thrustRatio(double h_m) const noexcept {
  const double h = effectiveHeight(h_m);
  if (!thrust_table_.empty()) return thrust_table_.value(h);
  return thrust_.g2_m2 / (h * h + thrust_.g1_m2);
}

double GroundEffectModel::thrustRatioSlope(double h_m) const noexcept {
  if (h_m < min_height_m_) return 0.0;  // clamped region: the model is constant there
  if (!thrust_table_.empty()) return thrust_table_.slope(h_m);
  const double den = h_m * h_m + thrust_.g1_m2;
  return -2.0 * thrust_.g2_m2 * h_m / (den * den);
}

double GroundEffectModel::levelingShape(double h_m) const noexcept {
  const double h = effectiveHeight(h_m);
  if (!leveling_table_.empty()) return leveling_table_.value(h);
  const double den = h * h + leveling_.g3_m * h + leveling_.g4_m2;
  return leveling_.scale_m4 * h / (den * den);
}

double GroundEffectModel::levelingPeakHeight() const noexcept {
  if (!leveling_table_.empty()) {
    const auto& v = leveling_table_.values();
    const auto peak = std::max_element(v.begin(), v.end()) - v.begin();
    return leveling_table_.heights()[static_cast<std::size_t>(peak)];
  }
  // d/dh [h/(h²+g3h+g4)²] = 0  ⇔  3h² + g3·h − g4 = 0.
  const double g3 = leveling_.g3_m;
  return (-g3 + std::sqrt(g3 * g3 + 12.0 * leveling_.g4_m2)) / 6.0;
}

Eigen::Vector3d GroundEffectModel::levelingTorque_B(const Eigen::Matrix3d& R_WB, double h_m,
                                                    double thrust_N) const noexcept {
  const Eigen::Vector3d z_B = R_WB.col(2);
  const Eigen::Vector3d tau_W = levelingCoefficient(h_m) * thrust_N * z_B.cross(Eigen::Vector3d::UnitZ());
  return R_WB.transpose() * tau_W;
}

double GroundEffectModel::levelingInertiaIncrement(double h_m) const noexcept {
  const double mg = levelingCoefficient(h_m) / (1.0 + thrustRatio(h_m));
  return mass_kg_ * mg * mg;
}

double GroundEffectModel::levelingInertiaIncrement(double h_m, double thrust_N) const noexcept {
  const double torque_per_rad = levelingCoefficient(h_m) * thrust_N;
  return torque_per_rad * torque_per_rad / (mass_kg_ * kGravity * kGravity);
}

Eigen::Matrix3d GroundEffectModel::levelingInertia(double h_m) const noexcept {
  return levelingInertiaDiagonal(h_m).asDiagonal();
}

Eigen::Vector3d GroundEffectModel::levelingInertiaDiagonal(double h_m) const noexcept {
  const double q = levelingInertiaIncrement(h_m);
  return inertia_kgm2_ + Eigen::Vector3d(q, q, 0.0);
}

Eigen::Vector3d GroundEffectModel::levelingInertiaDiagonal(double h_m, double fade) const noexcept {
  if (fade == 1.0) return levelingInertiaDiagonal(h_m);
  // q = m·[fade·M_G/(1 + fade·F_G)]²: both the leveling torque and the hover thrust's cushion fade.
  const double mg = fade * levelingCoefficient(h_m) / (1.0 + fade * thrustRatio(h_m));
  const double q = mass_kg_ * mg * mg;
  return inertia_kgm2_ + Eigen::Vector3d(q, q, 0.0);
}

}  // namespace geaware::model
