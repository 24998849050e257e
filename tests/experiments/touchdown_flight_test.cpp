// SPDX-License-Identifier: BSD-3-Clause
// Landing and take-off through ground effect in the as-built world (issue 13 item 5): the
// recommended controller touches down under 0.15 m/s without a bounce over 1 cm and the land
// detector takes the motors down; without the contact model the same landing ends in a strike
// of a foot (the behaviour before it); a take-off leaves the ground at the climb, level, once.
#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "geaware/control/controller_params.hpp"
#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/flight_setup.hpp"
#include "geaware/experiments/world_setup.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/sim/terrains.hpp"
#include "geaware/traj/touchdown.hpp"

namespace geaware::experiments {
namespace {

FlightScenario touchdownFlight(const std::string& controller, const std::string& kind, std::uint64_t seed) {
  FlightScenario s;
  s.vehicle = io::builtinVehicle();
  applyWorld(s, defaultWorld(s.vehicle, true, ""));  // the as-built world
  EXPECT_TRUE(control::parseConfiguration(controller, s.controller));
  TrajectoryOptions t;
  t.lemniscate = false;
  t.kind = kind;
  t.from_height_m = 1.0;
  t.height_m = 1.0;
  t.speed_mps = 0.5;  // descent / climb rate
  t.touchdown_height_m = s.vehicle.min_rotor_plane_height_m;
  s.trajectory = makeTrajectory(t);
  applyTouchdown(s);
  s.seed = seed;
  return s;
}

TEST(TouchdownFlight, RecommendedLandsSoftlyAndTheDetectorTakesTheMotorsDown) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    const FlightScenario s = touchdownFlight("recommended", "landing", seed);
    ASSERT_TRUE(s.plant.ground_contact);
    ASSERT_TRUE(s.land_detector.has_value());
    EXPECT_FALSE(s.controller.clearance_guard);
    const FlightResult r = runFlight(s);
    ASSERT_FALSE(r.crash) << r.crash_description;
    ASSERT_TRUE(r.ground_contact.has_value());
    const GroundContactSummary& g = *r.ground_contact;
    EXPECT_TRUE(g.touched);
    EXPECT_GT(g.touchdown_speed_mps, 0.0);
    EXPECT_LE(g.touchdown_speed_mps, 0.15);
    EXPECT_LE(g.bounce_m, 0.01);
    EXPECT_TRUE(g.landed);
    EXPECT_GT(g.landed_t_s, g.touchdown_t_s);
    EXPECT_EQ(g.feet_down_at_end, 4);
    EXPECT_LT(g.max_compression_m, 0.01);
    EXPECT_LT(g.max_tilt_on_ground_deg, 5.0);
    EXPECT_EQ(r.flag_counts[9], 0u) << "motor_failure flagged on the ground";
  }
}

TEST(TouchdownFlight, WithoutTheContactModelTheSameLandingStrikesAFoot) {
  FlightScenario s = touchdownFlight("recommended", "landing", 1);
  s.plant.ground_contact = false;
  const FlightResult r = runFlight(s);
  ASSERT_TRUE(r.crash);
  EXPECT_EQ(r.crash->part, sim::StrikePart::kLandingFoot);
  EXPECT_FALSE(r.ground_contact.has_value());
}

TEST(TouchdownFlight, RecommendedTakesOffAtTheClimbLevelAndOnce) {
  const FlightScenario s = touchdownFlight("recommended", "takeoff", 2);
  ASSERT_TRUE(s.start_on_ground);
  const FlightResult r = runFlight(s);
  ASSERT_FALSE(r.crash) << r.crash_description;
  const GroundContactSummary& g = r.ground_contact.value();
  // On the ground for the start hover (1 s) and the hold (1 s); off it within the climb's ramp.
  EXPECT_GT(g.liftoff_t_s, 1.9);
  EXPECT_LT(g.liftoff_t_s, 3.0);
  EXPECT_EQ(g.recontacts, 0);
  EXPECT_LT(g.max_tilt_on_ground_deg, 5.0);
  EXPECT_TRUE(std::isnan(g.touchdown_t_s));
  EXPECT_EQ(g.feet_down_at_end, 0);
  EXPECT_LT(r.tracking.rmse_all_m, 0.05);
}

TEST(TouchdownFlight, StandingOnTheGearNeedsTheContactModel) {
  FlightScenario s = touchdownFlight("recommended", "takeoff", 1);
  s.plant.ground_contact = false;
  const auto problems = validate(s);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].field, "start_on_ground");
  s.plant.ground_contact = true;
  s.land_detector = control::LandDetectorParams{};
  s.land_detector->confirm_s = -1.0;
  const auto bad = validate(s);
  ASSERT_EQ(bad.size(), 1u);
  EXPECT_EQ(bad[0].field, "land_detector.confirm_s");
}

TEST(TouchdownFlight, AGearWithoutLegsOrAReferenceBesideTheSurfaceIsRefused) {
  FlightScenario s = touchdownFlight("recommended", "takeoff", 1);
  ASSERT_TRUE(validate(s).empty());
  // Legs of stiffness 0 (the truth file's "no contact model") cannot hold the vehicle.
  s.truth = sim::fromNominal(s.vehicle);
  s.truth->landing_gear.stiffness_N_per_m = 0.0;
  const auto legs = validate(s);
  ASSERT_EQ(legs.size(), 1u);
  EXPECT_EQ(legs[0].field, "truth.landing_gear.stiffness_N_per_m");
  // A touchdown height 5 cm above where the vehicle file's gear meets the floor.
  FlightScenario high = touchdownFlight("recommended", "landing", 1);
  TrajectoryOptions t;
  t.lemniscate = false;
  t.kind = "landing";
  t.from_height_m = 1.0;
  t.speed_mps = 0.5;
  t.touchdown_height_m = high.vehicle.min_rotor_plane_height_m + 0.05;
  high.trajectory = makeTrajectory(t);
  const auto off = validate(high);
  ASSERT_EQ(off.size(), 1u);
  EXPECT_EQ(off[0].field, "trajectory.touchdown_height_m");
  EXPECT_NE(off[0].expected.find("within 0.02 m"), std::string::npos);
}

TEST(TouchdownFlight, OnUnevenGroundTheTakeOffStartsWithNoFootUnderTheSurface) {
  FlightScenario s = touchdownFlight("recommended", "takeoff", 1);
  // A 10° slope under the take-off point: the uphill feet touch, the others hang.
  s.terrain = std::make_shared<sim::TiltedPlane>(
      sim::TiltedPlane::fromTilt(Eigen::Vector3d::Zero(), 0.0, 10.0 * std::numbers::pi / 180.0));
  s.check_feasibility = false;
  s.trajectory = std::make_shared<traj::TakeOff>([&] {
    traj::TakeOffParams p;
    p.touchdown_height_m = s.vehicle.min_rotor_plane_height_m;  // the surface is at 0 under (0, 0)
    p.to_height_m = 1.0;
    return p;
  }());
  const FlightResult r = runFlight(s);
  ASSERT_FALSE(r.crash) << r.crash_description;
  EXPECT_LT(r.ground_contact->max_compression_m, 0.01);
}

}  // namespace
}  // namespace geaware::experiments
