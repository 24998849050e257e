// SPDX-License-Identifier: BSD-3-Clause
// The ground effect's forward-flight fade in the controller (issue 13 item 2): without the vehicle
// file's key the controller is bit for bit the paper's; with it, at rest nothing changes, and in
// a fast level run near the ground the model's cushion is faded, so the controller commands the
// thrust that holds the height without it (closed form at the reference's speed).
#include <cmath>
#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "geaware/control/controller.hpp"
#include "geaware/model/units.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace {

using namespace geaware::control;
using geaware::model::kGravity;

ControllerParams paperConfiguration() {
  ControllerParams p;
  EXPECT_TRUE(parseConfiguration("model:model_indi", p));
  return p;
}

/// A level run at speed V along x, exactly on the reference, at height h.
ControllerInput run(double h, double V) {
  ControllerInput in;
  in.reference.p_W = Eigen::Vector3d(0.0, 0.0, h);
  in.reference.v_W = Eigen::Vector3d(V, 0.0, 0.0);
  in.estimate.p_W = in.reference.p_W;
  in.estimate.v_W = in.reference.v_W;
  in.estimate.q_WB = Eigen::Quaterniond::Identity();
  in.accel_B = Eigen::Vector3d(0.0, 0.0, kGravity);
  in.height_m = h;
  in.height_valid = true;
  in.rotor_speeds_rpm.setConstant(geaware_test::paperVehicle().hoverSpeedRpm(h));
  return in;
}

TEST(ForwardFade, TheControllerFadesTheCushionWithTheReferencesSpeed) {
  auto params = geaware_test::paperParams();
  params.forward_fade_induced_velocity_mps = 8.26;
  const geaware::model::VehicleModel fading(params);
  Controller plain(geaware_test::paperVehicle(), paperConfiguration());
  Controller faded(fading, paperConfiguration());
  const double h = 0.15;
  // At rest: the same command, bit for bit.
  const ControllerOutput a = plain.update(run(h, 0.0));
  const ControllerOutput b = faded.update(run(h, 0.0));
  EXPECT_EQ(a.thrust_des_N, b.thrust_des_N);
  EXPECT_EQ(a.n_des_rpm, b.n_des_rpm);
  // At 5 m/s level: the vertical feed-forward a_G = T_ref/m·fade·F_G with T_ref ≈ m·g/(1 +
  // fade·F_G) (the flat map), so the commanded thrust is m·(g − a_G) ≈ m·g/(1 + fade·F_G),
  // against m·g/(1 + F_G) without the fade. ≈: the flat map tilts the reference 4.8° into the
  // rotor drag, cos = 0.9965, which moves T_ref by 0.01 N.
  plain.reset();
  faded.reset();
  const double F = geaware_test::paperVehicle().groundEffect().thrustRatio(h);
  const double fade = 8.26 * 8.26 / (8.26 * 8.26 + 25.0);
  const double m = params.mass_kg;
  const ControllerOutput c = plain.update(run(h, 5.0));
  const ControllerOutput d = faded.update(run(h, 5.0));
  EXPECT_NEAR(c.thrust_des_N, m * kGravity / (1.0 + F), 0.02);
  EXPECT_NEAR(d.thrust_des_N, m * kGravity / (1.0 + fade * F), 0.02);
  EXPECT_GT(d.thrust_des_N - c.thrust_des_N, 0.1);  // 0.46 N more at 0.15 m: the cushion is weaker
  // The feed-forward fades with the reference's speed, not the estimate's: the estimate at rest
  // and the reference at 5 m/s give the faded command.
  faded.reset();
  ControllerInput still = run(h, 5.0);
  still.estimate.v_W.setZero();
  const ControllerOutput e = faded.update(still);
  EXPECT_NEAR(e.thrust_des_N, m * kGravity / (1.0 + fade * F), 0.02);
}

}  // namespace
