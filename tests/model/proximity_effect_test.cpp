// SPDX-License-Identifier: BSD-3-Clause
// The image-method ceiling and wall laws (model/proximity_effect.hpp) against their closed
// forms: under a ceiling T/T∞ = 1/(1 − (R/(4d))²), the form of Cheeseman & Bennett's ground
// law; beside a wall no thrust change and a pull T·R²/(32·d²) toward it; surfaces below the rotor
// plane fade out (a wall does not, whatever the tilt up to 30°); the law is held at d = R/2.
#include "geaware/model/proximity_effect.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace geaware::model {
namespace {

const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();
constexpr double kR = 0.089;  // the paper vehicle's 7-inch propellers [m]

TEST(ProximityEffect, UnderACeilingTheThrustGrowsLikeTheGroundLaw) {
  for (const double d : {0.05, 0.1, 0.15, 0.3, 1.0}) {
    // The ceiling's normal toward the rotor points down.
    const Eigen::Vector3d u = imageInflow(d, kR, -kUp, kUp);
    const ProximityResponse r = proximityResponse(u, kUp);
    const double k = kR / (4.0 * d);
    EXPECT_NEAR(r.thrust_ratio, 1.0 / (1.0 - k * k), 1e-12) << d;
    EXPECT_GT(r.thrust_ratio, 1.0);  // a ceiling pulls up
    EXPECT_NEAR(r.side_force_per_N.norm(), 0.0, 1e-15);
  }
  // At 0.15 m with 7-inch propellers: +2.25 % (docs/world.md §10).
  EXPECT_NEAR(proximityResponse(imageInflow(0.15, kR, -kUp, kUp), kUp).thrust_ratio, 1.02250, 1e-5);
}

TEST(ProximityEffect, BesideAWallTheRotorIsPulledTowardIt) {
  // A wall on the +y side: its normal toward the rotor is −y.
  const Eigen::Vector3d n(0.0, -1.0, 0.0);
  for (const double d : {0.1, 0.2, 0.4}) {
    const ProximityResponse r = proximityResponse(imageInflow(d, kR, n, kUp), kUp);
    EXPECT_NEAR(r.thrust_ratio, 1.0, 1e-15);
    EXPECT_NEAR(r.side_force_per_N.y(), kR * kR / (32.0 * d * d), 1e-15) << d;
    EXPECT_EQ(r.side_force_per_N.x(), 0.0);
    EXPECT_EQ(r.side_force_per_N.z(), 0.0);
  }
}

TEST(ProximityEffect, SurfacesBelowTheRotorPlaneFadeOut) {
  // A face below the rotor (its normal toward the rotor has n·a > 0) is the ground's business.
  EXPECT_TRUE(imageInflow(0.2, kR, kUp, kUp).isZero(0.0));
  const auto at = [](double na) { return Eigen::Vector3d(std::sqrt(1.0 - na * na), 0.0, na); };
  const double full = imageInflow(0.2, kR, at(0.0), kUp).norm();
  // A wall seen from a vehicle rolled by up to 30° keeps its full weight.
  EXPECT_NEAR(imageInflow(0.2, kR, at(0.5), kUp).norm(), full, 1e-15);
  EXPECT_NEAR(imageInflow(0.2, kR, at(0.65), kUp).norm(), 0.5 * full, 1e-12);
  EXPECT_TRUE(imageInflow(0.2, kR, at(kUpstreamFadeCos), kUp).isZero(0.0));
}

TEST(ProximityEffect, HeldAtHalfARadiusAndBoundedForManySurfaces) {
  const Eigen::Vector3d at_half = imageInflow(0.5 * kR, kR, -kUp, kUp);
  EXPECT_EQ(imageInflow(0.1 * kR, kR, -kUp, kUp), at_half);
  EXPECT_NEAR(proximityResponse(at_half, kUp).thrust_ratio, 4.0 / 3.0, 1e-12);
  // Two ceilings at the closest distance do not stop the inflow.
  EXPECT_NEAR(proximityResponse(2.0 * at_half, kUp).thrust_ratio, 4.0 / 3.0, 1e-12);
  // No surface, a bad distance: nothing.
  EXPECT_TRUE(imageInflow(0.0, kR, -kUp, kUp).isZero(0.0));
  EXPECT_TRUE(imageInflow(std::numeric_limits<double>::quiet_NaN(), kR, -kUp, kUp).isZero(0.0));
  EXPECT_EQ(proximityResponse(Eigen::Vector3d::Zero(), kUp).thrust_ratio, 1.0);
}

}  // namespace
}  // namespace geaware::model
