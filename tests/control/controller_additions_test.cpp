// SPDX-License-Identifier: BSD-3-Clause
// geaware's additions to the paper's controller (docs/controller.md): the disturbance observer's
// residual fed forward, the position integral with anti-windup, the clearance guard, and the
// `recommended` configuration's name. Closed forms on the controller alone.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "geaware/control/controller.hpp"
#include "geaware/model/units.hpp"
#include "geaware_test/eigen_matchers.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace {

using namespace geaware::control;
using geaware::model::kGravity;
using geaware_test::paperVehicle;

constexpr double kDt = 1.0 / 200.0;

/// Level hover at height h on the reference, rotor speeds at the hover speed.
ControllerInput hoverInput(double h) {
  ControllerInput in;
  in.reference.p_W = Eigen::Vector3d(0.0, 0.0, h);
  in.estimate.p_W = in.reference.p_W;
  in.accel_B = Eigen::Vector3d(0.0, 0.0, kGravity);
  in.height_m = h;
  in.height_valid = true;
  in.rotor_speeds_rpm.setConstant(paperVehicle().hoverSpeedRpm(h));
  return in;
}

ControllerParams only(AccelerationCompensation acc) {
  ControllerParams p;
  p.acceleration = acc;
  p.torque = TorqueCompensation::kNone;
  return p;
}

TEST(ControllerDisturbanceFeedForward, ConvergesToAConstantDisturbanceWithItsTimeConstant) {
  // A step of ã_ext to a constant d far from the ground (F_G(100 m) ≈ 7e-7, at rest no drag):
  // the residual fed forward is the backward-Euler low-pass of the step,
  // r_k = d·(1 − (τ/(τ + Δt))^k), and the acceleration command takes it off: a_des = −r_k.
  ControllerParams p = only(AccelerationCompensation::kModel);
  p.dob_time_constant_s = 0.1;
  Controller c(paperVehicle(), p);
  const Eigen::Vector3d d(0.3, -0.2, -0.1 * kGravity);
  ControllerInput in = hoverInput(100.0);
  // The filter starts in steady state at its first input (none here), then d steps in.
  in.external_accel_valid = true;
  ASSERT_MATRIX_NEAR(c.update(in).a_dob_W, Eigen::Vector3d::Zero(), 1e-5);
  in.external_accel_W = d;
  const double rho = p.dob_time_constant_s / (p.dob_time_constant_s + kDt);
  for (int k = 1; k <= 200; ++k) {
    const ControllerOutput out = c.update(in);
    const Eigen::Vector3d expected = d * (1.0 - std::pow(rho, k));
    ASSERT_MATRIX_NEAR(out.a_dob_W, expected, 1e-5) << "tick " << k;
    ASSERT_MATRIX_NEAR(out.a_des_W, -expected, 1e-5) << "tick " << k;
    // One time constant (20 ticks): 1 − (1 + Δt/τ)^−20 = 0.623 of d (continuous: 1 − 1/e).
    if (k == 20) {
      EXPECT_NEAR(out.a_dob_W.z() / d.z(), 0.623, 0.001);
    }
  }
  // Without an estimate the residual is held, not decayed.
  in.external_accel_valid = false;
  const ControllerOutput held = c.update(in);
  EXPECT_MATRIX_NEAR(held.a_dob_W, d * (1.0 - std::pow(rho, 200)), 1e-5);
}

// Standing on the gear, the feet carry part of the weight and the observer reads the ground's
// reaction as an upward disturbance: nothing is fed forward until a valid height more than 1 cm
// above the gear's says the vehicle is airborne; from then on, also back down on the gear (a
// landing keeps its feed-forward), the filter runs from its first airborne input.
TEST(ControllerDisturbanceFeedForward, WaitsForTheLiftOffAndThenStaysOn) {
  ControllerParams p = only(AccelerationCompensation::kModel);
  p.dob_time_constant_s = 0.1;
  Controller c(paperVehicle(), p);
  const double gear = paperVehicle().params().min_rotor_plane_height_m;
  const Eigen::Vector3d d(0.0, 0.0, 2.0);  // the ground pushing up
  ControllerInput in = hoverInput(gear);
  in.external_accel_valid = true;
  in.external_accel_W = d;
  for (double h : {gear, gear + 0.005, gear + 0.0099}) {
    in.height_m = h;
    in.reference.p_W.z() = in.estimate.p_W.z() = h;
    for (int k = 0; k < 20; ++k) ASSERT_EQ(c.update(in).a_dob_W, Eigen::Vector3d::Zero()) << "h " << h;
  }
  in.height_m = gear + 0.05;  // airborne: the filter starts at its first input
  in.external_accel_W = Eigen::Vector3d(0.1, 0.0, 0.0);
  EXPECT_GT(c.update(in).a_dob_W.x(), 0.09);
  in.height_m = gear;  // back on the gear (a landing): still fed forward
  EXPECT_GT(c.update(in).a_dob_W.x(), 0.09);
  // A reset (a new flight) waits for the lift-off again.
  c.reset();
  EXPECT_EQ(c.update(in).a_dob_W, Eigen::Vector3d::Zero());
  // Only a valid height near the gear's withholds it: without a ranger height (out of range,
  // high up) the feed-forward works as ever.
  Controller high(paperVehicle(), p);
  in.height_valid = false;
  EXPECT_GT(high.update(in).a_dob_W.x(), 0.09);
}

TEST(ControllerDisturbanceFeedForward, FeedsForwardOnlyWhatTheModelDoesNotExplain) {
  // At 0.12 m the observer sees the ground's extra thrust F_G·T/m; the model explains it, so the
  // residual is zero and the command is the paper's.
  ControllerParams p = only(AccelerationCompensation::kModel);
  ControllerParams with = p;
  with.dob_time_constant_s = 0.1;
  Controller paper(paperVehicle(), p);
  Controller dob(paperVehicle(), with);
  const double h = 0.12;
  ControllerInput in = hoverInput(h);
  const auto& ge = paperVehicle().groundEffect();
  const double f_g = ge.thrustRatio(h);
  in.external_accel_W = Eigen::Vector3d(0.0, 0.0, kGravity * f_g / (1.0 + f_g));
  in.external_accel_valid = true;
  ControllerOutput a, b;
  for (int k = 0; k < 100; ++k) {
    a = paper.update(in);
    b = dob.update(in);
  }
  EXPECT_MATRIX_NEAR(b.a_dob_W, Eigen::Vector3d::Zero(), 1e-6);
  EXPECT_NEAR(b.thrust_des_N, a.thrust_des_N, 1e-5);
}

TEST(ControllerIntegral, IsBoundedUnderSaturationAndUnwindsInBoundedTime) {
  ControllerParams p = only(AccelerationCompensation::kNone);
  p.k_i_per_s3 = Eigen::Vector3d::Constant(1.0);
  p.integral_limit_mps2 = 1.0;
  Controller c(paperVehicle(), p);
  // 5 m behind in x (the tilt limit cuts the command) and 2 m low, for 10 s.
  ControllerInput in = hoverInput(2.0);
  in.reference.p_W += Eigen::Vector3d(5.0, 0.0, 2.0);
  bool tilt_limited = false;
  bool held = false;
  for (int k = 0; k < 2000; ++k) {
    const ControllerOutput out = c.update(in);
    tilt_limited |= (out.flags & kFlagTiltLimited) != 0;
    held |= (out.flags & kFlagIntegralHeld) != 0;
    ASSERT_LE(out.a_int_W.cwiseAbs().maxCoeff(), p.integral_limit_mps2 + 1e-12) << "tick " << k;
    // x: held while the tilt limit acts (it grew on the first tick only).
    ASSERT_LE(out.a_int_W.x(), 2.0 * p.k_i_per_s3.x() * 5.0 * kDt) << "tick " << k;
  }
  EXPECT_TRUE(tilt_limited);
  EXPECT_TRUE(held);
  // z wound up to its bound; the error reversed, it unwinds at K^I·|e| per second: from 1 m/s²
  // with e = −2 m it crosses zero within 0.5 s (+ one tick).
  ControllerOutput out = c.update(in);
  ASSERT_NEAR(out.a_int_W.z(), p.integral_limit_mps2, 1e-12);
  in.reference.p_W = in.estimate.p_W - Eigen::Vector3d(0.0, 0.0, 2.0);
  int ticks = 0;
  while (out.a_int_W.z() > 0.0 && ticks < 1000) {
    out = c.update(in);
    ++ticks;
  }
  EXPECT_LE(ticks, 101);
}

/// Guard-only controller: no feed-forward, so a_des is the guarded feedback command itself.
Controller guardOnly() {
  ControllerParams p = only(AccelerationCompensation::kNone);
  p.clearance_guard = true;
  p.guard_margin_m = 0.01;
  p.guard_brake_mps2 = 2.0;
  p.guard_reaction_time_s = 0.05;
  p.guard_rate_per_s = 4.0;
  return Controller(paperVehicle(), p);
}

TEST(ControllerClearanceGuard, TheCommandNeverGoesBelowTheClearance) {
  const double h_min = paperVehicle().params().min_rotor_plane_height_m + 0.01;
  const double a_b = 2.0, t_r = 0.05, gamma = 4.0;
  // A reference 1 m under the ground, diving: from every state the commanded height is the
  // floor, and while sinking the vertical command respects the braking barrier's bound.
  for (double h : {0.06, 0.082, 0.1, 0.2, 0.5}) {
    for (double v : {-2.0, -0.5, -0.05, 0.0, 0.5}) {
      Controller c = guardOnly();
      ControllerInput in = hoverInput(h);
      in.estimate.v_W.z() = v;
      in.reference.p_W.z() = -1.0;
      in.reference.v_W.z() = -3.0;
      in.reference.a_W.z() = -5.0;
      const ControllerOutput out = c.update(in);
      SCOPED_TRACE("h = " + std::to_string(h) + " m, v = " + std::to_string(v) + " m/s");
      EXPECT_NEAR(out.z_cmd_m, h_min, 1e-12);
      EXPECT_TRUE(out.flags & kFlagClearanceGuard);
      if (v < 0.0) {
        const double psi = (h - h_min) + v * t_r - v * v / (2.0 * a_b);
        const double bound = std::min((-v - gamma * psi) / (t_r - v / a_b), a_b);
        EXPECT_NEAR(out.guard_min_accel_z_mps2, bound, 1e-9);
        EXPECT_GE(out.a_des_W.z(), bound - 1e-12);
        // Outside the safe set (the floor cannot be kept after t_r braking at a_b): the
        // command brakes (ψ̇ ≥ γ·|ψ| > 0).
        if (psi <= 0.0) {
          EXPECT_GT(out.a_des_W.z(), 0.0);
        }
      } else {
        EXPECT_EQ(out.guard_min_accel_z_mps2, -std::numeric_limits<double>::infinity());
      }
    }
  }
}

TEST(ControllerClearanceGuard, KeepsAPointMassThatFollowsItsCommandAboveTheClearance) {
  // The invariance argument on a point mass that follows the vertical command exactly
  // (ḧ = a_des,z): started inside the safe set, 0.7 m high and sinking at 1.2 m/s
  // (ψ = 0.618 − 0.06 − 1.44/4 = 0.20 m), towards a reference 1 m under the ground: h never
  // goes below h_min, and the descent is stopped at it.
  const double h_min = paperVehicle().params().min_rotor_plane_height_m + 0.01;
  Controller c = guardOnly();
  double h = 0.7;
  double v = -1.2;
  double lowest = h;
  for (int k = 0; k < 1000; ++k) {
    ControllerInput in = hoverInput(h);
    in.estimate.v_W.z() = v;
    in.reference.p_W.z() = -1.0;
    const ControllerOutput out = c.update(in);
    const double acc = out.a_des_W.z();
    h += v * kDt + 0.5 * acc * kDt * kDt;
    v += acc * kDt;
    lowest = std::min(lowest, h);
  }
  EXPECT_GE(lowest, h_min - 1e-3);
  EXPECT_NEAR(h, h_min, 1e-3);
}

TEST(ControllerClearanceGuard, StaysOutOfTheWayOfOrdinaryErrorsAtTheReference) {
  // At a 0.12 m reference (3.8 cm above the floor h_min = 8.2 cm): 0.7 cm low sinking at
  // 9.4 cm/s, or 2 cm low sinking at 5 cm/s, the floor can be kept braking well below a_b
  // (ψ = 2.4 cm, 1.5 cm): the guard does nothing.
  for (const auto& [h, v] : {std::pair{0.113, -0.094}, std::pair{0.10, -0.05}, std::pair{0.12, 0.0}}) {
    Controller c = guardOnly();
    ControllerInput in = hoverInput(h);
    in.reference.p_W.z() = 0.12;
    in.estimate.v_W.z() = v;
    const ControllerOutput out = c.update(in);
    SCOPED_TRACE("h = " + std::to_string(h) + " m, v = " + std::to_string(v) + " m/s");
    EXPECT_FALSE(out.flags & kFlagClearanceGuard);
    EXPECT_NEAR(out.z_cmd_m, 0.12, 1e-15);
    EXPECT_LT(out.guard_min_accel_z_mps2, out.a_des_W.z());
  }
}

TEST(ControllerClearanceGuard, ATiltedVehicleKeepsItsLowestFootAboveTheFloor) {
  // A tilt θ lowers a foot by up to arm·sin θ (arm = b/2): the floor rises by it. At 0.10 m
  // sinking at 5 cm/s the level vehicle is left alone (ψ = 1.5 cm); tilted by 8° its lowest
  // foot is 2.4 cm lower, ψ < 0, and the guard brakes by the barrier's bound for the raised floor.
  const auto& p = paperVehicle().params();
  const double tilt = 8.0 * std::acos(-1.0) / 180.0;
  const double h_min_level = p.min_rotor_plane_height_m + 0.01;
  const double h_min = h_min_level + 0.5 * p.diagonal_rotor_distance_m * std::sin(tilt);
  const double h = 0.10, v = -0.05, a_b = 2.0, t_r = 0.05, gamma = 4.0;
  Controller level = guardOnly();
  ControllerInput in = hoverInput(h);
  in.reference.p_W.z() = 0.09;  // between the level and the tilted floor
  in.estimate.v_W.z() = v;
  const ControllerOutput out_level = level.update(in);
  ASSERT_LT(h_min_level, 0.09);
  EXPECT_NEAR(out_level.z_cmd_m, 0.09, 1e-12);  // level: the reference stands
  Controller tilted = guardOnly();
  in.estimate.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()));
  const ControllerOutput out = tilted.update(in);
  EXPECT_TRUE(out.flags & kFlagClearanceGuard);
  EXPECT_NEAR(out.z_cmd_m, h_min, 1e-9);  // the reference raised to the tilted floor
  const double psi = (h - h_min) + v * t_r - v * v / (2.0 * a_b);
  ASSERT_LT(psi, 0.0);
  const double bound = std::min((-v - gamma * psi) / (t_r - v / a_b), a_b);
  EXPECT_NEAR(out.guard_min_accel_z_mps2, bound, 1e-9);
  EXPECT_GT(out.guard_min_accel_z_mps2, out_level.guard_min_accel_z_mps2);
}

TEST(RecommendedConfiguration, IsModelModelIndiWithTheAdditionsAndParsesByName) {
  const ControllerParams r = recommendedControllerParams();
  EXPECT_EQ(r.acceleration, AccelerationCompensation::kModel);
  EXPECT_EQ(r.torque, TorqueCompensation::kModelIndi);
  EXPECT_TRUE(r.hasAdditions());
  EXPECT_TRUE(r.validate().empty());
  EXPECT_EQ(configurationName(r), "recommended");
  ControllerParams p;
  ASSERT_TRUE(parseConfiguration("recommended", p));
  EXPECT_EQ(configurationName(p), "recommended");
  EXPECT_EQ(p.dob_time_constant_s, r.dob_time_constant_s);
  // An ACC:TORQUE pair is the paper's row: no additions.
  ASSERT_TRUE(parseConfiguration("model:model_indi", p));
  EXPECT_FALSE(p.hasAdditions());
  EXPECT_EQ(configurationName(p), "model:model_indi");
  p.clearance_guard = true;
  EXPECT_EQ(configurationName(p), "model:model_indi+guard");
  EXPECT_FALSE(parseConfiguration("recommend", p));
  EXPECT_FALSE(parseConfiguration("model", p));
}

TEST(RecommendedConfiguration, ValidateNamesTheAdditionsOutOfRange) {
  ControllerParams p = recommendedControllerParams();
  p.k_i_per_s3.x() = 8.0;  // K^P·K^V = 7.5: the third-order loop would be unstable
  p.guard_rate_per_s = 0.0;
  p.dob_limit_mps2 = -1.0;
  const auto errors = p.validate();
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_EQ(errors[0].field, "dob_limit_mps2");
  EXPECT_EQ(errors[1].field, "k_i_per_s3.x");
  EXPECT_NE(errors[1].expected.find("Routh"), std::string::npos);
  EXPECT_EQ(errors[2].field, "guard_rate_per_s");
  ControllerParams indi = recommendedControllerParams();
  indi.acceleration = AccelerationCompensation::kIndi;
  const auto e2 = indi.validate();
  ASSERT_EQ(e2.size(), 1u);
  EXPECT_EQ(e2[0].field, "dob_time_constant_s");
}

}  // namespace
