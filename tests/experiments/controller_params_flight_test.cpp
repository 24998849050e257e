// SPDX-License-Identifier: BSD-3-Clause
// A closed-loop flight with the shipped default controller-parameters file is bit-identical to
// the same flight without it (docs/controller-params.md), and a file that changes a gain changes
// the flight.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "geaware/control/controller_schema.hpp"
#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/world_setup.hpp"
#include "geaware/io/controller_params_file.hpp"
#include "test_scenarios.hpp"

namespace geaware::experiments {
namespace {

std::filesystem::path defaultFile() {
  const char* dir = std::getenv("GEAWARE_SOURCE_DIR");
  const std::filesystem::path root = dir != nullptr ? dir : std::filesystem::current_path();
  return root / "config/controller-params/default.yaml";
}

void expectSameFlight(const FlightResult& a, const FlightResult& b) {
  EXPECT_TRUE(a.completed && b.completed);
  EXPECT_EQ(a.tracking.rmse_all_m, b.tracking.rmse_all_m);
  EXPECT_EQ(a.tracking.max_m, b.tracking.max_m);
  EXPECT_EQ(a.tracking.samples, b.tracking.samples);
  EXPECT_EQ(a.controller_updates, b.controller_updates);
  EXPECT_EQ(a.flag_counts, b.flag_counts);
}

TEST(ControllerParamsFlight, DefaultFileFliesBitIdentically) {
  for (const char* name : {"recommended", "model:model_indi"}) {
    FlightScenario s = test::scenario(0.2, control::AccelerationCompensation::kModel,
                                      control::TorqueCompensation::kModelIndi);
    applyWorld(s, defaultWorld(s.vehicle, true, ""));
    ASSERT_TRUE(control::parseConfiguration(name, s.controller));
    s.seed = 3;
    FlightScenario with = s;
    with.controller = io::withControllerParamsFile(s.controller, defaultFile());
    expectSameFlight(runFlight(s), runFlight(with));
  }
}

TEST(ControllerParamsFlight, AChangedGainChangesTheFlight) {
  FlightScenario s = test::scenario(0.2, control::AccelerationCompensation::kModel,
                                    control::TorqueCompensation::kModelIndi);
  s.seed = 3;
  control::ControllerParams v = io::loadControllerParamsFile(defaultFile());
  v.k_p_per_s2 *= 0.5;
  FlightScenario softer = s;
  softer.controller = control::applyParameters(s.controller, v);
  const FlightResult a = runFlight(s);
  const FlightResult b = runFlight(softer);
  ASSERT_TRUE(a.completed && b.completed);
  EXPECT_NE(a.tracking.rmse_all_m, b.tracking.rmse_all_m);
}

}  // namespace
}  // namespace geaware::experiments
