// SPDX-License-Identifier: BSD-3-Clause
// The paper's external disturbance observer (eq. 6) and its flight estimate of F_G. Inputs
// are generated from analytic rotational motion through the vehicle's own mixer, so
// "consistent data" means: rotor speeds that produce exactly the torque the motion needs.
#include "geaware/estimation/disturbance_observer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geaware/estimation/eskf.hpp"
#include "geaware/model/rotation.hpp"
#include "geaware/model/units.hpp"
#include "geaware_test/eigen_matchers.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace {

using namespace geaware::estimation;
using Eigen::Quaterniond;
using geaware::model::expMap;
using geaware::model::logMap;
using Eigen::Vector3d;
using Eigen::Vector4d;
using geaware_test::paperVehicle;

constexpr double kG = geaware::model::kGravity;
constexpr double kDt = 0.005;  // 200 Hz

/// Body rates, their derivative and thrust of a smooth manoeuvre (up to ~0.6 rad/s, 1.5 rad/s²).
struct Motion {
  Vector3d w, w_dot;
  double thrust;
};

Motion motionAt(double t) {
  const double m = paperVehicle().params().mass_kg;
  return {Vector3d(0.5 * std::sin(3.0 * t), 0.4 * std::cos(2.0 * t), 0.3 * std::sin(t)),
          Vector3d(1.5 * std::cos(3.0 * t), -0.8 * std::sin(2.0 * t), 0.3 * std::cos(t)),
          m * kG * (1.0 + 0.1 * std::sin(2.0 * t))};
}

/// Rotor speeds [rpm] that produce [T; τ] through the vehicle's mixer.
Vector4d speedsFor(double thrust, const Vector3d& tau) {
  Vector4d w;
  w << thrust, tau;
  return paperVehicle().mixer().squaredSpeeds(w).cwiseSqrt();
}

/// Attitude along the run: a slow analytic rotation (only rotates ã_ext to the world).
Quaterniond attitudeAt(double t) {
  return expMap(Vector3d(0.2 * std::sin(0.5 * t), 0.15 * std::cos(0.4 * t), 0.3 * t));
}

DisturbanceObserverInput inputAt(double t, const Vector3d& force_ext_W, const Vector3d& tau_ext_B) {
  const auto& p = paperVehicle().params();
  const Vector3d& J = p.inertia_kgm2;
  const Motion mo = motionAt(t);
  DisturbanceObserverInput in;
  in.t_s = t;
  in.q_WB = attitudeAt(t);
  in.gyro_B = mo.w;
  // Euler: J·ω̇ + ω×Jω = τ_B + τ_ext, so the rotors supply τ_B = J·ω̇ + ω×Jω − τ_ext.
  const Vector3d tau_B = J.cwiseProduct(mo.w_dot) + mo.w.cross(J.cwiseProduct(mo.w)) - tau_ext_B;
  in.rotor_speeds_rpm = speedsFor(mo.thrust, tau_B);
  // Specific force: rotor thrust along z_B plus the external force, per unit mass.
  in.accel_B =
      Vector3d::UnitZ() * mo.thrust / p.mass_kg + in.q_WB.conjugate() * force_ext_W / p.mass_kg;
  return in;
}

TEST(DisturbanceObserverParams, ValidateNamesOffendingFields) {
  DisturbanceObserverParams p;
  EXPECT_TRUE(p.validate().empty());
  p.filter_cutoff_hz = 150.0;  // above Nyquist at 200 Hz
  const auto e = p.validate();
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].field, "disturbance_observer.filter_cutoff_hz");
  EXPECT_THROW(DisturbanceObserver(paperVehicle(), p), std::invalid_argument);
}

/// Closed form: at rest, level, rotors holding the weight exactly → zero disturbance.
TEST(DisturbanceObserver, HoverGivesZero) {
  DisturbanceObserver obs(paperVehicle(), {});
  const auto& p = paperVehicle().params();
  DisturbanceObserverInput in;
  in.accel_B = {0.0, 0.0, kG};
  in.rotor_speeds_rpm.setConstant(std::sqrt(p.mass_kg * kG / (4.0 * p.rotor.k_T_N_per_rpm2)));
  DisturbanceEstimate d;
  for (int k = 0; k < 10; ++k) {
    in.t_s = k * kDt;
    d = obs.update(in);
  }
  ASSERT_TRUE(d.valid);
  EXPECT_MATRIX_NEAR(d.a_ext_W, Vector3d::Zero(), 1e-12);
  EXPECT_MATRIX_NEAR(d.tau_ext_B, Vector3d::Zero(), 1e-12);
  EXPECT_NEAR(d.thrust_f_N, p.mass_kg * kG, 1e-9);
  EXPECT_TRUE(d.f_g_valid);
  EXPECT_NEAR(d.f_g_ratio, 0.0, 1e-12);
}

/// Consistent data during a manoeuvre: the force part is exactly zero (the filter is linear
/// and sees the same T/m on both sides); the torque part is zero up to the midpoint rule's
/// O(dt²) and the filter not commuting with ω × Jω: below 0.1 % of the torque involved
/// (measured: 2e-5).
TEST(DisturbanceObserver, ConsistentManoeuvreGivesZero) {
  DisturbanceObserver obs(paperVehicle(), {});
  const Vector3d& J = paperVehicle().params().inertia_kgm2;
  double max_tau_ext = 0.0, max_tau = 0.0, max_a = 0.0;
  for (int k = 0; k < 1000; ++k) {
    const double t = k * kDt;
    const DisturbanceEstimate d = obs.update(inputAt(t, Vector3d::Zero(), Vector3d::Zero()));
    if (k < 40) continue;  // filter start-up from a moving state
    ASSERT_TRUE(d.valid);
    max_a = std::max(max_a, d.a_ext_W.norm());
    max_tau_ext = std::max(max_tau_ext, d.tau_ext_B.norm());
    const Motion mo = motionAt(t);
    max_tau = std::max(max_tau, J.cwiseProduct(mo.w_dot).norm());
  }
  EXPECT_LT(max_a, 1e-9);
  EXPECT_LT(max_tau_ext, 1e-3 * max_tau) << "max |τ̃_ext| = " << max_tau_ext << " N·m";
}

/// A constant external force (world frame) and torque (body frame) are recovered during the
/// manoeuvre, to the filter's lag on the force rotating in the body frame (≈ |ω|·7.5 ms:
/// 0.5 %; measured 0.12 %).
TEST(DisturbanceObserver, RecoversConstantExternalForceAndTorque) {
  DisturbanceObserver obs(paperVehicle(), {});
  const double m = paperVehicle().params().mass_kg;
  const Vector3d F(0.8, -0.5, 1.2);         // [N]
  const Vector3d tau(0.02, -0.015, 0.005);  // [N·m]
  for (int k = 0; k < 1000; ++k) {
    const DisturbanceEstimate d = obs.update(inputAt(k * kDt, F, tau));
    if (k < 60) continue;
    ASSERT_TRUE(d.valid);
    EXPECT_MATRIX_NEAR(d.a_ext_W * m, F, 0.005 * F.norm());
    EXPECT_MATRIX_NEAR(d.tau_ext_B, tau, 1e-3 * tau.norm());
  }
}

/// The paper's flight identification of F_G: a slow level descent from 1 m to 0.1 m with the
/// rotors holding the weight, T = m·g/(1 + F_G(h)); F̃_G = m·z_Wᵀ·ã_ext/T̃ returns F_G(h).
TEST(DisturbanceObserver, FlightEstimateRecoversAdditionalThrust) {
  const auto& veh = paperVehicle();
  const auto& p = veh.params();
  DisturbanceObserver obs(veh, {});
  const double speed = 0.09;  // [m/s]
  for (int k = 0; k <= 2000; ++k) {
    const double t = k * kDt;
    const double h = 1.0 - speed * t;
    DisturbanceObserverInput in;
    in.t_s = t;
    in.accel_B = {0.0, 0.0, kG};
    const double thrust = p.mass_kg * kG / (1.0 + veh.groundEffect().thrustRatio(h));
    in.rotor_speeds_rpm.setConstant(std::sqrt(thrust / (4.0 * p.rotor.k_T_N_per_rpm2)));
    const DisturbanceEstimate d = obs.update(in);
    if (k < 20 || k % 100 != 0) continue;
    ASSERT_TRUE(d.f_g_valid);
    // The estimate refers to the middle of the last interval, delayed by the filter (≈ 7.5 ms).
    const double f_true = veh.groundEffect().thrustRatio(h + speed * (0.5 * kDt + 0.0075));
    EXPECT_NEAR(d.f_g_ratio, f_true, 2e-3 * f_true) << "h = " << h;
  }
}

TEST(DisturbanceObserver, RejectsNonFiniteAndBackwardTime) {
  DisturbanceObserver obs(paperVehicle(), {});
  for (int k = 0; k < 10; ++k)
    (void)obs.update(inputAt(k * kDt, Vector3d::Zero(), Vector3d::Zero()));
  const DisturbanceEstimate before =
      obs.update(inputAt(10 * kDt, Vector3d::Zero(), Vector3d::Zero()));
  ASSERT_TRUE(before.valid);

  DisturbanceObserverInput bad = inputAt(11 * kDt, Vector3d::Zero(), Vector3d::Zero());
  bad.gyro_B.x() = std::numeric_limits<double>::quiet_NaN();
  DisturbanceEstimate d = obs.update(bad);
  EXPECT_FALSE(d.valid);
  EXPECT_EQ(obs.lastStatus(), ObserverStatus::kNonFinite);
  EXPECT_TRUE(d.tau_ext_B.allFinite() && d.a_ext_W.allFinite());

  bad = inputAt(11 * kDt, Vector3d::Zero(), Vector3d::Zero());
  bad.rotor_speeds_rpm(2) = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(obs.update(bad).valid);

  EXPECT_FALSE(obs.update(inputAt(5 * kDt, Vector3d::Zero(), Vector3d::Zero())).valid);
  EXPECT_EQ(obs.lastStatus(), ObserverStatus::kTimeNotIncreasing);
  EXPECT_EQ(obs.rejectedSamples(), 3u);

  // The filters were not touched: the next good sample continues smoothly.
  d = obs.update(inputAt(11 * kDt, Vector3d::Zero(), Vector3d::Zero()));
  EXPECT_TRUE(d.valid);
  EXPECT_LT(d.tau_ext_B.norm(), 1e-3);
}

}  // namespace
