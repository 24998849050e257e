// SPDX-License-Identifier: BSD-3-Clause
// Motor model and the ESC throttle curve (docs/paper-facts.md, supplementary section 3).
#include "geaware/model/motor.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "geaware/model/units.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace {

using geaware::model::ThrottleCurve;

TEST(ThrottleCurve, ReproducesTheThrottleFigure) {
  const ThrottleCurve curve(geaware_test::paperParams().throttle);
  // docs/paper-facts.md, off id_single_motor.PNG: ~3,300 rpm at 0, 10,300 at 0.2, 15,000 at 0.5,
  // 19,700 at full throttle; the corrected c0 reproduces them within 3 %. With the printed
  // (typo) c0 = 1.033111e8 the zero-throttle speed would be ~10,200 rpm and this fails.
  EXPECT_NEAR(curve.speedRpm(0.0), 3300.0, 0.03 * 3300.0);
  EXPECT_NEAR(curve.speedRpm(0.2), 10300.0, 0.03 * 10300.0);
  EXPECT_NEAR(curve.speedRpm(0.5), 15000.0, 0.03 * 15000.0);
  EXPECT_NEAR(curve.speedRpm(1.0), 19700.0, 0.03 * 19700.0);
  EXPECT_DOUBLE_EQ(curve.minSpeedRpm(), curve.speedRpm(0.0));
  EXPECT_DOUBLE_EQ(curve.maxSpeedRpm(), curve.speedRpm(1.0));
}

TEST(ThrottleCurve, InverseIsIdentityOnItsRange) {
  const ThrottleCurve curve(geaware_test::paperParams().throttle);
  for (double t = 0.0; t <= 1.0; t += 0.01) {
    EXPECT_NEAR(curve.throttle(curve.speedRpm(t)), t, 1e-12) << "t = " << t;
  }
  for (double n = curve.minSpeedRpm(); n <= curve.maxSpeedRpm(); n += 137.0) {
    EXPECT_NEAR(curve.speedRpm(curve.throttle(n)), n, 1e-8 * n) << "n = " << n;
  }
}

TEST(ThrottleCurve, ClampsOutsideItsRange) {
  const ThrottleCurve curve(geaware_test::paperParams().throttle);
  EXPECT_DOUBLE_EQ(curve.throttle(0.0), 0.0);
  EXPECT_DOUBLE_EQ(curve.throttle(1e6), 1.0);
  EXPECT_DOUBLE_EQ(curve.speedRpm(-0.5), curve.minSpeedRpm());
  EXPECT_DOUBLE_EQ(curve.speedRpm(1.5), curve.maxSpeedRpm());
}

TEST(ThrottleCurve, LinearCurveInvertsExactly) {
  // c2 = 0 is the degenerate case of the quadratic formula; the stable form handles it.
  const ThrottleCurve curve({0.0, 4e8, 1e6});
  EXPECT_NEAR(curve.throttle(std::sqrt(1e6 + 0.25 * 4e8)), 0.25, 1e-14);
}

TEST(Motor, ThrustAndReactionTorque) {
  const auto& r = geaware_test::paperParams().rotor;
  EXPECT_NEAR(geaware::model::rotorThrust(r, 10000.0), r.k_T_N_per_rpm2 * 1e8, 1e-15);
  // Hover check of docs/paper-facts.md: 16.64 N over 4 rotors needs ≈ 10,200 rpm with k_T = 4.0e-8.
  EXPECT_NEAR(std::sqrt(16.64 / 4.0 / r.k_T_N_per_rpm2), 10190.0, 30.0);
  // Steady: k_I·n²; accelerating at 1000 rpm/s adds J_R·(1000·2π/60) N·m.
  EXPECT_NEAR(geaware::model::rotorReactionTorque(r, 10000.0, 0.0), r.k_I_Nm_per_rpm2 * 1e8, 1e-15);
  EXPECT_NEAR(geaware::model::rotorReactionTorque(r, 10000.0, 1000.0) -
                  geaware::model::rotorReactionTorque(r, 10000.0, 0.0),
              r.J_R_kgm2 * 1000.0 * 2.0 * M_PI / 60.0, 1e-15);
}

TEST(VehicleModel, HoverSpeedFallsNearTheGround) {
  const auto& v = geaware_test::paperVehicle();
  const auto& p = v.params();
  for (double h : {0.072, 0.1, 0.2, 0.5, 2.0}) {
    const double n = v.hoverSpeedRpm(h);
    // Thrust with ground effect balances gravity: 4·k_T·n²·(1 + F_G) = m·g.
    EXPECT_NEAR(4.0 * p.rotor.k_T_N_per_rpm2 * n * n * (1.0 + v.groundEffect().thrustRatio(h)),
                p.mass_kg * geaware::model::kGravity, 1e-9);
  }
  EXPECT_LT(v.hoverSpeedRpm(0.1), v.hoverSpeedRpm(0.5));
  EXPECT_NEAR(v.hoverSpeedRpm(5.0), 10190.0, 50.0);
}

}  // namespace

// The battery-voltage dependence n(t, V) = n(t)·(V/V_ref)^p (model/vehicle_params.hpp).
TEST(ThrottleCurve, VoltageDependenceIsExactAtTheReferenceAndWithoutAMeasurement) {
  auto p = geaware_test::paperParams().throttle;
  const ThrottleCurve plain(p);
  p.reference_voltage_V = 16.0;
  p.voltage_exponent = 1.0;
  const ThrottleCurve curve(p);
  for (double n : {3500.0, 9000.0, 10187.0, 15350.0, 19000.0}) {
    EXPECT_EQ(curve.throttle(n, 16.0), plain.throttle(n));  // bit for bit at V_ref
    EXPECT_EQ(curve.throttle(n, std::nan("")), plain.throttle(n));  // not measured
    EXPECT_EQ(curve.throttle(n, 0.0), plain.throttle(n));
    EXPECT_EQ(plain.throttle(n, 14.0), plain.throttle(n));  // no dependence in the file
  }
  EXPECT_EQ(curve.voltageScale(std::numeric_limits<double>::infinity()), 1.0);
}

TEST(ThrottleCurve, VoltageDependenceScalesTheSpeedAndItsInverseUndoesIt) {
  auto p = geaware_test::paperParams().throttle;
  p.reference_voltage_V = 16.0;
  p.voltage_exponent = 1.3;
  const ThrottleCurve curve(p);
  EXPECT_NEAR(curve.voltageScale(14.0), std::pow(14.0 / 16.0, 1.3), 1e-15);
  EXPECT_DOUBLE_EQ(curve.speedRpm(0.4, 14.0), curve.speedRpm(0.4) * std::pow(14.0 / 16.0, 1.3));
  for (double t : {0.1, 0.3, 0.5, 0.8}) {
    for (double v : {13.0, 14.8, 16.8}) EXPECT_NEAR(curve.throttle(curve.speedRpm(t, v), v), t, 1e-12);
  }
  // A low battery needs more throttle for the same speed; an absurd reading is held to 0.5·V_ref.
  EXPECT_GT(curve.throttle(10000.0, 14.0), curve.throttle(10000.0, 16.0));
  EXPECT_EQ(curve.voltageScale(1.0), std::pow(0.5, 1.3));
}
