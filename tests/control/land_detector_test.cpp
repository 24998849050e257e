// SPDX-License-Identifier: BSD-3-Clause
// The land detector (control/land_detector.hpp): armed only once the reference has reached the
// gear's height, a verdict after confirm_s of standing still at it, a linear spool-down to zero,
// never re-armed; invalid parameters named.
#include "geaware/control/land_detector.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace geaware::control {
namespace {

constexpr double kGear = 0.072;
constexpr double kRate = 200.0;

/// A tick with the rotor plane at `h_m` over flat ground at z = 0, sinking at `v_z`, and the
/// reference at `ref_z`.
ControllerInput tick(double t_s, double h_m, double v_z, double ref_z) {
  ControllerInput in;
  in.t_s = t_s;
  in.height_m = h_m;
  in.height_valid = true;
  in.estimate.p_W = Eigen::Vector3d(0.0, 0.0, h_m);
  in.estimate.v_W = Eigen::Vector3d(0.0, 0.0, v_z);
  in.reference.p_W = Eigen::Vector3d(0.0, 0.0, ref_z);
  return in;
}

TEST(LandDetector, StandingStillAtTheGearsHeightForConfirmSIsLanded) {
  const LandDetectorParams p;  // 1 cm, 0.05 m/s, 0.2 s, 0.3 s
  LandDetector d(kGear, p, kRate);
  // Hovering low but with the reference above the floor: not armed, whatever the height.
  for (int k = 0; k < 100; ++k) EXPECT_EQ(d.update(tick(0.005 * k, 0.075, 0.0, 0.2)), 1.0);
  EXPECT_FALSE(d.landed());
  // The reference below the gear, the vehicle still sinking fast: not yet.
  for (int k = 0; k < 100; ++k) EXPECT_EQ(d.update(tick(0.5 + 0.005 * k, 0.08, -0.3, 0.05)), 1.0);
  EXPECT_FALSE(d.landed());
  // Standing still: the verdict after 0.2 s = 40 ticks, not before.
  for (int k = 0; k < 39; ++k) (void)d.update(tick(1.0 + 0.005 * k, 0.070, -0.01, 0.05));
  EXPECT_FALSE(d.landed());
  (void)d.update(tick(1.195, 0.070, -0.01, 0.05));
  ASSERT_TRUE(d.landed());
  EXPECT_DOUBLE_EQ(d.landedAt(), 1.195);
  // Spool-down: 1 − k·(1/200)/0.3, zero after 60 ticks, and it stays there even if lifted.
  EXPECT_NEAR(d.update(tick(1.2, 0.07, 0.0, 0.05)), 1.0 - 1.0 / 60.0, 1e-12);
  for (int k = 0; k < 59; ++k) (void)d.update(tick(1.2, 0.07, 0.0, 0.05));
  EXPECT_EQ(d.update(tick(1.5, 0.5, 1.0, 1.0)), 0.0);
  EXPECT_TRUE(d.landed());
}

TEST(LandDetector, ABreakRestartsTheConfirmationAndNoHeightNeverLands) {
  LandDetector d(kGear, LandDetectorParams{}, kRate);
  for (int k = 0; k < 30; ++k) (void)d.update(tick(0.005 * k, 0.07, 0.0, 0.05));
  (void)d.update(tick(0.15, 0.085, 0.0, 0.05));  // a bounce above the margin
  for (int k = 0; k < 39; ++k) (void)d.update(tick(0.2 + 0.005 * k, 0.07, 0.0, 0.05));
  EXPECT_FALSE(d.landed());
  ControllerInput blind = tick(1.0, 0.07, 0.0, 0.05);
  blind.height_valid = false;
  LandDetector e(kGear, LandDetectorParams{}, kRate);
  for (int k = 0; k < 400; ++k) EXPECT_EQ(e.update(blind), 1.0);
  EXPECT_FALSE(e.landed());
}

TEST(LandDetector, InvalidParametersAreNamed) {
  LandDetectorParams p;
  p.height_margin_m = 0.0;
  p.confirm_s = std::nan("");
  const auto errors = p.validate();
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0].field, "height_margin_m");
  EXPECT_EQ(errors[1].field, "confirm_s");
}

}  // namespace
}  // namespace geaware::control
