// SPDX-License-Identifier: BSD-3-Clause
// Per-rotor ground effect in the controller (ControllerParams::per_rotor_ground_effect, issue 13
// item 1): it reduces to the vehicle-level model over one plane bit for bit; partial ground
// effect (rotors beyond a table edge) is predicted with the sign the truth's per-rotor
// aerodynamics gives and compensated; the leveling torque acts toward a sloped ground's normal
// (closed form); an invalid ground shape keeps the last valid one.
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "geaware/control/controller.hpp"
#include "geaware/model/mixer.hpp"
#include "geaware/model/units.hpp"
#include "geaware/sim/rotor_aerodynamics.hpp"
#include "geaware/sim/truth_params.hpp"
#include "geaware_test/eigen_matchers.hpp"
#include "geaware_test/paper_vehicle.hpp"
#include "configurations.hpp"

namespace {

using namespace geaware::control;
using geaware::model::kGravity;
using geaware_test::hoverThrust;
using geaware_test::named;
using geaware_test::paperVehicle;

/// Hover at height h over one plane, slightly tilted, with a small position error and body
/// rate, so that every term of the controller is non-trivial.
ControllerInput input(double h, int k) {
  ControllerInput in;
  in.reference.p_W = Eigen::Vector3d(0.2, -0.1, h);
  in.estimate.p_W = in.reference.p_W + Eigen::Vector3d(0.01, -0.02, 0.003 * std::sin(0.1 * k));
  in.estimate.v_W = Eigen::Vector3d(0.05, 0.0, -0.01);
  in.estimate.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.02 * std::cos(0.05 * k), Eigen::Vector3d::UnitX()));
  in.gyro_B = Eigen::Vector3d(0.01, -0.02, 0.005);
  in.accel_B = Eigen::Vector3d(0.1, 0.0, kGravity);
  in.height_m = h;
  in.height_valid = true;
  in.rotor_speeds_rpm.setConstant(paperVehicle().hoverSpeedRpm(h));
  in.external_accel_W = Eigen::Vector3d(0.02, 0.01, 0.3);
  in.external_accel_valid = true;
  in.ground_shape_valid = true;
  return in;
}

/// A level hover exactly on the reference at height h over one plane: the thrust vector is
/// vertical, so a vertical feed-forward changes only its length.
ControllerInput levelHover(double h) {
  ControllerInput in;
  in.reference.p_W = Eigen::Vector3d(0.2, -0.1, h);
  in.estimate.p_W = in.reference.p_W;
  in.accel_B = Eigen::Vector3d(0.0, 0.0, kGravity);
  in.height_m = h;
  in.height_valid = true;
  in.rotor_speeds_rpm.setConstant(paperVehicle().hoverSpeedRpm(h));
  in.ground_shape_valid = true;
  return in;
}

/// Rotor offsets with the rotors at body x > 0 beyond an edge, δ farther from their surface.
std::array<double, 4> beyondEdgeAtPlusX(double delta_m) {
  const auto r = geaware::model::Mixer::rotorPositions_B(paperVehicle().params().diagonal_rotor_distance_m);
  std::array<double, 4> d{};
  for (std::size_t i = 0; i < 4; ++i) d[i] = r[i].x() > 0.0 ? delta_m : 0.0;
  return d;
}

TEST(PerRotorGroundEffect, ReducesToTheVehicleLevelModelOverOnePlaneBitForBit) {
  for (const std::string base : {"recommended", "model:model_indi", "model:model", "model:none", "none:model"}) {
    Controller with(paperVehicle(), named(base + "+rotors"));
    Controller without(paperVehicle(), named(base));
    for (int k = 0; k < 300; ++k) {
      const double h = 0.11 + 0.0005 * k;
      const ControllerOutput a = with.update(input(h, k));
      const ControllerOutput b = without.update(input(h, k));
      SCOPED_TRACE(base + " tick " + std::to_string(k));
      for (std::size_t i = 0; i < 4; ++i) ASSERT_EQ(a.throttle[i], b.throttle[i]);
      ASSERT_EQ(a.tau_des_B, b.tau_des_B);
      ASSERT_EQ(a.a_des_W, b.a_des_W);
      ASSERT_EQ(a.a_dob_W, b.a_dob_W);
      ASSERT_EQ(a.a_ground_shape_W, Eigen::Vector3d::Zero());
      ASSERT_EQ(a.tau_ground_shape_B, Eigen::Vector3d::Zero());
    }
  }
}

TEST(PerRotorGroundEffect, ATableEdgeTorqueHasTheTruthsSignAndIsCompensated) {
  const double h = 0.12, delta = 0.10;  // the rotors at +x are over a void 10 cm deeper
  const auto& ge = paperVehicle().groundEffect();
  Controller c(paperVehicle(), named("model:model+rotors"));
  Controller plain(paperVehicle(), named("model:model"));
  ControllerInput in = levelHover(h);
  in.rotor_height_offset_m = beyondEdgeAtPlusX(delta);
  const ControllerOutput a = c.update(in);
  const ControllerOutput b = plain.update(in);

  // Closed form: the two rotors beyond the edge lose T/4·(F_G(h) − F_G(h + δ)) each.
  const double df = ge.thrustRatio(h + delta) - ge.thrustRatio(h);
  ASSERT_LT(df, 0.0);
  const double arm_x = std::sqrt(2.0) * paperVehicle().params().diagonal_rotor_distance_m / 4.0;
  const double T = hoverThrust(h);  // the reference thrust, as the model uses it
  EXPECT_NEAR(a.tau_ground_shape_B.y(), -2.0 * arm_x * 0.25 * T * df, 1e-3 * std::abs(arm_x * T * df));
  EXPECT_NEAR(a.tau_ground_shape_B.x(), 0.0, 1e-12);
  const double a_z = 0.5 * df * T / paperVehicle().params().mass_kg;
  EXPECT_NEAR(a.a_ground_shape_W.z(), a_z, 1e-3 * std::abs(a_z));

  // The truth (per-rotor aerodynamics of the as-calibrated world) over the same edge: the rotors
  // nearer their surface make more thrust, so the vehicle is pushed towards the void (+τ_y
  // turns z_B towards +x). The controller predicts the same sign…
  const geaware::sim::TruthParams truth = geaware::sim::fromNominal(geaware_test::paperParams());
  const geaware::sim::RotorAerodynamics aero(truth.rotorGeometry(), truth.aero);
  geaware::sim::RotorSurroundings over_edge, over_floor;
  for (std::size_t i = 0; i < 4; ++i) {
    const double x = truth.rotorGeometry().position_B[i].x();
    over_edge.ground_distance_m[i] = h + (x > 0.0 ? delta : 0.0);
    over_floor.ground_distance_m[i] = h;
  }
  std::array<double, 4> n{};
  n.fill(paperVehicle().hoverSpeedRpm(h));
  const auto R = Eigen::Matrix3d::Identity();
  const double tau_truth = aero.compute(n, R, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), over_edge).wrench.torque_B.y() -
                           aero.compute(n, R, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), over_floor).wrench.torque_B.y();
  EXPECT_GT(tau_truth, 0.0);
  EXPECT_GT(a.tau_ground_shape_B.y(), 0.0);
  // …and commands the opposite torque, with more collective thrust for the lift it lost.
  EXPECT_NEAR(a.tau_des_B.y() - b.tau_des_B.y(), -a.tau_ground_shape_B.y(), 1e-9);
  EXPECT_GT(a.thrust_des_N, b.thrust_des_N);
}

TEST(PerRotorGroundEffect, TorqueIndiFeedsForwardOnlyWhatItsFilterDoesNotHoldYet) {
  // With torque INDI the rotors' measured torque already answers a steady ground torque; the
  // prediction is fed forward at the step and fades as the filtered measurement takes over.
  Controller c(paperVehicle(), named("model:model_indi+rotors"));
  Controller plain(paperVehicle(), named("model:model_indi"));
  ControllerInput in = levelHover(0.12);
  for (int k = 0; k < 50; ++k) {
    (void)c.update(in);
    (void)plain.update(in);
  }
  in.rotor_height_offset_m = beyondEdgeAtPlusX(0.10);
  ControllerOutput a = c.update(in), b = plain.update(in);
  const double first = a.tau_des_B.y() - b.tau_des_B.y();
  EXPECT_LT(first, -0.5 * a.tau_ground_shape_B.y()) << "most of the step is fed forward at once";
  for (int k = 0; k < 400; ++k) {
    a = c.update(in);
    b = plain.update(in);
  }
  EXPECT_NEAR(a.tau_des_B.y() - b.tau_des_B.y(), 0.0, 1e-3 * a.tau_ground_shape_B.y())
      << "a steady torque is not cancelled twice";
}

TEST(PerRotorGroundEffect, LevelingActsTowardASlopedGroundsNormal) {
  const double h = 0.15, slope = 10.0 * geaware::model::kDegToRad;
  Controller c(paperVehicle(), named("model:model+rotors"));
  ControllerInput in = levelHover(h);
  in.ground_normal_W = Eigen::Vector3d(std::sin(slope), 0.0, std::cos(slope));
  const ControllerOutput out = c.update(in);
  // M_G·T·(z_B × n) − M_G·T·(z_B × z_W) with z_B = z_W: M_G·T·(0, sin σ, 0).
  const double tau_y = paperVehicle().groundEffect().levelingCoefficient(h) * hoverThrust(h) * std::sin(slope);
  EXPECT_NEAR(out.tau_ground_shape_B.y(), tau_y, 1e-3 * tau_y);
  EXPECT_NEAR(out.tau_ground_shape_B.x(), 0.0, 1e-12);
  EXPECT_NEAR(out.tau_ground_shape_B.z(), 0.0, 1e-12);
  EXPECT_GT(tau_y, 0.0) << "toward the normal: z_B turns to +x";
}

TEST(PerRotorGroundEffect, AnInvalidGroundShapeKeepsTheLastValidOne) {
  Controller c(paperVehicle(), named("model:model+rotors"));
  ControllerInput in = input(0.12, 0);
  in.rotor_height_offset_m = beyondEdgeAtPlusX(0.10);
  const ControllerOutput valid = c.update(in);
  ASSERT_GT(valid.tau_ground_shape_B.y(), 0.0);
  const auto again = [&](ControllerInput bad) {
    bad.rotor_height_offset_m = std::array<double, 4>{};  // would be "one plane" if read
    return c.update(bad).tau_ground_shape_B.y();
  };
  ControllerInput missing = in;
  missing.ground_shape_valid = false;
  EXPECT_NEAR(again(missing), valid.tau_ground_shape_B.y(), 1e-9);
  ControllerInput nan_normal = in;
  nan_normal.ground_normal_W.x() = std::nan("");
  EXPECT_NEAR(again(nan_normal), valid.tau_ground_shape_B.y(), 1e-9);
  ControllerInput wall = in;
  wall.ground_normal_W = Eigen::Vector3d::UnitX();  // not ground
  EXPECT_NEAR(again(wall), valid.tau_ground_shape_B.y(), 1e-9);
  ControllerInput inf_offset = in;
  inf_offset.rotor_height_offset_m[0] = std::numeric_limits<double>::infinity();
  EXPECT_NEAR(c.update(inf_offset).tau_ground_shape_B.y(), valid.tau_ground_shape_B.y(), 1e-9);
}

TEST(PerRotorGroundEffect, TheSwitchIsAConfigurationSuffixAndNeedsAModelTerm) {
  ControllerParams p;
  ASSERT_TRUE(parseConfiguration("recommended+rotors", p));
  EXPECT_TRUE(p.per_rotor_ground_effect);
  EXPECT_EQ(configurationName(p), "recommended+rotors");
  ASSERT_TRUE(parseConfiguration("model:model_indi+rotors+learn0", p));
  EXPECT_TRUE(p.per_rotor_ground_effect);
  EXPECT_EQ(p.learn_ground_effect, GroundEffectLearning::kFromNothing);
  EXPECT_EQ(configurationName(p), "model:model_indi+rotors+learn0");
  ASSERT_TRUE(parseConfiguration("model:model_indi", p));
  EXPECT_FALSE(p.per_rotor_ground_effect) << "parsing a name sets every switch";
  ASSERT_TRUE(parseConfiguration("indi:indi+rotors", p));
  const auto errors = p.validate();
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].field, "per_rotor_ground_effect");
  EXPECT_NE(errors[0].expected.find("indi:indi"), std::string::npos) << errors[0].expected;
}

}  // namespace
