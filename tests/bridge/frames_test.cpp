// SPDX-License-Identifier: BSD-3-Clause
// One test per conversion at the bridge's edge (bridge/frames.hpp), against hand-worked cases.
#include <gtest/gtest.h>

#include <cmath>

#include "geaware/bridge/frames.hpp"
#include "geaware_test/eigen_matchers.hpp"

namespace geaware::bridge {
namespace {

TEST(Frames, EnuToNedSwapsEastNorthAndFlipsUp) {
  // 1 m east, 2 m north, 3 m up is 2 m north, 1 m east, 3 m *down* negative.
  const Eigen::Vector3d ned = enuToNed({1.0, 2.0, 3.0});
  EXPECT_EQ(ned, Eigen::Vector3d(2.0, 1.0, -3.0));
  EXPECT_EQ(nedToEnu(ned), Eigen::Vector3d(1.0, 2.0, 3.0));
}

TEST(Frames, FluToFrdFlipsLeftAndUp) {
  EXPECT_EQ(fluToFrd({1.0, 2.0, 3.0}), Eigen::Vector3d(1.0, -2.0, -3.0));
  EXPECT_EQ(frdToFlu(fluToFrd({0.5, -0.25, 9.81})), Eigen::Vector3d(0.5, -0.25, 9.81));
}

TEST(Frames, LevelFacingEastIsPx4YawNinetyDegrees) {
  // Level, body x along ENU x (east): PX4 sees yaw +90° (north → east, clockwise from above).
  const Eigen::Quaterniond q = enuFluToNedFrd(Eigen::Quaterniond::Identity());
  const Eigen::Quaterniond expected(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(q.angularDistance(expected), 0.0, 1e-12);
}

TEST(Frames, LevelFacingNorthIsPx4YawZero) {
  const Eigen::Quaterniond q_enu(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(enuFluToNedFrd(q_enu).angularDistance(Eigen::Quaterniond::Identity()), 0.0, 1e-12);
}

TEST(Frames, AttitudeConversionRotatesVectorsConsistently) {
  // For any attitude, R_ned_frd · v_frd must equal enuToNed(R_enu_flu · v_flu).
  const Eigen::Quaterniond q = Eigen::Quaterniond(0.3, -0.5, 0.7, 0.2).normalized();
  const Eigen::Quaterniond p = enuFluToNedFrd(q);
  const Eigen::Vector3d v_flu(0.4, -1.2, 2.5);
  EXPECT_TRUE((p * fluToFrd(v_flu)).isApprox(enuToNed(q * v_flu), 1e-12));
  EXPECT_GE(p.w(), 0.0);
  EXPECT_NEAR(nedFrdToEnuFlu(p).angularDistance(q), 0.0, 1e-12);
}

TEST(Frames, MotorMapDefaultIsPx4QuadXAndRefusesDuplicates) {
  MotorMap m;
  EXPECT_TRUE(m.valid());
  EXPECT_EQ(m.px4_index, (std::array<int, 4>{0, 1, 2, 3}));
  m.px4_index = {0, 1, 1, 3};
  EXPECT_FALSE(m.valid());
  m.px4_index = {0, 1, 2, 12};
  EXPECT_FALSE(m.valid());
  m.px4_index = {3, 2, 11, 0};
  EXPECT_TRUE(m.valid());
}

TEST(Frames, ThrustModelMatchesPx4FormulaAndInverts) {
  // f = 0: linear; f = 1: quadratic; f = 0.4 at u = 0.5: 0.4·0.25 + 0.6·0.5 = 0.4.
  EXPECT_DOUBLE_EQ(normalisedThrustFromThrottle(0.3, 0.0), 0.3);
  EXPECT_DOUBLE_EQ(normalisedThrustFromThrottle(0.5, 1.0), 0.25);
  EXPECT_NEAR(normalisedThrustFromThrottle(0.5, 0.4), 0.4, 1e-15);
  for (double f : {0.0, 0.25, 0.4, 1.0}) {
    for (double u = 0.0; u <= 1.0; u += 0.05) {
      EXPECT_NEAR(throttleFromNormalisedThrust(normalisedThrustFromThrottle(u, f), f), u, 1e-12)
          << "f " << f << " u " << u;
    }
  }
  EXPECT_DOUBLE_EQ(normalisedThrustFromThrottle(1.7, 0.3), 1.0);
  EXPECT_DOUBLE_EQ(throttleFromNormalisedThrust(-0.2, 0.3), 0.0);
  EXPECT_TRUE(std::isnan(normalisedThrustFromThrottle(std::nan(""), 0.3)));
}

TEST(Frames, MicrosecondsRoundTripAndRefuseNegative) {
  EXPECT_EQ(toMicroseconds(0.005), 5000u);
  EXPECT_EQ(toMicroseconds(12.3456789), 12345679u);
  EXPECT_EQ(toMicroseconds(-1.0), 0u);
  EXPECT_EQ(toMicroseconds(std::nan("")), 0u);
  EXPECT_EQ(toMicroseconds(toSeconds(987654321u)), 987654321u);
}

}  // namespace
}  // namespace geaware::bridge
