// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/traj/smooth_profile.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "flat_output_checks.hpp"

namespace {

using geaware::traj::ProfileSample;
using geaware::traj::SmoothProfile;

// Derivatives of s as an array, so that "derivative k+1 vs difference of derivative k" loops.
std::array<double, 5> asArray(const ProfileSample& p) {
  return {p.s, p.s_dot, p.s_ddot, p.s_dddot, p.s_ddddot};
}

TEST(SmoothProfile, CoversExactlyTheDistanceAndEndsAtRest) {
  const SmoothProfile profile(7.5, 1.2, 1.5);
  EXPECT_DOUBLE_EQ(profile.duration(), 7.5 / 1.2 + 1.5);
  const ProfileSample end = profile.sample(profile.duration());
  EXPECT_DOUBLE_EQ(end.s, 7.5);  // exact by construction (s = S − V·T_r·Σ(0))
  for (double t : {profile.duration(), profile.duration() + 10.0}) {
    const ProfileSample p = profile.sample(t);
    EXPECT_DOUBLE_EQ(p.s, 7.5);
    EXPECT_EQ(p.s_dot, 0.0);
    EXPECT_EQ(p.s_ddot, 0.0);
    EXPECT_EQ(p.s_dddot, 0.0);
    EXPECT_EQ(p.s_ddddot, 0.0);
  }
  for (double t : {0.0, -3.0}) {
    const ProfileSample p = profile.sample(t);
    EXPECT_EQ(p.s, 0.0);
    EXPECT_EQ(p.s_dot, 0.0);
    EXPECT_EQ(p.s_ddddot, 0.0);
  }
}

TEST(SmoothProfile, CruisesAtTheRateBetweenTheRamps) {
  const double v = 0.8;
  const double tr = 2.0;
  const SmoothProfile profile(10.0, v, tr);
  EXPECT_DOUBLE_EQ(profile.cruiseTime(), 10.0 / v - tr);
  // Each ramp covers V·T_r/2 (∫₀¹σ = 1/2): the end of the first ramp is at V·T_r/2.
  EXPECT_NEAR(profile.sample(tr).s, 0.5 * v * tr, 1e-12);
  for (double t = tr; t <= tr + profile.cruiseTime(); t += 0.25) {
    const ProfileSample p = profile.sample(t);
    EXPECT_NEAR(p.s_dot, v, 1e-12) << "t = " << t;
    EXPECT_NEAR(p.s_ddot, 0.0, 1e-12) << "t = " << t;
    EXPECT_NEAR(p.s_ddddot, 0.0, 1e-9) << "t = " << t;
  }
}

TEST(SmoothProfile, RateStaysWithinZeroAndCruiseAndProgressIsMonotone) {
  const SmoothProfile profile(3.0, 1.0, 2.5);
  double previous = -1.0;
  for (int i = 0; i <= 2000; ++i) {
    const double t = profile.duration() * i / 2000.0;
    const ProfileSample p = profile.sample(t);
    EXPECT_GE(p.s_dot, 0.0) << "t = " << t;
    EXPECT_LE(p.s_dot, 1.0 + 1e-15) << "t = " << t;
    EXPECT_GE(p.s, previous) << "t = " << t;
    previous = p.s;
  }
}

TEST(SmoothProfile, EachDerivativeIsTheFiniteDifferenceOfTheOneBelow) {
  // Ramps of 1.3 s, cruise of 2.4 s. h = 1e-3 with the fourth-order stencil: truncation
  // h⁴/30·|s⁽⁶⁾| ≤ 3.3e-14·V·max|σ⁽⁵⁾|/T_r⁵ ≈ 1e-10, rounding ≈ 1.5·ε·|s|/h ≈ 1e-12;
  // tolerance 1e-8 leaves a wide margin yet catches any wrong factor of T_r or sign.
  const double tr = 1.3;
  const SmoothProfile profile(2.0 * (tr + 2.4), 2.0, tr);
  const double h = 1e-3;
  const std::array<double, 4> joints = {0.0, tr, tr + 2.4, profile.duration()};
  int checked = 0;
  for (int i = 1; i < 700; ++i) {
    const double t = profile.duration() * i / 700.0;
    bool near_joint = false;
    for (double j : joints) near_joint = near_joint || std::abs(t - j) < 2.5 * h;
    if (near_joint) continue;  // the stencil would straddle a jump of s⁽⁵⁾
    const std::array<double, 5> d = asArray(profile.sample(t));
    for (std::size_t k = 0; k + 1 < d.size(); ++k) {
      const double fd = geaware_test::centralDifference(
          [&](double s) { return asArray(profile.sample(s))[k]; }, t, h);
      EXPECT_NEAR(d[k + 1], fd, 1e-8 * (1.0 + std::abs(d[k + 1])))
          << "derivative " << k + 1 << " at t = " << t;
    }
    ++checked;
  }
  EXPECT_GT(checked, 650);  // the joint filter must not have skipped the whole range
}

TEST(SmoothProfile, IsContinuousUpToSnapAtTheJoints) {
  // Across a joint a continuous derivative changes by at most δ·max|next derivative|; the
  // largest is s⁽⁵⁾ = V·|σ''''|/T_r⁴ = 1.5·840/0.9⁴ ≈ 1.9e3, so 1e-6 is 5× that bound at
  // δ = 1e-10. A real jump (e.g. a quintic smootherstep, whose σ''' ≠ 0 at the ends, gives a
  // snap step of V·60/T_r³ ≈ 120) is far above it.
  const double tr = 0.9;
  const SmoothProfile profile(5.0, 1.5, tr);
  const double delta = 1e-10;
  for (double joint : {tr, profile.duration() - tr}) {
    const auto l = asArray(profile.sample(joint - delta));
    const auto r = asArray(profile.sample(joint + delta));
    for (std::size_t k = 0; k < l.size(); ++k) {
      EXPECT_NEAR(l[k], r[k], 1e-6) << "derivative " << k << " at t = " << joint;
    }
  }
  // From rest and back to rest: every derivative tends to the held end state.
  for (double t : {delta, profile.duration() - delta}) {
    const auto p = asArray(profile.sample(t));
    for (std::size_t k = 1; k < p.size(); ++k) EXPECT_NEAR(p[k], 0.0, 1e-6) << "k = " << k;
  }
}

TEST(SmoothProfile, RampsThatFillTheWholeDistanceLeaveNoCruise) {
  // S = V·T_r exactly: the rate touches V only at t = T_r.
  const SmoothProfile profile(3.0, 1.5, 2.0);
  EXPECT_DOUBLE_EQ(profile.cruiseTime(), 0.0);
  EXPECT_DOUBLE_EQ(profile.duration(), 4.0);
  EXPECT_NEAR(profile.sample(2.0).s_dot, 1.5, 1e-12);
  EXPECT_NEAR(profile.sample(2.0).s, 1.5, 1e-12);
  EXPECT_DOUBLE_EQ(profile.sample(4.0).s, 3.0);
}

TEST(SmoothProfile, ZeroRampTimeIsAConstantRate) {
  const SmoothProfile profile(6.0, 2.0, 0.0);
  EXPECT_DOUBLE_EQ(profile.duration(), 3.0);
  const ProfileSample mid = profile.sample(1.2);
  EXPECT_DOUBLE_EQ(mid.s, 2.4);
  EXPECT_DOUBLE_EQ(mid.s_dot, 2.0);
  EXPECT_EQ(mid.s_ddot, 0.0);
  EXPECT_DOUBLE_EQ(profile.sample(3.0).s, 6.0);
  EXPECT_EQ(profile.sample(3.0).s_dot, 0.0);
}

TEST(SmoothProfile, NonFiniteTimeGivesNonFiniteOutput) {
  const SmoothProfile profile(1.0, 1.0, 0.5);
  EXPECT_TRUE(std::isnan(profile.sample(std::nan("")).s));
  EXPECT_DOUBLE_EQ(profile.sample(INFINITY).s, 1.0);
}

// The exception text must contain every needle (field names and values).
void expectThrowsMentioning(double s, double v, double tr,
                            std::initializer_list<const char*> needles) {
  try {
    const SmoothProfile profile(s, v, tr);
    ADD_FAILURE() << "no exception for S = " << s << ", V = " << v << ", T_r = " << tr;
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    for (const char* n : needles) {
      EXPECT_NE(what.find(n), std::string::npos) << what << " lacks " << n;
    }
  }
}

TEST(SmoothProfile, InvalidParametersThrowNamingTheField) {
  expectThrowsMentioning(-1.0, 1.0, 0.5, {"distance", "-1"});
  expectThrowsMentioning(0.0, 1.0, 0.5, {"distance"});
  expectThrowsMentioning(1.0, 0.0, 0.5, {"cruise_rate"});
  expectThrowsMentioning(1.0, std::nan(""), 0.5, {"cruise_rate", "nan"});
  expectThrowsMentioning(1.0, 1.0, -0.1, {"ramp_time_s", "-0.1"});
  expectThrowsMentioning(INFINITY, 1.0, 0.1, {"distance", "inf"});
  // Two offending fields: both named.
  expectThrowsMentioning(-1.0, -2.0, 0.5, {"distance", "cruise_rate"});
  // Feasible field by field, impossible together: the ramps alone cover 2·1.5 = 3 > 2.
  expectThrowsMentioning(2.0, 2.0, 1.5, {"impossible", "ramp_time_s", "distance = 2", "= 3"});
}

}  // namespace
