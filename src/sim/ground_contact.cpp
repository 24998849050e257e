// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/sim/ground_contact.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace geaware::sim {

GroundContact::GroundContact(const LandingGearParams& params,
                             std::vector<Eigen::Vector3d> feet_from_com_B, double mass_kg)
    : params_(params),
      feet_B_(std::move(feet_from_com_B)),
      ground_W_(feet_B_.size(), Eigen::Vector3d::Zero()),
      normal_W_(feet_B_.size(), Eigen::Vector3d::UnitZ()),
      feet_(feet_B_.size()) {
  if (!feet_B_.empty() && params_.enabled()) {
    const double foot_mass_kg = mass_kg / static_cast<double>(feet_B_.size());
    damping_Ns_per_m_ =
        2.0 * params_.damping_ratio * std::sqrt(params_.stiffness_N_per_m * foot_mass_kg);
  }
}

void GroundContact::sample(const Terrain* terrain, const double* flat_z_m,
                           const RigidBodyState& body, const Eigen::Matrix3d& R_WB) noexcept {
  has_ground_ = terrain != nullptr;
  if (!has_ground_) return;
  for (std::size_t k = 0; k < feet_B_.size(); ++k) {
    const Eigen::Vector3d f = body.p_W + R_WB * feet_B_[k];
    if (flat_z_m != nullptr) {
      ground_W_[k] = Eigen::Vector3d(f.x(), f.y(), *flat_z_m);
      normal_W_[k] = Eigen::Vector3d::UnitZ();
    } else {
      ground_W_[k] = Eigen::Vector3d(f.x(), f.y(), terrain->heightAt(f.x(), f.y()));
      normal_W_[k] = terrain->normalAt(f.x(), f.y());
    }
  }
}

Wrench GroundContact::wrench(const RigidBodyState& x, const Eigen::Matrix3d& R_WB,
                             bool keep) noexcept {
  Wrench total;
  if (!has_ground_ || !params_.enabled()) return total;
  const Eigen::Vector3d w_W = R_WB * x.w_B;
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque_W = Eigen::Vector3d::Zero();  // about the CoM
  for (std::size_t k = 0; k < feet_B_.size(); ++k) {
    const Eigen::Vector3d r_W = R_WB * feet_B_[k];
    const Eigen::Vector3d f = x.p_W + r_W;
    const Eigen::Vector3d& g = ground_W_[k];
    const Eigen::Vector3d& n = normal_W_[k];
    // The plane through g with normal n: its height at the foot's (x, y), then the distance
    // under it along n.
    const double plane_z = g.z() - (n.x() * (f.x() - g.x()) + n.y() * (f.y() - g.y())) / n.z();
    const double compression = (plane_z - f.z()) * n.z();
    FootContact foot;
    if (compression > 0.0) {
      const Eigen::Vector3d v_foot = x.v_W + w_W.cross(r_W);
      const double v_n = v_foot.dot(n);
      const double f_n =
          std::max(0.0, params_.stiffness_N_per_m * compression - damping_Ns_per_m_ * v_n);
      const Eigen::Vector3d v_t = v_foot - v_n * n;
      const double slip = std::sqrt(v_t.squaredNorm() + params_.slip_speed_mps * params_.slip_speed_mps);
      const Eigen::Vector3d f_W = f_n * n - (params_.friction_coefficient * f_n / slip) * v_t;
      force_W += f_W;
      torque_W += r_W.cross(f_W);
      foot = FootContact{compression, f_n, true};
    }
    if (keep) feet_[k] = foot;
  }
  total.force_B = R_WB.transpose() * force_W;
  total.torque_B = R_WB.transpose() * torque_W;
  return total;
}

int GroundContact::touchingFeet() const noexcept {
  int n = 0;
  for (const FootContact& f : feet_) n += f.touching ? 1 : 0;
  return n;
}

}  // namespace geaware::sim
