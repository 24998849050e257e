// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/traj/min_snap.hpp"

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <initializer_list>
#include <new>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/LU>

#include "flat_output_checks.hpp"
#include "geaware_test/allocation_counter.hpp"
#include "geaware_test/eigen_matchers.hpp"


namespace {

using geaware::traj::FlatOutput;
using geaware::traj::MinSnapTrajectory;
using geaware::traj::Waypoint;

// A 3-D loop with yaw, segments of unequal durations.
std::vector<Waypoint> loopWaypoints() {
  return {{Eigen::Vector3d(0.0, 0.0, 1.0), 0.0},
          {Eigen::Vector3d(2.0, 1.0, 1.5), 0.5},
          {Eigen::Vector3d(3.0, -1.0, 1.0), 1.0},
          {Eigen::Vector3d(1.0, -2.0, 0.5), 0.2},
          {Eigen::Vector3d(0.0, 0.0, 1.0), 0.0}};
}
const std::vector<double> kLoopDurations = {1.5, 2.0, 1.2, 2.5};

// The closed-form rest-to-rest polynomial σ(x) = 35x⁴ − 84x⁵ + 70x⁶ − 20x⁷ and its first four
// derivatives in x: the unique degree-7 polynomial from 0 to 1 with v = a = j = 0 at both ends.
std::array<double, 5> smootherstep(double x) {
  return {
      x * x * x * x * (35.0 - 84.0 * x + 70.0 * x * x - 20.0 * x * x * x),
      140.0 * std::pow(x * (1.0 - x), 3),
      420.0 * x * x - 1680.0 * std::pow(x, 3) + 2100.0 * std::pow(x, 4) - 840.0 * std::pow(x, 5),
      840.0 * x - 5040.0 * x * x + 8400.0 * std::pow(x, 3) - 4200.0 * std::pow(x, 4),
      840.0 - 10080.0 * x + 25200.0 * x * x - 16800.0 * std::pow(x, 3)};
}

TEST(MinSnap, TwoWaypointsGiveTheClosedFormRestToRestPolynomial) {
  const Waypoint a{Eigen::Vector3d(1.0, -2.0, 0.5), 0.3};
  const Waypoint b{Eigen::Vector3d(4.0, 2.0, 1.7), -1.1};
  const double t_seg = 2.7;
  const MinSnapTrajectory traj({a, b}, {t_seg});
  const Eigen::Vector3d dp = b.p_W - a.p_W;
  const double dyaw = b.yaw_rad - a.yaw_rad;
  for (int i = 0; i <= 50; ++i) {
    const double t = t_seg * i / 50.0;
    const std::array<double, 5> s = smootherstep(t / t_seg);
    const FlatOutput o = traj.sample(t);
    SCOPED_TRACE(::testing::Message() << "t = " << t);
    // Tolerance: the 8×8 solve is exact up to rounding, ~1e-13 on coefficients of order 100.
    EXPECT_MATRIX_NEAR(o.p_W, a.p_W + dp * s[0], 1e-11);
    EXPECT_MATRIX_NEAR(o.v_W, dp * s[1] / t_seg, 1e-11);
    EXPECT_MATRIX_NEAR(o.a_W, dp * s[2] / std::pow(t_seg, 2), 1e-11);
    EXPECT_MATRIX_NEAR(o.j_W, dp * s[3] / std::pow(t_seg, 3), 1e-10);
    EXPECT_MATRIX_NEAR(o.s_W, dp * s[4] / std::pow(t_seg, 4), 1e-10);
    EXPECT_NEAR(o.yaw_rad, a.yaw_rad + dyaw * s[0], 1e-11);
    EXPECT_NEAR(o.yaw_rate_radps, dyaw * s[1] / t_seg, 1e-11);
    EXPECT_NEAR(o.yaw_acc_radps2, dyaw * s[2] / std::pow(t_seg, 2), 1e-11);
  }
}

TEST(MinSnap, PassesThroughEveryWaypointAndStartsAndEndsAtRest) {
  const MinSnapTrajectory traj(loopWaypoints(), kLoopDurations);
  ASSERT_EQ(traj.waypointTimes().size(), 5U);
  EXPECT_NEAR(traj.duration(), 7.2, 1e-15);
  for (std::size_t k = 0; k < traj.waypoints().size(); ++k) {
    const FlatOutput o = traj.sample(traj.waypointTimes()[k]);
    EXPECT_MATRIX_NEAR(o.p_W, traj.waypoints()[k].p_W, 1e-12) << "waypoint " << k;
    EXPECT_NEAR(o.yaw_rad, traj.waypoints()[k].yaw_rad, 1e-12) << "waypoint " << k;
  }
  for (double t : {0.0, traj.duration()}) {
    const FlatOutput o = traj.sample(t);
    EXPECT_MATRIX_NEAR(o.v_W, Eigen::Vector3d::Zero(), 1e-12) << "t = " << t;
    EXPECT_MATRIX_NEAR(o.a_W, Eigen::Vector3d::Zero(), 1e-12) << "t = " << t;
    EXPECT_MATRIX_NEAR(o.j_W, Eigen::Vector3d::Zero(), 1e-11) << "t = " << t;
    EXPECT_NEAR(o.yaw_rate_radps, 0.0, 1e-12);
    EXPECT_NEAR(o.yaw_acc_radps2, 0.0, 1e-12);
  }
  // Strictly outside: exactly the end waypoints, at rest.
  const FlatOutput before = traj.sample(-1.0);
  const FlatOutput after = traj.sample(traj.duration() + 1e-9);
  EXPECT_EQ(before.p_W, loopWaypoints().front().p_W);
  EXPECT_EQ(after.p_W, loopWaypoints().back().p_W);
  EXPECT_EQ(after.s_W, Eigen::Vector3d::Zero());
}

TEST(MinSnap, IsContinuousUpToSnapAcrossInteriorWaypoints) {
  // δ = 1e-10: a continuous quantity changes by ≤ δ·|p⁽⁵⁾| (p⁽⁵⁾ ≲ 1e3 here); tolerance
  // 1e-6. A segment-index or time-offset bug gives jumps of order 1.
  const MinSnapTrajectory traj(loopWaypoints(), kLoopDurations);
  for (std::size_t k = 1; k + 1 < traj.waypointTimes().size(); ++k) {
    geaware_test::expectContinuousAt(traj, traj.waypointTimes()[k], 1e-10, 1e-6);
  }
}

TEST(MinSnap, FifthAndSixthDerivativesAreContinuousToo) {
  // The optimality condition is continuity up to the 6th derivative. sample() stops at snap,
  // which is a cubic on each segment, so one-sided 4-point stencils differentiate it exactly
  // (up to rounding): f'(0) = (−11f₀ + 18f₁ − 9f₂ + 2f₃)/6δ, f''(0) = (2f₀ − 5f₁ + 4f₂ − f₃)/δ².
  // Left and right values must agree. Rounding: ≈ 20·ε·|snap|/δ² ≈ 1e-10 at δ = 0.1 s.
  const MinSnapTrajectory traj(loopWaypoints(), kLoopDurations);
  const double d = 0.1;  // well inside the shortest segment (1.2 s)
  for (std::size_t k = 1; k + 1 < traj.waypointTimes().size(); ++k) {
    const double tk = traj.waypointTimes()[k];
    std::array<Eigen::Vector3d, 4> left;
    std::array<Eigen::Vector3d, 4> right;
    for (std::size_t i = 0; i < 4; ++i) {
      // The left stencil's first point is the knot itself, where snap is continuous (tested
      // above): take it from just inside the left segment.
      left[i] = traj.sample(tk - (i == 0 ? 1e-12 : static_cast<double>(i) * d)).s_W;
      right[i] = traj.sample(tk + static_cast<double>(i) * d).s_W;
    }
    // Left stencil runs backwards in time: odd derivatives change sign.
    const Eigen::Vector3d d5_left =
        -(-11.0 * left[0] + 18.0 * left[1] - 9.0 * left[2] + 2.0 * left[3]) / (6.0 * d);
    const Eigen::Vector3d d5_right =
        (-11.0 * right[0] + 18.0 * right[1] - 9.0 * right[2] + 2.0 * right[3]) / (6.0 * d);
    const Eigen::Vector3d d6_left =
        (2.0 * left[0] - 5.0 * left[1] + 4.0 * left[2] - left[3]) / (d * d);
    const Eigen::Vector3d d6_right =
        (2.0 * right[0] - 5.0 * right[1] + 4.0 * right[2] - right[3]) / (d * d);
    SCOPED_TRACE(::testing::Message() << "knot at t = " << tk);
    EXPECT_MATRIX_NEAR(d5_left, d5_right, 1e-7);
    EXPECT_MATRIX_NEAR(d6_left, d6_right, 1e-6);
    // And the check has teeth: the 6th derivative is not trivially zero here.
    EXPECT_GT(d6_right.norm(), 1e-2);
  }
}

TEST(MinSnap, EachDerivativeIsTheFiniteDifferenceOfTheOneBelow) {
  // Inside a segment p⁽⁸⁾ = 0, so the fourth-order stencil's truncation error h⁴/30·f⁽⁵⁾
  // vanishes and only rounding remains (≈ 1.5·ε·|f|/h ≈ 1e-12 at h = 1e-3); 1e-8 relative
  // still fails for a wrong 1/Tʳ scaling or derivative table entry.
  const MinSnapTrajectory traj(loopWaypoints(), kLoopDurations);
  const double h = 1e-3;
  for (int i = 1; i < 300; ++i) {
    const double t = traj.duration() * i / 300.0;
    bool near_knot = false;
    for (double tk : traj.waypointTimes()) near_knot = near_knot || std::abs(t - tk) < 2.5 * h;
    if (near_knot) continue;
    geaware_test::expectDerivativesMatchFiniteDifferences(traj, t, h, 1e-8);
  }
}

TEST(MinSnap, ManyUnevenSegmentsStayAccurate) {
  // 60 random waypoints, durations spread over 50×: the normalised-time system must stay well
  // conditioned. Waypoint error 1e-9 m and joint continuity 1e-6 (δ = 1e-10, see above).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-5.0, 5.0);
  std::uniform_real_distribution<double> duration(0.2, 10.0);
  std::vector<Waypoint> wps;
  std::vector<double> durations;
  for (int i = 0; i < 60; ++i) {
    wps.push_back({Eigen::Vector3d(coord(rng), coord(rng), 6.0 + coord(rng)), coord(rng)});
    if (i > 0) durations.push_back(duration(rng));
  }
  const MinSnapTrajectory traj(wps, durations);
  for (std::size_t k = 0; k < wps.size(); ++k) {
    const FlatOutput o = traj.sample(traj.waypointTimes()[k]);
    EXPECT_MATRIX_NEAR(o.p_W, wps[k].p_W, 1e-9) << "waypoint " << k;
    EXPECT_NEAR(o.yaw_rad, wps[k].yaw_rad, 1e-9) << "waypoint " << k;
    if (k > 0 && k + 1 < wps.size()) {
      geaware_test::expectContinuousAt(traj, traj.waypointTimes()[k], 1e-10, 1e-6);
    }
  }
}

// ---- Optimality: no feasible trajectory has less snap energy -----------------------------

// 5-point Gauss–Legendre on [0, 1]: exact for polynomials up to degree 9 (snap² of degree-7
// pieces is degree 6).
constexpr std::array<double, 5> kGaussX = {0.04691007703066800, 0.2307653449471585, 0.5,
                                           0.7692346550528415, 0.9530899229693320};
constexpr std::array<double, 5> kGaussW = {0.1184634425280945, 0.2393143352496832,
                                           0.2844444444444444, 0.2393143352496832,
                                           0.1184634425280945};

/// Position, velocity, acceleration, jerk (3-D) at one instant.
using KnotState = std::array<Eigen::Vector3d, 4>;

/// ∫‖p⁗‖² of the degree-7 polynomial with the given states at τ = 0 and τ = T (Hermite).
double hermiteSnapEnergy(const KnotState& s0, const KnotState& s1, double t_seg) {
  Eigen::Matrix<double, 8, 8> a = Eigen::Matrix<double, 8, 8>::Zero();
  Eigen::Matrix<double, 8, 3> b;
  for (int r = 0; r < 4; ++r) {
    for (int k = r; k < 8; ++k) {
      double f = 1.0;
      for (int i = 0; i < r; ++i) f *= k - i;
      if (k == r) a(r, k) = f;  // at τ = 0 only the x^r term survives
      a(4 + r, k) = f * std::pow(t_seg, k - r);
    }
    b.row(r) = s0[static_cast<std::size_t>(r)].transpose();
    b.row(4 + r) = s1[static_cast<std::size_t>(r)].transpose();
  }
  const Eigen::Matrix<double, 8, 3> c = a.fullPivLu().solve(b);
  double energy = 0.0;
  for (std::size_t q = 0; q < kGaussX.size(); ++q) {
    const double tau = kGaussX[q] * t_seg;
    Eigen::RowVector3d snap = Eigen::RowVector3d::Zero();
    for (int k = 4; k < 8; ++k) {
      snap += k * (k - 1) * (k - 2) * (k - 3) * std::pow(tau, k - 4) * c.row(k);
    }
    energy += kGaussW[q] * t_seg * snap.squaredNorm();
  }
  return energy;
}

/// ∫‖p⁗‖² of the min-snap trajectory, by the same quadrature over its sampled snap.
double snapEnergy(const MinSnapTrajectory& traj) {
  double energy = 0.0;
  for (std::size_t i = 0; i < traj.segmentDurations().size(); ++i) {
    const double t_seg = traj.segmentDurations()[i];
    for (std::size_t q = 0; q < kGaussX.size(); ++q) {
      energy += kGaussW[q] * t_seg *
                traj.sample(traj.waypointTimes()[i] + kGaussX[q] * t_seg).s_W.squaredNorm();
    }
  }
  return energy;
}

TEST(MinSnap, NoPerturbedFeasibleTrajectoryHasLessSnap) {
  // Feasible competitors: the same waypoints, times and rest-to-rest ends, but the velocity,
  // acceleration and jerk at the interior waypoints moved; each segment is then the degree-7
  // Hermite polynomial between its end states (C³, so its snap energy is finite). Both signs
  // and small steps are tried: a non-zero first-order term (wrong optimality conditions)
  // would make one of J(±ε) smaller than J(0).
  const MinSnapTrajectory traj(loopWaypoints(), kLoopDurations);
  const std::vector<double>& times = traj.waypointTimes();
  std::vector<KnotState> knots(times.size());
  for (std::size_t k = 0; k < times.size(); ++k) {
    const FlatOutput o = traj.sample(times[k]);
    knots[k] = {o.p_W, o.v_W, o.a_W, o.j_W};
  }
  const auto energyOf = [&](const std::vector<KnotState>& ks) {
    double e = 0.0;
    for (std::size_t i = 0; i + 1 < ks.size(); ++i) {
      e += hermiteSnapEnergy(ks[i], ks[i + 1], traj.segmentDurations()[i]);
    }
    return e;
  };
  const double optimum = snapEnergy(traj);
  ASSERT_GT(optimum, 0.0);
  // Sanity: the Hermite rebuild of the optimum's own knot states is the optimum.
  EXPECT_NEAR(energyOf(knots), optimum, 1e-9 * optimum);

  std::mt19937 rng(20240611);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<KnotState> direction(knots.size());
    for (std::size_t k = 0; k < knots.size(); ++k) {
      for (auto& v : direction[k]) v.setZero();
      if (k == 0 || k + 1 == knots.size()) continue;  // the ends are fixed by the problem
      for (std::size_t r = 1; r < 4; ++r) {
        direction[k][r] = Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
      }
    }
    for (double eps : {1e-3, -1e-3, 0.3, -0.3}) {
      std::vector<KnotState> perturbed = knots;
      for (std::size_t k = 0; k < knots.size(); ++k) {
        for (std::size_t r = 1; r < 4; ++r) perturbed[k][r] += eps * direction[k][r];
      }
      // The increase is second order, ε²·J(direction) ≳ 1e-6·O(1) at ε = 1e-3; the
      // tolerance 1e-10·J allows only rounding.
      EXPECT_GT(energyOf(perturbed), optimum * (1.0 - 1e-10))
          << "trial " << trial << ", eps = " << eps;
    }
  }
}

// ---- Durations from an average speed --------------------------------------------------------

TEST(MinSnap, AverageSpeedGivesDurationsProportionalToLengthWithAFloor) {
  std::vector<Waypoint> wps = {{Eigen::Vector3d(0, 0, 1), 0.0},
                               {Eigen::Vector3d(3, 4, 1), 0.0},   // 5 m
                               {Eigen::Vector3d(3, 4, 1), 1.5},   // repeated: yaw-only turn
                               {Eigen::Vector3d(3, 4, 2), 1.5}};  // 1 m
  const MinSnapTrajectory traj = MinSnapTrajectory::fromAverageSpeed(wps, 2.0, 0.8);
  ASSERT_EQ(traj.segmentDurations().size(), 3U);
  EXPECT_DOUBLE_EQ(traj.segmentDurations()[0], 2.5);
  EXPECT_DOUBLE_EQ(traj.segmentDurations()[1], 0.8);  // zero length: the floor
  EXPECT_DOUBLE_EQ(traj.segmentDurations()[2], 0.8);  // 0.5 s by length, below the floor
  for (std::size_t k = 0; k < wps.size(); ++k) {
    const FlatOutput o = traj.sample(traj.waypointTimes()[k]);
    EXPECT_MATRIX_NEAR(o.p_W, wps[k].p_W, 1e-12) << "waypoint " << k;
    EXPECT_NEAR(o.yaw_rad, wps[k].yaw_rad, 1e-12) << "waypoint " << k;
  }
  for (double t = 0.0; t <= traj.duration(); t += 0.01) ASSERT_TRUE(traj.sample(t).allFinite());
}

TEST(MinSnap, SampleDoesNotAllocate) {
  const MinSnapTrajectory traj(loopWaypoints(), kLoopDurations);
  double sink = 0.0;
  const long before = geaware_test::allocationCount();
  for (int i = -10; i <= 1010; ++i) sink += traj.sample(traj.duration() * i / 1000.0).s_W.x();
  const long after = geaware_test::allocationCount();
  EXPECT_EQ(after - before, 0);
  EXPECT_TRUE(std::isfinite(sink));
}

// ---- Validation ---------------------------------------------------------------------------

void expectThrowsMentioning(const std::vector<Waypoint>& w, const std::vector<double>& d,
                            std::initializer_list<const char*> needles) {
  try {
    const MinSnapTrajectory traj(w, d);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    for (const char* n : needles) {
      EXPECT_NE(what.find(n), std::string::npos) << what << " lacks " << n;
    }
  }
}

TEST(MinSnap, InvalidInputsThrowNamingTheField) {
  const std::vector<Waypoint> two = {{Eigen::Vector3d::Zero(), 0.0},
                                     {Eigen::Vector3d::UnitX(), 0.0}};
  expectThrowsMentioning({two[0]}, {}, {"waypoints: size = 1"});
  expectThrowsMentioning({}, {}, {"waypoints: size = 0"});
  expectThrowsMentioning(two, {1.0, 2.0}, {"segment_durations_s: size = 2", "= 1"});
  expectThrowsMentioning(two, {0.0}, {"segment_durations_s[0] = 0"});
  expectThrowsMentioning(two, {-1.0}, {"segment_durations_s[0] = -1"});
  expectThrowsMentioning(two, {std::nan("")}, {"segment_durations_s[0] = nan"});
  std::vector<Waypoint> bad = loopWaypoints();
  bad[2].p_W.y() = INFINITY;
  bad[3].yaw_rad = std::nan("");
  expectThrowsMentioning(bad, kLoopDurations, {"waypoints[2]", "inf", "waypoints[3]"});
  EXPECT_EQ(MinSnapTrajectory::validate(bad, {1.0, 0.0, 1.0, 1.0}).size(), 3U);

  EXPECT_THROW((void)MinSnapTrajectory::fromAverageSpeed(two, 0.0), std::invalid_argument);
  try {
    (void)MinSnapTrajectory::fromAverageSpeed(two, -1.0, 0.0);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("average_speed_mps = -1"), std::string::npos) << what;
    EXPECT_NE(what.find("min_segment_duration_s = 0"), std::string::npos) << what;
  }
  // A repeated waypoint with a positive duration is fine (hover in place while turning).
  const std::vector<Waypoint> repeated = {two[0], {Eigen::Vector3d::Zero(), 1.0}};
  EXPECT_NO_THROW((void)MinSnapTrajectory(repeated, {1.0}));
}

}  // namespace
