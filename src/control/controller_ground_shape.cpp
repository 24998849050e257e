// SPDX-License-Identifier: BSD-3-Clause
// Per-rotor ground effect (ControllerParams::per_rotor_ground_effect, "+rotors"; issue 13 item 1,
// docs/controller.md "Per-rotor ground effect"): the lift and torque of the ground's shape under
// the vehicle, from the lattice ranger's per-rotor offsets and ground normal.
#include <cmath>

#include "controller_internal.hpp"
#include "geaware/control/controller.hpp"
#include "geaware/model/finite.hpp"

namespace geaware::control {

Controller::GroundShapeTerms Controller::groundShapeTerms(const ControllerInput& in, double h,
                                                          double thrust_N,
                                                          const Eigen::Matrix3d& R) noexcept {
  GroundShapeTerms g;
  if (!params_.per_rotor_ground_effect) return g;
  // The last valid shape is held, like the height: offsets finite and within the far-from-ground
  // height, the normal a finite unit vector no steeper than 60°.
  bool ok = in.ground_shape_valid && model::allFinite(in.ground_normal_W) &&
            std::abs(in.ground_normal_W.norm() - 1.0) < 1e-3 && in.ground_normal_W.z() > 0.5;
  for (double d : in.rotor_height_offset_m) ok = ok && std::isfinite(d) && std::abs(d) <= detail::kFarFromGroundM;
  if (ok) {
    for (int i = 0; i < 4; ++i) mem_.rotor_height_offset_m_[i] = in.rotor_height_offset_m[static_cast<std::size_t>(i)];
    mem_.ground_normal_W_ = in.ground_normal_W.normalized();
  }
  // Rotor i flies at h + δ_i above the surface beneath it: F_G(h + δ_i) of a quarter of the
  // thrust, against F_G(h) for all four in the vehicle-level model (docs/controller.md).
  const double f0 = ground_effect_.thrustRatio(h);
  double df_sum = 0.0;
  Eigen::Vector3d tau_B = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < 4; ++i) {
    const double df =
        mem_.fade_ref_ * (ground_effect_.thrustRatio(h + mem_.rotor_height_offset_m_[static_cast<int>(i)]) - f0);
    df_sum += df;
    // r_i × (0, 0, ΔT_i) = ΔT_i·(r_y, −r_x, 0), ΔT_i = T/4·ΔF_i.
    tau_B += (0.25 * thrust_N * df) * Eigen::Vector3d(rotors_B_[i].y(), -rotors_B_[i].x(), 0.0);
  }
  const Eigen::Vector3d z_B = R.col(2);
  if (params_.acceleration == AccelerationCompensation::kModel) {
    g.a_W = (0.25 * df_sum * thrust_N / mass_kg_) * z_B;
  }
  if (detail::usesJPrime(params_.torque)) {
    // Leveling toward the ground's normal n: M_G·T·(z_B × n) (paper eq. 13 with n for z_W), of
    // which J'(h) models the part M_G·T·(z_B × z_W); the rest is predicted here.
    const Eigen::Vector3d extra_W =
        mem_.fade_ref_ * ground_effect_.levelingCoefficient(h) * thrust_N *
        z_B.cross(mem_.ground_normal_W_ - Eigen::Vector3d::UnitZ());
    g.tau_B = tau_B + R.transpose() * extra_W;
  }
  return g;
}

}  // namespace geaware::control
