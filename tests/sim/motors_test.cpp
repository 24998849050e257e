// SPDX-License-Identifier: BSD-3-Clause
// Motors, ESC curve and battery against closed forms.
#include "geaware/sim/motors.hpp"

#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "geaware/model/motor.hpp"
#include "geaware/model/units.hpp"
#include "geaware_test/eigen_matchers.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace geaware::sim {
namespace {

TruthParams noBattery() {
  TruthParams p = fromNominal(geaware_test::paperParams());
  p.battery.enabled = false;
  return p;
}

TEST(Motors, FirstOrderStepResponseIsExact) {
  // n(t) = n_ss + (n0 − n_ss)·e^(−t/τ) at every step, whatever the step length (the exact
  // discretisation), up to round-off.
  const TruthParams p = noBattery();
  Motors m(p, {5000.0, 5000.0, 5000.0, 5000.0});
  const double throttle = 0.5;
  const double n_ss = model::ThrottleCurve(p.motor.throttle).speedRpm(throttle);
  const double tau = p.motor.time_constant_s;
  double t = 0.0;
  for (int k = 0; k < 100; ++k) {
    const double dt = k % 2 == 0 ? 1e-3 : 2.5e-3;
    m.beginStep({throttle, throttle, throttle, throttle}, dt);
    m.endStep();
    t += dt;
    const double expected = n_ss + (5000.0 - n_ss) * std::exp(-t / tau);
    ASSERT_NEAR(m.speedsRpm()[0], expected, 1e-9 * n_ss) << "t = " << t;
  }
}

TEST(Motors, SpeedsWithinTheStepAndTheirRates) {
  const TruthParams p = noBattery();
  Motors m(p, {8000.0, 9000.0, 10000.0, 11000.0});
  m.beginStep({0.2, 0.4, 0.6, 0.8}, 1e-3);
  std::array<double, 4> n{};
  std::array<double, 4> n_dot{};
  m.speedsAt(0.0, n, n_dot);
  const model::ThrottleCurve curve(p.motor.throttle);
  EXPECT_DOUBLE_EQ(n[2], 10000.0);
  EXPECT_NEAR(n_dot[2], (curve.speedRpm(0.6) - 10000.0) / p.motor.time_constant_s, 1e-6);
  // The rate is the derivative of the exact trajectory: compare with a central difference.
  std::array<double, 4> n_a{};
  std::array<double, 4> n_b{};
  std::array<double, 4> unused{};
  m.speedsAt(0.5e-3 - 1e-7, n_a, unused);
  m.speedsAt(0.5e-3 + 1e-7, n_b, unused);
  m.speedsAt(0.5e-3, n, n_dot);
  EXPECT_NEAR(n_dot[1], (n_b[1] - n_a[1]) / 2e-7, 1e-3 * std::abs(n_dot[1]));
}

TEST(Motors, SpeedLimitsClampTheTarget) {
  TruthParams p = noBattery();
  p.motor.max_speed_rpm = 15000.0;
  p.motor.min_speed_rpm = 4000.0;
  Motors m(p, {0.0, 30000.0, 10000.0, 10000.0});
  EXPECT_DOUBLE_EQ(m.speedsRpm()[0], 4000.0);  // initial speeds clamped too
  EXPECT_DOUBLE_EQ(m.speedsRpm()[1], 15000.0);
  for (int k = 0; k < 2000; ++k) {
    m.beginStep({1.0, 0.0, 2.0, -1.0}, 1e-3);  // out-of-range throttles clamp to [0, 1]
    m.endStep();
  }
  EXPECT_NEAR(m.speedsRpm()[0], 15000.0, 1e-6);
  EXPECT_NEAR(m.speedsRpm()[1], 4000.0, 1e-6);  // the curve gives 3,214 rpm at zero throttle
  EXPECT_NEAR(m.speedsRpm()[2], 15000.0, 1e-6);
  EXPECT_NEAR(m.speedsRpm()[3], 4000.0, 1e-6);
}

TEST(Motors, ReactionTorqueUsesJrTimesSpeedRateInRadians) {
  // Rotor 1 (yaw sign −1, spinning about +z) speeding up at ṅ: the body feels −J_R·ṅ·(2π/60) about
  // z.
  const TruthParams p = noBattery();
  const std::array<double, 4> n{10000.0, 0.0, 0.0, 0.0};
  const std::array<double, 4> n_dot{60000.0, 0.0, 0.0, 0.0};
  const Wrench w =
      motorTorques(p.motor.J_R_kgm2, p.yaw_sign, n, n_dot, Eigen::Vector3d::Zero(), true, false);
  EXPECT_DOUBLE_EQ(p.yaw_sign[0], -1.0);
  EXPECT_NEAR(w.torque_B.z(), -p.motor.J_R_kgm2 * 60000.0 * model::kRpmToRadPerSec, 1e-15);
  EXPECT_MATRIX_NEAR(w.force_B, Eigen::Vector3d::Zero(), 0.0);
  // Consistent with the model's single-rotor torque M = k_I·n² + J_R·ṅ (its J_R part).
  model::RotorParams rp;
  rp.J_R_kgm2 = p.motor.J_R_kgm2;
  EXPECT_NEAR(-w.torque_B.z(), model::rotorReactionTorque(rp, 0.0, 60000.0), 1e-15);
}

TEST(Motors, GyroscopicTorqueOfTheSpinningRotors) {
  const TruthParams p = noBattery();
  const Eigen::Vector3d w_B(0.5, -0.2, 3.0);
  // Equal speeds: two rotors each way, the angular momenta cancel.
  const std::array<double, 4> equal{10000.0, 10000.0, 10000.0, 10000.0};
  const std::array<double, 4> zero{};
  EXPECT_MATRIX_NEAR(
      motorTorques(p.motor.J_R_kgm2, p.yaw_sign, equal, zero, w_B, true, true).torque_B,
      Eigen::Vector3d::Zero(), 1e-15);
  // Rotor 1 alone: h = J_R·Ω·z_B (it spins about +z), τ = −ω × h·z_B = h·(−ω_y, ω_x, 0).
  const std::array<double, 4> one{12000.0, 0.0, 0.0, 0.0};
  const double h = p.motor.J_R_kgm2 * 12000.0 * model::kRpmToRadPerSec;
  const Eigen::Vector3d expected = -w_B.cross(Eigen::Vector3d(0.0, 0.0, h));
  EXPECT_MATRIX_NEAR(
      motorTorques(p.motor.J_R_kgm2, p.yaw_sign, one, zero, w_B, false, true).torque_B, expected,
      1e-15);
  EXPECT_MATRIX_NEAR(expected, Eigen::Vector3d(-h * w_B.y(), h * w_B.x(), 0.0), 1e-15);
}

TEST(Motors, BatterySagSlowsTheRotors) {
  // With the battery on, the steady speed scales with V/V_nom; drawing current lowers V by
  // R_int·I at once and by the discharge over time.
  const TruthParams p = fromNominal(geaware_test::paperParams());
  Motors m(p, {10000.0, 10000.0, 10000.0, 10000.0});
  const double n_curve = model::ThrottleCurve(p.motor.throttle).speedRpm(0.5);
  m.beginStep({0.5, 0.5, 0.5, 0.5}, 1e-3);
  const double v_start = m.voltageV();
  EXPECT_LT(v_start, p.battery.full_voltage_V - 0.1);  // sag under ~25 A
  EXPECT_GT(m.currentA(), 10.0);
  EXPECT_NEAR(m.steadySpeedRpm(0.5, p.battery.nominal_voltage_V), n_curve, 1e-9);
  EXPECT_NEAR(m.steadySpeedRpm(0.5, 0.9 * p.battery.nominal_voltage_V), 0.9 * n_curve, 1e-9);
  m.endStep();
  // Let the rotors reach their speed (10 τ), then fly 60 s more.
  for (int k = 0; k < 300; ++k) {
    m.beginStep({0.5, 0.5, 0.5, 0.5}, 1e-3);
    m.endStep();
  }
  const double i_start = m.currentA();
  const double q_start = m.chargeUsedAh();
  for (int k = 0; k < 60000; ++k) {
    m.beginStep({0.5, 0.5, 0.5, 0.5}, 1e-3);
    m.endStep();
  }
  // 60 s at ~70 A (four rotors at ~15,000 rpm: 4·k_I·n²·Ω/η ≈ 1.2 kW) draws ≈ 1.2 A·h of the
  // 3 A·h: the open-circuit voltage falls by ≈ 0.4·2.8 V and the rotors lose speed. The current
  // falls a little with the speed (less power) but stays within its first and last values.
  const double drawn = m.chargeUsedAh() - q_start;
  EXPECT_LE(drawn, i_start * 60.0 / 3600.0);
  EXPECT_GE(drawn, m.currentA() * 60.0 / 3600.0);
  EXPECT_GT(drawn, 1.0);
  EXPECT_LT(m.voltageV(), v_start - 0.3);
  EXPECT_NEAR(m.speedsRpm()[0], n_curve * m.voltageV() / p.battery.nominal_voltage_V, 1.0);
}

TEST(Motors, ThrottleForSteadySpeedInvertsTheSaggedCurve) {
  // A battery that does not discharge noticeably (huge capacity), so that only the sag R_int·I
  // remains: the steady speed is then exactly the requested one.
  TruthParams p = fromNominal(geaware_test::paperParams());
  p.battery.capacity_Ah = 1e6;
  Motors m(p, {10200.0, 10200.0, 10200.0, 10200.0});
  const double t = m.throttleForSteadySpeed(10200.0);
  EXPECT_GT(m.voltageV(), 15.0);
  EXPECT_LT(m.voltageV(), p.battery.full_voltage_V - 0.4);  // ~24 A through 25 mΩ
  for (int k = 0; k < 500; ++k) {
    m.beginStep({t, t, t, t}, 1e-3);
    m.endStep();
  }
  EXPECT_NEAR(m.speedsRpm()[3], 10200.0, 0.01);
}

}  // namespace
}  // namespace geaware::sim
