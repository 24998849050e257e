// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/model/mixer.hpp"

#include <cmath>

#include <Eigen/LU>

namespace geaware::model {

const Eigen::Matrix4d& Mixer::allocationPattern() noexcept {
  static const Eigen::Matrix4d A = (Eigen::Matrix4d() << 1, 1, 1, 1,  //
                                    -1, 1, 1, -1,                     //
                                    -1, 1, -1, 1,                     //
                                    -1, -1, 1, 1)
                                       .finished();
  return A;
}

const Eigen::Vector4d& Mixer::yawSigns() noexcept {
  static const Eigen::Vector4d s(-1.0, -1.0, 1.0, 1.0);
  return s;
}

std::array<Eigen::Vector3d, 4> Mixer::rotorPositions_B(double b_m) noexcept {
  // Roll torque of a rotor at (x, y) is +y·f and pitch torque −x·f, so the signs of A's rows 2
  // and 3 give y and −x of each rotor; the arm is b/2 along the diagonal: |x| = |y| = √2·b/4.
  const double a = mixerArm_m(b_m);
  const Eigen::Matrix4d& A = allocationPattern();
  std::array<Eigen::Vector3d, 4> r;
  for (int i = 0; i < 4; ++i) r[static_cast<std::size_t>(i)] = Eigen::Vector3d(-A(2, i) * a, A(1, i) * a, 0.0);
  return r;
}

Mixer::Mixer(const VehicleParams& params) {
  const auto& r = params.rotor;
  const double arm = mixerArm_m(params.diagonal_rotor_distance_m);
  const Eigen::Vector4d gains(r.k_T_N_per_rpm2, arm * r.k_TX_N_per_rpm2, arm * r.k_TY_N_per_rpm2,
                              r.k_I_Nm_per_rpm2);
  M_ = gains.asDiagonal() * allocationPattern();
  // A is orthogonal up to scale (A·Aᵀ = 4·I), so M⁻¹ = Aᵀ·diag(gains)⁻¹ / 4 exactly.
  M_inv_ = allocationPattern().transpose() * gains.cwiseInverse().asDiagonal() / 4.0;
  const Eigen::Vector4d k(r.k_T_N_per_rpm2, r.k_TX_N_per_rpm2, r.k_TY_N_per_rpm2, r.k_I_Nm_per_rpm2);
  base_ = k.cwiseInverse().asDiagonal() * M_;
}

}  // namespace geaware::model
