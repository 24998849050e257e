// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/traj/hover_descent.hpp"

#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "flat_output_checks.hpp"
#include "geaware_test/eigen_matchers.hpp"

namespace {

using geaware::traj::FlatOutput;
using geaware::traj::HoverDescent;
using geaware::traj::HoverDescentParams;

HoverDescentParams offsetParams() {
  HoverDescentParams p;
  p.position_xy_m = Eigen::Vector2d(0.4, -1.2);
  p.from_height_m = 1.0;
  p.to_height_m = 0.08;
  p.descent_rate_mps = 0.2;
  p.ramp_time_s = 0.8;
  p.hold_start_s = 1.0;
  p.hold_end_s = 3.0;
  p.yaw_rad = -0.3;
  return p;
}

TEST(HoverDescent, DefaultsAreValidAndGiveTheExpectedDuration) {
  const HoverDescentParams p;
  EXPECT_TRUE(p.validate().empty());
  EXPECT_EQ(p.from_height_m, 1.5);
  EXPECT_EQ(p.to_height_m, 0.1);
  EXPECT_EQ(p.descent_rate_mps, 0.1);
  const HoverDescent traj(p);
  // holds + (from − to)/rate + T_r (the ramps cost T_r in total at the same distance).
  EXPECT_NEAR(traj.duration(), 2.0 + 1.4 / 0.1 + 1.0 + 2.0, 1e-12);
}

TEST(HoverDescent, HoldsThenDescendsThenHolds) {
  const HoverDescentParams p = offsetParams();
  const HoverDescent traj(p);
  const Eigen::Vector3d top(0.4, -1.2, 1.0);
  const Eigen::Vector3d bottom(0.4, -1.2, 0.08);
  const double descent_end = p.hold_start_s + traj.descent().duration();
  for (double t : {-1.0, 0.0, 0.5, p.hold_start_s}) {
    const FlatOutput o = traj.sample(t);
    EXPECT_MATRIX_NEAR(o.p_W, top, 0.0) << "t = " << t;
    EXPECT_MATRIX_NEAR(o.v_W, Eigen::Vector3d::Zero(), 0.0) << "t = " << t;
    EXPECT_MATRIX_NEAR(o.s_W, Eigen::Vector3d::Zero(), 0.0) << "t = " << t;
  }
  for (double t : {descent_end, descent_end + 1.0, traj.duration(), traj.duration() + 5.0}) {
    const FlatOutput o = traj.sample(t);
    EXPECT_MATRIX_NEAR(o.p_W, bottom, 1e-15) << "t = " << t;
    EXPECT_MATRIX_NEAR(o.v_W, Eigen::Vector3d::Zero(), 0.0) << "t = " << t;
    EXPECT_MATRIX_NEAR(o.a_W, Eigen::Vector3d::Zero(), 0.0) << "t = " << t;
  }
  // Between the ramps the vertical speed is the requested rate, downwards, and the height
  // falls linearly.
  const double cruise_start = p.hold_start_s + p.ramp_time_s;
  for (double t = cruise_start; t <= descent_end - p.ramp_time_s; t += 0.1) {
    const FlatOutput o = traj.sample(t);
    EXPECT_NEAR(o.v_W.z(), -0.2, 1e-12) << "t = " << t;
    EXPECT_NEAR(o.a_W.z(), 0.0, 1e-12) << "t = " << t;
    EXPECT_NEAR(o.p_W.z(), 1.0 - 0.2 * (0.5 * p.ramp_time_s + (t - cruise_start)), 1e-12);
  }
}

TEST(HoverDescent, MovesOnlyVerticallyAndNeverOvershoots) {
  const HoverDescentParams p = offsetParams();
  const HoverDescent traj(p);
  double previous_z = INFINITY;
  for (double t = -0.5; t <= traj.duration() + 0.5; t += 0.01) {
    const FlatOutput o = traj.sample(t);
    EXPECT_EQ(o.p_W.head<2>(), p.position_xy_m) << "t = " << t;
    EXPECT_EQ(o.v_W.head<2>(), Eigen::Vector2d::Zero()) << "t = " << t;
    EXPECT_EQ(o.s_W.head<2>(), Eigen::Vector2d::Zero()) << "t = " << t;
    EXPECT_EQ(o.yaw_rad, p.yaw_rad);
    EXPECT_LE(o.v_W.z(), 0.0) << "t = " << t;
    EXPECT_GE(o.v_W.z(), -p.descent_rate_mps - 1e-15) << "t = " << t;
    EXPECT_LE(o.p_W.z(), previous_z) << "t = " << t;
    EXPECT_GE(o.p_W.z(), p.to_height_m - 1e-15) << "t = " << t;
    previous_z = o.p_W.z();
  }
}

TEST(HoverDescent, EachDerivativeIsTheFiniteDifferenceOfTheOneBelow) {
  // h = 1e-3 with the fourth-order stencil: truncation h⁴/30·V·|σ⁽⁷⁾|/T_r⁷ ≈ 3e-14·0.2·1e5/0.2
  // ≈ 3e-9 at T_r = 0.8; rounding ≈ 1.5·ε·1 m/h ≈ 3e-13. Tolerance 1e-7.
  const HoverDescentParams p = offsetParams();
  const HoverDescent traj(p);
  const double h = 1e-3;
  const double t0 = p.hold_start_s;
  const double t3 = p.hold_start_s + traj.descent().duration();
  for (int i = 1; i < 500; ++i) {
    const double t = traj.duration() * i / 500.0;
    bool near_joint = false;
    for (double j : {t0, t0 + p.ramp_time_s, t3 - p.ramp_time_s, t3}) {
      near_joint = near_joint || std::abs(t - j) < 2.5 * h;
    }
    if (near_joint) continue;
    geaware_test::expectDerivativesMatchFiniteDifferences(traj, t, h, 1e-7);
  }
}

TEST(HoverDescent, IsContinuousUpToSnapAtEveryPhaseChange) {
  // δ = 1e-10: continuous quantities change by ≤ δ·V·840/T_r⁴ ≈ 4e-8; tolerance 1e-6.
  const HoverDescentParams p = offsetParams();
  const HoverDescent traj(p);
  const double t0 = p.hold_start_s;
  const double t3 = p.hold_start_s + traj.descent().duration();
  for (double joint : {t0, t0 + p.ramp_time_s, t3 - p.ramp_time_s, t3}) {
    geaware_test::expectContinuousAt(traj, joint, 1e-10, 1e-6);
  }
}

void expectThrowsMentioning(const HoverDescentParams& p,
                            std::initializer_list<const char*> needles) {
  try {
    const HoverDescent traj(p);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    for (const char* n : needles) {
      EXPECT_NE(what.find(n), std::string::npos) << what << " lacks " << n;
    }
  }
}

TEST(HoverDescent, InvalidParametersThrowNamingTheField) {
  HoverDescentParams p;
  p.to_height_m = 1.5;  // equal to from: nothing to descend
  expectThrowsMentioning(p, {"to_height_m = 1.5", "from_height_m = 1.5"});
  p = {};
  p.to_height_m = 2.0;
  expectThrowsMentioning(p, {"to_height_m = 2"});
  p = {};
  p.to_height_m = 0.0;
  expectThrowsMentioning(p, {"to_height_m = 0"});
  p = {};
  p.from_height_m = std::nan("");
  expectThrowsMentioning(p, {"from_height_m = nan"});
  p = {};
  p.descent_rate_mps = -0.1;
  expectThrowsMentioning(p, {"descent_rate_mps = -0.1"});
  p = {};
  p.hold_start_s = -1.0;
  expectThrowsMentioning(p, {"hold_start_s"});
  p = {};
  p.hold_end_s = INFINITY;
  expectThrowsMentioning(p, {"hold_end_s"});
  p = {};
  p.position_xy_m.y() = std::nan("");
  expectThrowsMentioning(p, {"position_xy_m"});
  // Impossible: at 1 m/s, ramps of 2 s would descend 2 m, more than the 1.4 m available.
  p = {};
  p.descent_rate_mps = 1.0;
  p.ramp_time_s = 2.0;
  expectThrowsMentioning(p, {"ramp_time_s = 2", "1.4"});
}

}  // namespace
