// SPDX-License-Identifier: BSD-3-Clause
// Scenario validation: every offending field named, an impossible trajectory refused before
// flying.
#include "geaware/experiments/flight.hpp"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_scenarios.hpp"

namespace geaware::experiments {
namespace {

using control::AccelerationCompensation;
using control::TorqueCompensation;
using test::lemniscate;
using test::scenario;

// ---------------------------------------------------------------------------------------------
// Validation
// ---------------------------------------------------------------------------------------------

bool mentions(const std::vector<ScenarioProblem>& problems, const std::string& field,
              const std::string& text = "") {
  for (const auto& p : problems) {
    if (p.field == field && (p.value + p.expected).find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(FlightScenarioValidation, ADefaultScenarioWithATrajectoryIsValid) {
  EXPECT_TRUE(
      validate(scenario(1.0, AccelerationCompensation::kModel, TorqueCompensation::kModelIndi))
          .empty());
}

TEST(FlightScenarioValidation, NamesEveryOffendingField) {
  FlightScenario s;
  s.vehicle = io::builtinVehicle();
  s.vehicle.mass_kg = -1.0;
  s.controller.acceleration = AccelerationCompensation::kNeural;
  s.controller.rate_hz = 300.0;
  s.plant_rate_hz = 1000.0;
  s.start_hover_s = -1.0;
  s.sensors.ranger.side = 40;
  s.eskf.imu_rate_hz = 100.0;
  s.disturbances.unsteadiness = true;
  s.disturbances.unsteadiness_params.correlation_time_s = 0.0;
  const auto problems = validate(s);
  EXPECT_TRUE(mentions(problems, "vehicle.mass_kg"));
  EXPECT_TRUE(mentions(problems, "trajectory", "a trajectory to fly"));
  EXPECT_TRUE(mentions(problems, "residual", "neural"));
  EXPECT_TRUE(mentions(problems, "plant_rate_hz", "multiple of controller.rate_hz"));
  EXPECT_TRUE(mentions(problems, "start_hover_s"));
  EXPECT_TRUE(mentions(problems, "sensors.ranger.side"));
  EXPECT_TRUE(mentions(problems, "eskf.imu_rate_hz", "sensors.imu.rate_Hz"));
  EXPECT_TRUE(mentions(problems, "disturbances.unsteadiness.correlation_time_s"));
  try {
    (void)runFlight(s);
    FAIL() << "runFlight accepted an invalid scenario";
  } catch (const InvalidScenario& e) {
    EXPECT_EQ(e.problems().size(), problems.size());
    EXPECT_NE(std::string(e.what()).find("vehicle.mass_kg"), std::string::npos) << e.what();
  }
}

TEST(FlightScenarioValidation, AnImpossibleTrajectoryIsRefusedBeforeFlying) {
  // 6 m/s through a ±1.5 m × ±0.8 m figure-eight needs ≈ 40 m/s² of lateral acceleration.
  FlightScenario s = scenario(1.0, AccelerationCompensation::kModel, TorqueCompensation::kModel);
  s.trajectory = lemniscate(1.0, 6.0);
  const auto problems = validate(s);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_TRUE(mentions(problems, "trajectory", "rotor speeds beyond the motors"))
      << problems[0].value;
  EXPECT_THROW((void)runFlight(s), InvalidScenario);
  s.check_feasibility = false;
  EXPECT_TRUE(validate(s).empty());
}

}  // namespace
}  // namespace geaware::experiments
