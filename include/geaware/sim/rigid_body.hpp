// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// 6-DoF rigid-body dynamics of the centre of mass and a classic RK4
// integrator that takes the dynamics as a callable (STYLE.md point 7):
//   ṗ = v,   v̇ = R·f_B/m,   q̇ = ½·q ⊗ (0, ω),   ω̇ = J⁻¹·(τ_B − ω × J·ω),
// with f_B the total body-frame force (gravity included, as a contribution) and τ_B the total
// torque about the CoM. The state here is the CoM's; the plant converts to and from the
// geometric centre that PlantState reports.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geaware/sim/wrench.hpp"

namespace geaware::sim {

/// State of the centre of mass.
struct RigidBodyState {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();             ///< CoM position [m]
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();             ///< CoM velocity [m/s]
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();  ///< attitude, body → world
  Eigen::Vector3d w_B = Eigen::Vector3d::Zero();             ///< body rates [rad/s]
};

/// Time derivative of RigidBodyState (the quaternion's as four raw coefficients w, x, y, z).
struct RigidBodyDerivative {
  Eigen::Vector3d p_dot = Eigen::Vector3d::Zero();  ///< [m/s]
  Eigen::Vector3d v_dot = Eigen::Vector3d::Zero();  ///< [m/s²]
  Eigen::Vector4d q_dot = Eigen::Vector4d::Zero();  ///< (ẇ, ẋ, ẏ, ż) [1/s]
  Eigen::Vector3d w_dot = Eigen::Vector3d::Zero();  ///< [rad/s²]
};

/// Mass properties about the CoM, with the inverse inertia precomputed.
class MassProperties {
 public:
  /// Requires mass > 0 and a symmetric positive-definite inertia.
  MassProperties(double mass_kg, const Eigen::Matrix3d& inertia_kgm2);
  [[nodiscard]] double mass() const noexcept { return mass_kg_; }
  [[nodiscard]] double massInverse() const noexcept { return inv_mass_; }
  [[nodiscard]] const Eigen::Matrix3d& inertia() const noexcept { return J_; }
  [[nodiscard]] const Eigen::Matrix3d& inertiaInverse() const noexcept { return J_inv_; }

 private:
  double mass_kg_;
  double inv_mass_;
  Eigen::Matrix3d J_;
  Eigen::Matrix3d J_inv_;
};

/// Newton–Euler derivative of the state under a body-frame wrench (about the CoM). The
/// quaternion is normalised before use so that the stage states of RK4 (slightly off the unit
/// sphere) still give a rotation.
[[nodiscard]] RigidBodyDerivative rigidBodyDerivative(const RigidBodyState& x, const Wrench& wrench,
                                                      const MassProperties& mass) noexcept;

// The three functions below run at every RK4 stage; they are defined here, inline, so that the
// integrator and the plant's dynamics compile into one piece without calls (and without the
// stores and reloads of the stage state a call needs).

/// The same with the rotation matrix of x's normalised quaternion already at hand. Always
/// inlined: GCC 12 otherwise keeps it out of line in the plant's stage evaluation, which then
/// pays a call and a store/reload of the derivative (≈ 3 % of a plant step).
[[nodiscard, gnu::always_inline]] inline RigidBodyDerivative rigidBodyDerivative(
    const RigidBodyState& x, const Eigen::Matrix3d& R_WB, const Wrench& wrench,
    const MassProperties& mass) noexcept {
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

/// The rotation matrix of q/|q| for any non-zero q = (w, v), without normalising q first (one
/// division, no square root): R = I + s·(w·[v]× + [v]×²) with s = 2/|q|².
[[nodiscard]] inline Eigen::Matrix3d rotationOf(const Eigen::Quaterniond& q) noexcept {
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

/// x + h·dx (the quaternion advanced in its coefficients, not renormalised: RK4's stages).
[[nodiscard]] inline RigidBodyState advance(const RigidBodyState& x, const RigidBodyDerivative& dx,
                                            double h) noexcept {
  RigidBodyState y;
  y.p_W = x.p_W + h * dx.p_dot;
  y.v_W = x.v_W + h * dx.v_dot;
  y.q_WB = Eigen::Quaterniond(x.q_WB.w() + h * dx.q_dot[0], x.q_WB.x() + h * dx.q_dot[1],
                              x.q_WB.y() + h * dx.q_dot[2], x.q_WB.z() + h * dx.q_dot[3]);
  y.w_B = x.w_B + h * dx.w_dot;
  return y;
}

/// One classic RK4 step of length dt from time t. `f(t, x) → RigidBodyDerivative` is called at
/// t, t + dt/2 (twice) and t + dt. The quaternion is renormalised at the end. RK4 is exact for
/// dynamics whose solution is a polynomial of degree ≤ 4 in time (e.g. constant acceleration).
template <typename Dynamics>
[[nodiscard]] RigidBodyState rk4Step(const RigidBodyState& x, double t, double dt, Dynamics&& f) {
  const RigidBodyDerivative k1 = f(t, x);
  const RigidBodyDerivative k2 = f(t + 0.5 * dt, advance(x, k1, 0.5 * dt));
  const RigidBodyDerivative k3 = f(t + 0.5 * dt, advance(x, k2, 0.5 * dt));
  const RigidBodyDerivative k4 = f(t + dt, advance(x, k3, dt));
  RigidBodyDerivative sum;
  sum.p_dot = k1.p_dot + 2.0 * k2.p_dot + 2.0 * k3.p_dot + k4.p_dot;
  sum.v_dot = k1.v_dot + 2.0 * k2.v_dot + 2.0 * k3.v_dot + k4.v_dot;
  sum.q_dot = k1.q_dot + 2.0 * k2.q_dot + 2.0 * k3.q_dot + k4.q_dot;
  sum.w_dot = k1.w_dot + 2.0 * k2.w_dot + 2.0 * k3.w_dot + k4.w_dot;
  RigidBodyState out = advance(x, sum, dt / 6.0);
  out.q_WB.normalize();
  return out;
}

/// Kinetic energy ½m·v² + ½ωᵀJω [J] and angular momentum in the world frame R·J·ω [N·m·s]
/// (invariants for the tests).
[[nodiscard]] double kineticEnergy(const RigidBodyState& x, const MassProperties& mass) noexcept;
[[nodiscard]] Eigen::Vector3d angularMomentum_W(const RigidBodyState& x,
                                                const MassProperties& mass) noexcept;

}  // namespace geaware::sim
