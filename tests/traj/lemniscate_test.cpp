// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/traj/lemniscate.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "flat_output_checks.hpp"
#include "geaware_test/eigen_matchers.hpp"

namespace {

using geaware::traj::FlatOutput;
using geaware::traj::Lemniscate;
using geaware::traj::LemniscateParams;

constexpr double kPi = std::numbers::pi;

// An off-origin figure-eight with yaw, two laps: exercises the centre offset and lap count.
LemniscateParams offsetParams() {
  LemniscateParams p;
  p.centre_xy_m = Eigen::Vector2d(1.5, -2.0);
  p.half_extent_x_m = 1.75;
  p.half_extent_y_m = 0.8;
  p.height_m = 1.0;
  p.peak_speed_mps = 1.0;
  p.laps = 2;
  p.ramp_time_s = 1.5;
  p.yaw_rad = 0.7;
  return p;
}

TEST(Lemniscate, DefaultsAreThePapersExperimentSeven) {
  const LemniscateParams p;
  EXPECT_TRUE(p.validate().empty());
  EXPECT_EQ(p.half_extent_x_m, 4.0);
  EXPECT_EQ(p.half_extent_y_m, 1.7);
  EXPECT_EQ(p.height_m, 0.18);
  EXPECT_EQ(p.peak_speed_mps, 3.0);
  EXPECT_EQ(p.laps, 1);
  EXPECT_EQ(p.ramp_time_s, 2.0);
  const Lemniscate traj(p);
  // Ω = v/√(A² + 4B²); duration = 2π·laps/Ω + T_r (SmoothProfile).
  const double omega = 3.0 / std::sqrt(16.0 + 4.0 * 1.7 * 1.7);
  EXPECT_NEAR(traj.cruisePhaseRate(), omega, 1e-15);
  EXPECT_NEAR(traj.duration(), 2.0 * kPi / omega + 2.0, 1e-12);
}

TEST(Lemniscate, StartsAndEndsAtRestAtTheCentre) {
  for (const LemniscateParams& p : {LemniscateParams{}, offsetParams()}) {
    const Lemniscate traj(p);
    const Eigen::Vector3d centre(p.centre_xy_m.x(), p.centre_xy_m.y(), p.height_m);
    for (double t : {0.0, traj.duration(), -1.0, traj.duration() + 1.0}) {
      SCOPED_TRACE(::testing::Message() << "t = " << t);
      const FlatOutput o = traj.sample(t);
      // After 2π·laps the sines are zero up to rounding of the phase (≈ 1e-15·A).
      EXPECT_MATRIX_NEAR(o.p_W, centre, 1e-12);
      EXPECT_MATRIX_NEAR(o.v_W, Eigen::Vector3d::Zero(), 0.0);
      EXPECT_MATRIX_NEAR(o.a_W, Eigen::Vector3d::Zero(), 0.0);
      EXPECT_MATRIX_NEAR(o.j_W, Eigen::Vector3d::Zero(), 0.0);
      EXPECT_MATRIX_NEAR(o.s_W, Eigen::Vector3d::Zero(), 0.0);
    }
  }
}

TEST(Lemniscate, PeakSpeedIsTheRequestedOne) {
  for (const LemniscateParams& p : {LemniscateParams{}, offsetParams()}) {
    const Lemniscate traj(p);
    // By symmetry of the profile the phase is π·laps at mid-time, a centre crossing during
    // the cruise, where |dP/dθ| is largest: the speed is exactly the peak there.
    EXPECT_NEAR(traj.sample(0.5 * traj.duration()).v_W.norm(), p.peak_speed_mps, 1e-12);
    // Dense sampling: never above the peak (beyond rounding) and reaching it to within the
    // grid: near the maximum the speed drops by ½·|d²‖v‖/dt²|·(Δt/2)² ≈ 1e-6 at Δt = 1 ms.
    double max_speed = 0.0;
    for (double t = 0.0; t <= traj.duration(); t += 1e-3) {
      max_speed = std::max(max_speed, traj.sample(t).v_W.norm());
    }
    EXPECT_LE(max_speed, p.peak_speed_mps * (1.0 + 1e-12));
    EXPECT_GE(max_speed, p.peak_speed_mps - 1e-5);
  }
}

TEST(Lemniscate, StaysOnTheGeronoCurveWithTheRequestedExtents) {
  const LemniscateParams p = offsetParams();
  const Lemniscate traj(p);
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(INFINITY);
  Eigen::Vector2d hi = -lo;
  for (double t = 0.0; t <= traj.duration(); t += 2e-3) {
    const FlatOutput o = traj.sample(t);
    // With X = (x − cx)/A = sin θ and Y = (y − cy)/B = sin 2θ: Y² = 4X²(1 − X²), an oracle
    // that does not depend on θ(t).
    const double x = (o.p_W.x() - p.centre_xy_m.x()) / p.half_extent_x_m;
    const double y = (o.p_W.y() - p.centre_xy_m.y()) / p.half_extent_y_m;
    EXPECT_NEAR(y * y, 4.0 * x * x * (1.0 - x * x), 1e-12) << "t = " << t;
    EXPECT_DOUBLE_EQ(o.p_W.z(), p.height_m);
    EXPECT_EQ(o.v_W.z(), 0.0);
    EXPECT_EQ(o.s_W.z(), 0.0);
    EXPECT_EQ(o.yaw_rad, p.yaw_rad);
    EXPECT_EQ(o.yaw_rate_radps, 0.0);
    EXPECT_EQ(o.yaw_acc_radps2, 0.0);
    lo = lo.cwiseMin(o.p_W.head<2>());
    hi = hi.cwiseMax(o.p_W.head<2>());
  }
  // The extremes sin θ = ±1 lie on the grid to within Δθ = Ω·Δt/2 ≈ 5e-4, so the sampled
  // extent falls short by at most A·Δθ²/2 ≈ 2e-7.
  const Eigen::Vector2d half(p.half_extent_x_m, p.half_extent_y_m);
  EXPECT_MATRIX_NEAR(hi, p.centre_xy_m + half, 1e-6);
  EXPECT_MATRIX_NEAR(lo, p.centre_xy_m - half, 1e-6);
}

TEST(Lemniscate, CompletesTheLapsAndPassesTheCentreAtEachHalfLap) {
  const LemniscateParams p = offsetParams();
  const Lemniscate traj(p);
  EXPECT_NEAR(traj.phase().distance(), 2.0 * kPi * p.laps, 1e-15);
  EXPECT_NEAR(traj.phase().sample(traj.duration()).s, 2.0 * kPi * p.laps, 1e-15);
  // Count centre crossings (sign changes of x − cx): 2 per lap, plus none at the ends.
  int crossings = 0;
  double previous = traj.sample(1e-3).p_W.x() - p.centre_xy_m.x();
  for (double t = 2e-3; t < traj.duration() - 1e-3; t += 1e-3) {
    const double x = traj.sample(t).p_W.x() - p.centre_xy_m.x();
    if ((x > 0.0) != (previous > 0.0)) ++crossings;
    previous = x;
  }
  EXPECT_EQ(crossings, 2 * p.laps - 1);  // the first half-lap starts, the last ends, at it
}

TEST(Lemniscate, EachDerivativeIsTheFiniteDifferenceOfTheOneBelow) {
  // Fourth-order stencil, h = 1e-3: truncation h⁴/30·|p⁽⁸⁾| stays below 1e-10 here (p⁽⁸⁾ is
  // dominated by |P'|·V·|σ⁽⁷⁾|/T_r⁷ ≈ 5·0.57·1e5/128 ≈ 2e3 for the defaults); 1e-8 relative
  // leaves a margin and still catches a wrong Faà di Bruno coefficient (of order |p⁽ᵏ⁾|).
  for (const LemniscateParams& p : {LemniscateParams{}, offsetParams()}) {
    const Lemniscate traj(p);
    const double tr = p.ramp_time_s;
    const double h = 1e-3;
    for (int i = 1; i < 400; ++i) {
      const double t = traj.duration() * i / 400.0;
      if (std::abs(t - tr) < 2.5 * h || std::abs(t - (traj.duration() - tr)) < 2.5 * h) continue;
      geaware_test::expectDerivativesMatchFiniteDifferences(traj, t, h, 1e-8);
    }
  }
}

TEST(Lemniscate, AHeightSwingRisesMidLapAndItsDerivativesAreExact) {
  LemniscateParams p = offsetParams();
  p.height_m = 0.1;
  p.height_swing_m = 0.2;
  const Lemniscate traj(p);
  // z = 0.1 + 0.1·(1 − cos θ): 0.1 m at each centre crossing of θ = 0, 2π, 4π; 0.3 m at θ = π, 3π.
  EXPECT_NEAR(traj.sample(0.0).p_W.z(), 0.1, 1e-15);
  EXPECT_NEAR(traj.sample(traj.duration()).p_W.z(), 0.1, 1e-12);
  double lo = 1.0, hi = 0.0;
  for (int i = 0; i <= 4000; ++i) {
    const double z = traj.sample(traj.duration() * i / 4000.0).p_W.z();
    lo = std::min(lo, z);
    hi = std::max(hi, z);
  }
  EXPECT_NEAR(lo, 0.1, 1e-12);
  EXPECT_NEAR(hi, 0.3, 1e-5);
  const double h = 1e-3;
  for (int i = 1; i < 200; ++i) {
    const double t = traj.duration() * i / 200.0;
    if (std::abs(t - p.ramp_time_s) < 2.5 * h || std::abs(t - (traj.duration() - p.ramp_time_s)) < 2.5 * h) continue;
    geaware_test::expectDerivativesMatchFiniteDifferences(traj, t, h, 1e-8);
  }
  // No swing: z exactly the height, every z derivative exactly +0 (the paper's flights unchanged).
  const Lemniscate level(offsetParams());
  for (double t : {0.3, 2.0, 5.0, 9.0}) {
    const auto o = level.sample(t);
    EXPECT_EQ(o.p_W.z(), 1.0);
    EXPECT_FALSE(std::signbit(o.v_W.z()) || std::signbit(o.a_W.z()) || std::signbit(o.j_W.z()) ||
                 std::signbit(o.s_W.z()));
  }
  p.height_swing_m = -0.1;
  EXPECT_EQ(p.validate().size(), 1u);
}

TEST(Lemniscate, IsContinuousUpToSnapAtTheRampJoints) {
  // At δ = 1e-10 a continuous quantity changes by ≤ δ·|p⁽⁵⁾| ≈ 1e-10·1e3; tolerance 1e-6.
  const Lemniscate traj{LemniscateParams{}};
  const double tr = traj.params().ramp_time_s;
  geaware_test::expectContinuousAt(traj, tr, 1e-10, 1e-6);
  geaware_test::expectContinuousAt(traj, traj.duration() - tr, 1e-10, 1e-6);
}

// The exception text must contain every needle.
void expectThrowsMentioning(const LemniscateParams& p, std::initializer_list<const char*> needles) {
  try {
    const Lemniscate traj(p);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    for (const char* n : needles) {
      EXPECT_NE(what.find(n), std::string::npos) << what << " lacks " << n;
    }
  }
}

TEST(Lemniscate, InvalidParametersThrowNamingTheField) {
  LemniscateParams p;
  p.half_extent_x_m = -4.0;
  expectThrowsMentioning(p, {"half_extent_x_m = -4"});
  p = {};
  p.half_extent_y_m = 0.0;
  expectThrowsMentioning(p, {"half_extent_y_m"});
  p = {};
  p.height_m = std::nan("");
  expectThrowsMentioning(p, {"height_m = nan"});
  p = {};
  p.peak_speed_mps = 0.0;
  expectThrowsMentioning(p, {"peak_speed_mps"});
  p = {};
  p.laps = 0;
  expectThrowsMentioning(p, {"laps = 0"});
  p = {};
  p.centre_xy_m.x() = INFINITY;
  expectThrowsMentioning(p, {"centre_xy_m"});
  p = {};
  p.yaw_rad = INFINITY;
  expectThrowsMentioning(p, {"yaw_rad"});
  p = {};
  p.ramp_time_s = -1.0;
  expectThrowsMentioning(p, {"ramp_time_s = -1"});

  // Every problem is listed, not only the first.
  p = {};
  p.half_extent_x_m = -1.0;
  p.laps = -2;
  EXPECT_EQ(p.validate().size(), 2U);

  // Impossible trajectory: at 3 m/s on the default curve, Ω ≈ 0.57 rad/s, so ramps of 20 s
  // would cover 11.4 rad of phase, more than one lap (2π).
  p = {};
  p.ramp_time_s = 20.0;
  expectThrowsMentioning(p, {"ramp_time_s = 20", "peak_speed_mps", "laps"});
  p.laps = 2;  // 4π ≈ 12.6 rad: now the ramps fit
  EXPECT_TRUE(p.validate().empty());
}

}  // namespace
