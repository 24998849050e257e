// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/sim/rigid_body.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

namespace geaware::sim {

MassProperties::MassProperties(double mass_kg, const Eigen::Matrix3d& inertia_kgm2)
    : mass_kg_(mass_kg), J_(inertia_kgm2) {
  if (!(std::isfinite(mass_kg) && mass_kg > 0.0) || !J_.allFinite() ||
      !J_.isApprox(J_.transpose(), 1e-12) ||
      !(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(J_).eigenvalues().minCoeff() > 0.0)) {
    throw std::invalid_argument(
        "MassProperties: mass must be positive and inertia symmetric positive definite");
  }
  J_inv_ = J_.inverse();
  inv_mass_ = 1.0 / mass_kg_;
}

RigidBodyDerivative rigidBodyDerivative(const RigidBodyState& x, const Wrench& wrench,
                                        const MassProperties& mass) noexcept {
  return rigidBodyDerivative(x, rotationOf(x.q_WB), wrench, mass);
}

double kineticEnergy(const RigidBodyState& x, const MassProperties& mass) noexcept {
  return 0.5 * mass.mass() * x.v_W.squaredNorm() + 0.5 * x.w_B.dot(mass.inertia() * x.w_B);
}

Eigen::Vector3d angularMomentum_W(const RigidBodyState& x, const MassProperties& mass) noexcept {
  return x.q_WB.normalized() * (mass.inertia() * x.w_B);
}

}  // namespace geaware::sim
