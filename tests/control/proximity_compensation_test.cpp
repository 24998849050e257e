// SPDX-License-Identifier: BSD-3-Clause
// The ceiling and wall feed-forward (ControllerParams::proximity_compensation, issue 13 item 4):
// without a beam that sees a surface it changes nothing, bit for bit (so every table flown
// without obstacles is unchanged); with an upward or sideways beam it feeds forward the image
// law's force in closed form, with the truth's sign (sim::ProximityContribution as the oracle).
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "geaware/control/controller.hpp"
#include "geaware/model/mixer.hpp"
#include "geaware/sim/obstacles.hpp"
#include "geaware/sim/truth_params.hpp"
#include "geaware_test/paper_vehicle.hpp"
#include "configurations.hpp"

namespace {

using namespace geaware::control;
using geaware::model::kGravity;
using geaware_test::hoverThrust;
using geaware_test::named;
using geaware_test::paperVehicle;

ControllerInput hover(double h, int k = 0) {
  ControllerInput in;
  in.reference.p_W = Eigen::Vector3d(0.2, -0.1, h);
  in.estimate.p_W = in.reference.p_W + Eigen::Vector3d(0.01, -0.02, 0.003 * std::sin(0.1 * k));
  in.estimate.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.02 * std::cos(0.05 * k), Eigen::Vector3d::UnitX()));
  in.accel_B = Eigen::Vector3d(0.0, 0.0, kGravity);
  in.height_m = h;
  in.height_valid = true;
  in.rotor_speeds_rpm.setConstant(paperVehicle().hoverSpeedRpm(h));
  in.external_accel_W = Eigen::Vector3d(0.02, 0.01, 0.3);
  in.external_accel_valid = true;
  return in;
}

geaware::model::BeamReading beam(const Eigen::Vector3d& dir_B, double range_m) {
  geaware::model::BeamReading b;
  b.direction_B = dir_B;
  b.range_m = range_m;
  b.valid = true;
  return b;
}

TEST(ProximityCompensation, WithoutASurfaceInABeamNothingChangesBitForBit) {
  ControllerParams rec_off = recommendedControllerParams();
  rec_off.proximity_compensation = false;
  const std::array<std::pair<ControllerParams, ControllerParams>, 3> pairs{
      std::pair{recommendedControllerParams(), rec_off},
      std::pair{named("model:model_indi+proximity"), named("model:model_indi")},
      std::pair{named("indi:none+proximity"), named("indi:none")}};
  for (const auto& [on, off] : pairs) {
    Controller with(paperVehicle(), on);
    Controller without(paperVehicle(), off);
    for (int k = 0; k < 300; ++k) {
      ControllerInput in = hover(0.3 + 0.001 * k, k);
      // A beam without a return, and one that looks down at the floor (the lattice's business).
      in.beams[0] = beam(Eigen::Vector3d::UnitZ(), 0.2);
      in.beams[0].valid = false;
      in.beams[1] = beam(-Eigen::Vector3d::UnitZ(), 0.3);
      const ControllerOutput a = with.update(in);
      const ControllerOutput b = without.update(in);
      SCOPED_TRACE(configurationName(on) + " tick " + std::to_string(k));
      for (std::size_t i = 0; i < 4; ++i) ASSERT_EQ(a.throttle[i], b.throttle[i]);
      ASSERT_EQ(a.tau_des_B, b.tau_des_B);
      ASSERT_EQ(a.a_des_W, b.a_des_W);
      ASSERT_EQ(a.a_dob_W, b.a_dob_W);
    }
  }
}

/// Two ticks 20 ms apart, each with a new reading of the same beams (a beam is fed forward once
/// two successive readings agree), for `with` and `without`; the second tick's outputs.
std::pair<ControllerOutput, ControllerOutput> twoTicks(Controller& with, Controller& without, ControllerInput in) {
  for (int k = 0;; ++k) {
    in.t_s = 0.02 * k;
    for (auto& b : in.beams) b.t_s = in.t_s;
    const ControllerOutput a = with.update(in);
    const ControllerOutput b = without.update(in);
    if (k == 1) return {a, b};
  }
}

ControllerInput levelHover(double h) {
  ControllerInput in = hover(h);
  in.estimate.p_W = in.reference.p_W;
  in.estimate.q_WB.setIdentity();
  return in;
}

TEST(ProximityCompensation, ACeilingOverheadIsFedForwardInClosedForm) {
  const double h = 1.0, d = 0.15;
  Controller c(paperVehicle(), named("model:model+proximity"));
  Controller plain(paperVehicle(), named("model:model"));
  ControllerInput in = levelHover(h);
  in.beams[0] = beam(Eigen::Vector3d::UnitZ(), d);
  const auto [a, b] = twoTicks(c, plain, in);
  const double R = paperVehicle().params().propeller_radius_m;
  const double k = R / (4.0 * d);
  const double ratio = 1.0 / (1.0 - k * k);
  // The rotors make T/ratio; the ceiling gives T·(1 − 1/ratio).
  const double pull = hoverThrust(h) * (1.0 - 1.0 / ratio) / paperVehicle().params().mass_kg;
  EXPECT_NEAR(b.a_des_W.z() - a.a_des_W.z(), pull, 1e-9 * pull);
  EXPECT_LT(a.thrust_des_N, b.thrust_des_N);  // less thrust: the ceiling gives the rest
  EXPECT_NEAR((a.tau_des_B - b.tau_des_B).norm(), 0.0, 1e-12);
}

TEST(ProximityCompensation, AWallIsFedForwardAsTheTruthPullsIt) {
  const double h = 1.0, d = 0.33;  // the +y beam meets a wall 0.33 m from the centre
  Controller c(paperVehicle(), named("model:model+proximity"));
  Controller plain(paperVehicle(), named("model:model"));
  ControllerInput in = levelHover(h);
  in.beams[2] = beam(Eigen::Vector3d::UnitY(), d);
  const auto [a, b] = twoTicks(c, plain, in);
  const double R = paperVehicle().params().propeller_radius_m;
  const auto rotors = geaware::model::Mixer::rotorPositions_B(paperVehicle().params().diagonal_rotor_distance_m);
  double pull = 0.0;
  for (const Eigen::Vector3d& r : rotors) pull += 0.25 * hoverThrust(h) * R * R / (32.0 * (d - r.y()) * (d - r.y()));
  pull /= paperVehicle().params().mass_kg;
  EXPECT_GT(pull, 0.0);
  EXPECT_NEAR(b.a_des_W.y() - a.a_des_W.y(), pull, 1e-9 * pull);
  // The truth's pull on the same vehicle at the same wall, hovering at the same rotor speed:
  // toward the wall, and as large within the truth's rotor-by-rotor thrust at hover speed.
  const geaware::sim::TruthParams truth = geaware::sim::fromNominal(geaware_test::paperParams());
  geaware::sim::ProximityContribution oracle(
      truth, std::make_shared<const geaware::sim::Obstacles>(std::vector<geaware::sim::Box>{geaware::sim::boxFromCorners(
                 Eigen::Vector3d(-5, d, -5), Eigen::Vector3d(5, d + 0.2, 5))}));
  geaware::sim::ContributionContext ctx;
  ctx.n_rpm.fill(paperVehicle().hoverSpeedRpm(h));
  EXPECT_NEAR(oracle.wrench(ctx).force_B.y() / truth.mass_kg, pull, 0.02 * pull);
}

TEST(ProximityCompensation, ALoneOutlierIsNotFedForward) {
  // One reading of 2 cm (the ranger's outliers are uniform over its range) between readings of
  // nothing: never two that agree, so no feed-forward at all.
  Controller c(paperVehicle(), named("model:model+proximity"));
  Controller plain(paperVehicle(), named("model:model"));
  ControllerInput in = levelHover(1.0);
  for (int k = 0; k < 6; ++k) {
    in.t_s = 0.02 * k;
    in.beams[0] = beam(Eigen::Vector3d::UnitZ(), 0.02);
    in.beams[0].t_s = in.t_s;
    in.beams[0].valid = k == 3;
    const ControllerOutput a = c.update(in);
    const ControllerOutput b = plain.update(in);
    ASSERT_EQ(a.a_des_W, b.a_des_W) << k;
  }
}

TEST(ProximityCompensation, TranslationalIndiMeasuresTheForce) {
  Controller c(paperVehicle(), named("indi:model+proximity"));
  Controller plain(paperVehicle(), named("indi:model"));
  ControllerInput in = hover(1.0);
  in.beams[0] = beam(Eigen::Vector3d::UnitZ(), 0.15);
  const auto [a, b] = twoTicks(c, plain, in);
  EXPECT_EQ(a.a_des_W, b.a_des_W);
}

TEST(ProximityCompensation, TheLearnerTakesNoSampleUnderACeiling) {
  // The observer's estimate holds the ceiling's pull too; F_G would learn it as ground effect.
  for (const bool ceiling : {false, true}) {
    Controller c(paperVehicle(), named("model:model_indi+proximity+learn"));
    ControllerInput in = hover(0.2);
    for (int k = 0; k < 200; ++k) {
      in.t_s = 0.005 * k;
      in.beams[0] = beam(Eigen::Vector3d::UnitZ(), 0.15);
      in.beams[0].t_s = 0.02 * (k / 4);
      in.beams[0].valid = ceiling;
      (void)c.update(in);
    }
    ASSERT_NE(c.learner(), nullptr);
    if (ceiling) {
      EXPECT_EQ(c.learner()->used(), 0u);
    } else {
      EXPECT_GT(c.learner()->used(), 0u);
    }
  }
}

TEST(ProximityCompensation, TheSwitchIsInRecommendedAndASuffixElsewhere) {
  EXPECT_TRUE(recommendedControllerParams().proximity_compensation);
  EXPECT_EQ(configurationName(recommendedControllerParams()), "recommended");
  const ControllerParams p = named("model:model_indi+proximity+rotors+learn");
  EXPECT_TRUE(p.proximity_compensation);
  EXPECT_TRUE(p.per_rotor_ground_effect);
  EXPECT_EQ(configurationName(p), "model:model_indi+proximity+rotors+learn");
  EXPECT_FALSE(named("model:model_indi").proximity_compensation);
  ControllerParams q;
  EXPECT_FALSE(parseConfiguration("recommended+proximity", q));
}

}  // namespace
