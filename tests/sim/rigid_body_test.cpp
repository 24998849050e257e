// SPDX-License-Identifier: BSD-3-Clause
// Closed-form checks of the rigid body and its RK4 integrator.
#include "geaware/sim/rigid_body.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "geaware_test/eigen_matchers.hpp"

namespace geaware::sim {
namespace {

TEST(RigidBody, Rk4IntegratesConstantAccelerationExactly) {
  // The solution p = p0 + v0·t + ½·a·t² is a polynomial of degree 2: RK4 is exact for it, so
  // only round-off remains (large steps on purpose).
  const Eigen::Vector3d a(0.3, -1.2, -9.81);
  RigidBodyState x;
  x.p_W = Eigen::Vector3d(1.0, 2.0, 3.0);
  x.v_W = Eigen::Vector3d(-0.5, 0.25, 4.0);
  const auto f = [&](double, const RigidBodyState& s) {
    RigidBodyDerivative d;
    d.p_dot = s.v_W;
    d.v_dot = a;
    return d;
  };
  const double dt = 0.25;
  double t = 0.0;
  for (int k = 0; k < 8; ++k, t += dt) x = rk4Step(x, t, dt, f);
  const Eigen::Vector3d p_exact =
      Eigen::Vector3d(1.0, 2.0, 3.0) + Eigen::Vector3d(-0.5, 0.25, 4.0) * t + 0.5 * a * t * t;
  EXPECT_MATRIX_NEAR(x.p_W, p_exact, 1e-12);
  EXPECT_MATRIX_NEAR(x.v_W, Eigen::Vector3d(Eigen::Vector3d(-0.5, 0.25, 4.0) + a * t), 1e-12);
}

TEST(RigidBody, Rk4PassesStageTimes) {
  // The callable sees t, t + dt/2 (twice) and t + dt: a time-dependent acceleration a = t
  // integrates exactly (v = t²/2, p = t³/6 are polynomials of degree ≤ 4).
  RigidBodyState x;
  const auto f = [](double t, const RigidBodyState& s) {
    RigidBodyDerivative d;
    d.p_dot = s.v_W;
    d.v_dot = Eigen::Vector3d(t, 0.0, 0.0);
    return d;
  };
  double t = 0.0;
  for (int k = 0; k < 10; ++k, t += 0.1) x = rk4Step(x, t, 0.1, f);
  EXPECT_NEAR(x.v_W.x(), t * t / 2.0, 1e-13);
  EXPECT_NEAR(x.p_W.x(), t * t * t / 6.0, 1e-13);
}

TEST(RigidBody, TorqueFreeSpinConservesMomentumAndEnergy) {
  // An asymmetric body spinning near its intermediate axis (a tumbling, strongly non-linear
  // motion). Without torque, the world-frame angular momentum and the kinetic energy are
  // invariants. RK4's local error is O(dt⁵); at dt = 1 ms and |ω| ≈ 5 rad/s the drift over
  // 10 s is far below 1e-9 relative, the quaternion renormalisation adds only round-off.
  const MassProperties mass(1.7, Eigen::Vector3d(0.0075, 0.0079, 0.0125).asDiagonal());
  RigidBodyState x;
  x.w_B = Eigen::Vector3d(0.05, 5.0, 0.1);
  x.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  const Eigen::Vector3d L0 = angularMomentum_W(x, mass);
  const double E0 = kineticEnergy(x, mass);
  const auto f = [&](double, const RigidBodyState& s) {
    return rigidBodyDerivative(s, Wrench{}, mass);
  };
  const double dt = 1e-3;
  Eigen::Vector3d w_min = x.w_B;
  for (int k = 0; k < 10000; ++k) {
    x = rk4Step(x, k * dt, dt, f);
    w_min = w_min.cwiseMin(x.w_B);
  }
  EXPECT_LT(w_min.y(), 0.0)
      << "the intermediate-axis spin should have flipped (the test exercises tumbling)";
  EXPECT_MATRIX_NEAR(angularMomentum_W(x, mass), L0, 1e-9 * L0.norm());
  EXPECT_NEAR(kineticEnergy(x, mass), E0, 1e-9 * E0);
  EXPECT_NEAR(x.q_WB.norm(), 1.0, 1e-15);
}

TEST(RigidBody, ForceIsAppliedInTheBodyFrame) {
  // A body rolled by 90° about x: a body-y force points along world z.
  const MassProperties mass(2.0, Eigen::Matrix3d::Identity() * 0.01);
  RigidBodyState x;
  x.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(std::numbers::pi / 2.0, Eigen::Vector3d::UnitX()));
  Wrench w;
  w.force_B = Eigen::Vector3d(0.0, 4.0, 0.0);
  w.torque_B = Eigen::Vector3d(0.0, 0.0, 0.02);
  const RigidBodyDerivative d = rigidBodyDerivative(x, w, mass);
  EXPECT_MATRIX_NEAR(d.v_dot, Eigen::Vector3d(0.0, 0.0, 2.0), 1e-15);
  EXPECT_MATRIX_NEAR(d.w_dot, Eigen::Vector3d(0.0, 0.0, 2.0), 1e-15);
}

TEST(RigidBody, GyroscopicCouplingOfTheEulerEquation) {
  // ω̇ = J⁻¹(τ − ω × Jω): for ω = (1, 1, 0) and J = diag(1, 2, 3), ω × Jω = (0, 0, 1).
  const MassProperties mass(1.0, Eigen::Vector3d(1.0, 2.0, 3.0).asDiagonal());
  RigidBodyState x;
  x.w_B = Eigen::Vector3d(1.0, 1.0, 0.0);
  const RigidBodyDerivative d = rigidBodyDerivative(x, Wrench{}, mass);
  EXPECT_MATRIX_NEAR(d.w_dot, Eigen::Vector3d(0.0, 0.0, -1.0 / 3.0), 1e-15);
}

TEST(RigidBody, RotationOfAnUnnormalisedQuaternion) {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -2.0, 0.7).normalized()));
  const Eigen::Quaterniond scaled(1.7 * q.w(), 1.7 * q.x(), 1.7 * q.y(), 1.7 * q.z());
  EXPECT_MATRIX_NEAR(rotationOf(scaled), q.toRotationMatrix(), 1e-15);
  EXPECT_MATRIX_NEAR(rotationOf(q), q.toRotationMatrix(), 1e-15);
}

TEST(RigidBody, RejectsInvalidMassProperties) {
  EXPECT_THROW(MassProperties(0.0, Eigen::Matrix3d::Identity()), std::invalid_argument);
  EXPECT_THROW(MassProperties(1.0, -Eigen::Matrix3d::Identity()), std::invalid_argument);
  Eigen::Matrix3d asym = Eigen::Matrix3d::Identity();
  asym(0, 1) = 0.1;
  EXPECT_THROW(MassProperties(1.0, asym), std::invalid_argument);
}

}  // namespace
}  // namespace geaware::sim
