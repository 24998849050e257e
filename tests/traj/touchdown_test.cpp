// SPDX-License-Identifier: BSD-3-Clause
// Landing and take-off references (traj/touchdown.hpp): continuity up to snap at every joint,
// analytic derivatives against finite differences, the touchdown where and at the speed asked
// for, the bounded press below it, and every invalid parameter named.
#include "geaware/traj/touchdown.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "flat_output_checks.hpp"

namespace {

using geaware::traj::Landing;
using geaware::traj::LandingParams;
using geaware::traj::TakeOff;
using geaware::traj::TakeOffParams;

LandingParams landing() {
  LandingParams p;
  p.position_xy_m = Eigen::Vector2d(0.3, -0.4);
  p.from_height_m = 1.2;
  p.touchdown_height_m = 0.072;
  p.descent_rate_mps = 0.5;
  p.flare_height_m = 0.3;
  p.touchdown_speed_mps = 0.1;
  p.press_depth_m = 0.03;
  p.ramp_time_s = 1.0;
  p.hold_start_s = 0.5;
  p.hold_end_s = 1.5;
  p.yaw_rad = 0.4;
  return p;
}

TEST(Landing, TouchesDownAtTheGearsHeightAtTheTouchdownSpeed) {
  const LandingParams p = landing();
  const Landing l(p);
  // Speed-up 1 s (0.25 m), cruise (1.2 − 0.072 − 0.3 − 0.25)/0.5 = 1.156 s, flare 2·0.3/0.6 = 1 s.
  EXPECT_NEAR(l.touchdownTime(), 0.5 + 1.0 + 1.156 + 1.0, 1e-12);
  const auto td = l.sample(l.touchdownTime());
  EXPECT_NEAR(td.p_W.z(), p.touchdown_height_m, 1e-12);
  EXPECT_NEAR(td.v_W.z(), -p.touchdown_speed_mps, 1e-12);
  EXPECT_NEAR(td.a_W.z(), 0.0, 1e-12);
  // Cruise at the descent rate, the hold at the start and the rest below the gear at the end.
  EXPECT_NEAR(l.sample(2.0).v_W.z(), -p.descent_rate_mps, 1e-12);
  EXPECT_NEAR(l.sample(0.2).p_W.z(), p.from_height_m, 0.0);
  // Press: v_td → 0 over 2·0.03/0.1 = 0.6 s, then the hold.
  EXPECT_NEAR(l.duration(), l.touchdownTime() + 0.6 + p.hold_end_s, 1e-12);
  const auto end = l.sample(l.duration());
  EXPECT_NEAR(end.p_W.z(), p.touchdown_height_m - p.press_depth_m, 1e-12);
  EXPECT_EQ(end.v_W.z(), 0.0);
  EXPECT_EQ(end.p_W.head<2>(), p.position_xy_m);
  EXPECT_EQ(end.yaw_rad, p.yaw_rad);
  // The descent never speeds up past v_d and never climbs.
  double previous = p.from_height_m;
  for (double t = 0.0; t <= l.duration(); t += 0.01) {
    const auto o = l.sample(t);
    EXPECT_LE(o.p_W.z(), previous + 1e-15) << t;
    EXPECT_GE(o.v_W.z(), -p.descent_rate_mps - 1e-12) << t;
    previous = o.p_W.z();
  }
}

TEST(Landing, IsContinuousUpToSnapAndItsDerivativesAreExact) {
  const Landing l(landing());
  for (double t : {0.5, 1.5, 2.656, 3.656, 4.256})
    geaware_test::expectContinuousAt(l, t, 1e-9, 1e-5);
  for (double t : {0.9, 1.3, 2.2, 3.0, 3.4, 3.9, 4.1})
    geaware_test::expectDerivativesMatchFiniteDifferences(l, t, 1e-3, 1e-6);
}

TEST(Landing, EveryInvalidParameterIsNamed) {
  LandingParams p = landing();
  p.descent_rate_mps = 0.5;
  p.touchdown_speed_mps = 0.8;
  p.press_depth_m = 0.0;
  const auto problems = p.validate();
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_NE(problems[0].find("touchdown_speed_mps = 0.8 (expected <= descent_rate_mps = 0.5"), std::string::npos);
  EXPECT_NE(problems[1].find("press_depth_m"), std::string::npos);
  LandingParams low = landing();
  low.from_height_m = 0.5;  // 0.072 + 0.3 + 0.25 = 0.622 needed
  const auto room = low.validate();
  ASSERT_EQ(room.size(), 1u);
  EXPECT_NE(room[0].find("from_height_m = 0.5 (expected >= 0.622"), std::string::npos);
  EXPECT_THROW(Landing{low}, std::invalid_argument);
  LandingParams step = landing();
  step.ramp_time_s = 0.0;  // a speed step: not continuous up to snap
  ASSERT_EQ(step.validate().size(), 1u);
  EXPECT_NE(step.validate()[0].find("ramp_time_s"), std::string::npos);
}

TEST(TakeOff, ClimbsFromTheGearToTheHoverHeight) {
  TakeOffParams p;
  p.touchdown_height_m = 0.072;
  p.to_height_m = 1.0;
  p.climb_rate_mps = 0.5;
  p.ramp_time_s = 1.0;
  p.hold_start_s = 1.0;
  p.hold_end_s = 2.0;
  const TakeOff t(p);
  EXPECT_EQ(t.sample(0.0).p_W.z(), p.touchdown_height_m);
  EXPECT_EQ(t.sample(0.99).p_W.z(), p.touchdown_height_m);
  EXPECT_NEAR(t.sample(t.duration()).p_W.z(), p.to_height_m, 1e-12);
  EXPECT_NEAR(t.duration(), 1.0 + (0.928 / 0.5 + 1.0) + 2.0, 1e-12);
  geaware_test::expectDerivativesMatchFiniteDifferences(t, 1.5, 1e-3, 1e-6);
  p.to_height_m = 0.05;
  EXPECT_EQ(p.validate().size(), 1u);
  EXPECT_THROW(TakeOff{p}, std::invalid_argument);
}

}  // namespace
