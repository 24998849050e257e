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

Eigen::Matrix3d rotationOf(const Eigen::Quaterniond& q) noexcept {
  const double w = q.w();
  const double x = q.x();
  const double y = q.y();
  const double z = q.z();
  const double s = 2.0 / (w * w + x * x + y * y + z * z);
  Eigen::Matrix3d R;
  R << 1.0 - s * (y * y + z * z), s * (x * y - w * z), s * (x * z + w * y),  //
      s * (x * y + w * z), 1.0 - s * (x * x + z * z), s * (y * z - w * x),   //
      s * (x * z - w * y), s * (y * z + w * x), 1.0 - s * (x * x + y * y);
  return R;
}

RigidBodyDerivative rigidBodyDerivative(const RigidBodyState& x, const Eigen::Matrix3d& R_WB,
                                        const Wrench& wrench, const MassProperties& mass) noexcept {
  RigidBodyDerivative d;
  d.p_dot = x.v_W;
  d.v_dot = R_WB * (wrench.force_B * mass.massInverse());
  // q̇ = ½·q ⊗ (0, ω) with the un-normalised stage quaternion, so RK4 integrates its own
  // variable consistently; the norm drift is O(dt⁵) per step and removed at every step's end.
  const Eigen::Quaterniond qdot = x.q_WB * Eigen::Quaterniond(0.0, x.w_B.x(), x.w_B.y(), x.w_B.z());
  d.q_dot = 0.5 * Eigen::Vector4d(qdot.w(), qdot.x(), qdot.y(), qdot.z());
  d.w_dot = mass.inertiaInverse() * (wrench.torque_B - x.w_B.cross(mass.inertia() * x.w_B));
  return d;
}

RigidBodyState advance(const RigidBodyState& x, const RigidBodyDerivative& dx, double h) noexcept {
  RigidBodyState y;
  y.p_W = x.p_W + h * dx.p_dot;
  y.v_W = x.v_W + h * dx.v_dot;
  y.q_WB = Eigen::Quaterniond(x.q_WB.w() + h * dx.q_dot[0], x.q_WB.x() + h * dx.q_dot[1],
                              x.q_WB.y() + h * dx.q_dot[2], x.q_WB.z() + h * dx.q_dot[3]);
  y.w_B = x.w_B + h * dx.w_dot;
  return y;
}

double kineticEnergy(const RigidBodyState& x, const MassProperties& mass) noexcept {
  return 0.5 * mass.mass() * x.v_W.squaredNorm() + 0.5 * x.w_B.dot(mass.inertia() * x.w_B);
}

Eigen::Vector3d angularMomentum_W(const RigidBodyState& x, const MassProperties& mass) noexcept {
  return x.q_WB.normalized() * (mass.inertia() * x.w_B);
}

}  // namespace geaware::sim
