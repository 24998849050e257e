// SPDX-License-Identifier: BSD-3-Clause
// The robustness suite and the fault campaign from sweep files (experiments/suite_sweep.hpp):
// the shipped files are the grids the suites' documents describe, a file's grid is the grid the
// suite flies, and a file a suite cannot fly is refused naming the file, the item and what the
// suite expects.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

#include "geaware/control/controller_params.hpp"
#include "geaware/experiments/suite_sweep.hpp"
#include "geaware/experiments/table_one.hpp"
#include "geaware/experiments/world_setup.hpp"
#include "geaware/io/config_error.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "sweep_support.hpp"

namespace ex = geaware::experiments;
using geaware::sweep_test::sourceDir;
using ::testing::HasSubstr;

namespace {

ex::SweepSpec parse(const std::string& text) {
  return ex::parseSweepYaml(text, "suite.yaml", sourceDir() / "tests/sweep");
}

const std::string kHead = "format_version: 1\nvehicle: builtin\nworld: default\ncalibrate: true\n";
const std::string kLow = "{type: lemniscate, height_m: 0.12, speed_mps: 1.0, half_extent_x_m: 1.5, half_extent_y_m: 0.8}";

/// The problems `of` finds in the sweep `text`, keyed "key: message"; a failure when it
/// accepts the file or does not name it.
template <class Of>
std::vector<std::string> refusal(const std::string& text, Of of) {
  const ex::SweepSpec spec = parse(text);
  try {
    (void)of(spec);
  } catch (const geaware::io::ConfigError& e) {
    EXPECT_EQ(e.file(), "suite.yaml");
    EXPECT_THAT(e.what(), HasSubstr("suite.yaml: key '"));
    std::vector<std::string> out;
    for (const auto& p : e.problems()) out.push_back(p.key + ": " + p.message);
    return out;
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return {};
}

/// `problems` are one for each of `expected` (in any order), each containing its words.
void expectProblems(const std::vector<std::string>& problems, const std::vector<std::string>& expected) {
  EXPECT_EQ(problems.size(), expected.size());
  for (const auto& words : expected) {
    const auto n = std::count_if(problems.begin(), problems.end(),
                                 [&](const std::string& p) { return p.find(words) != std::string::npos; });
    EXPECT_EQ(n, 1) << "problems with \"" << words << "\"";
  }
  for (const auto& p : problems) std::cout << "  " << p << "\n";  // the messages, as a user reads them
}

std::vector<std::string> names(const std::vector<ex::SuiteController>& cs) {
  std::vector<std::string> out;
  for (const auto& c : cs) out.push_back(c.name);
  return out;
}

/// Every field of two lemniscates equal.
void expectSameLemniscate(const geaware::traj::LemniscateParams& a, const geaware::traj::LemniscateParams& b) {
  EXPECT_EQ(a.centre_xy_m, b.centre_xy_m);
  EXPECT_EQ(a.half_extent_x_m, b.half_extent_x_m);
  EXPECT_EQ(a.half_extent_y_m, b.half_extent_y_m);
  EXPECT_EQ(a.height_m, b.height_m);
  EXPECT_EQ(a.height_swing_m, b.height_swing_m);
  EXPECT_EQ(a.peak_speed_mps, b.peak_speed_mps);
  EXPECT_EQ(a.laps, b.laps);
  EXPECT_EQ(a.ramp_time_s, b.ramp_time_s);
  EXPECT_EQ(a.yaw_rad, b.yaw_rad);
}

}  // namespace

TEST(SuiteSweep, TheShippedRobustnessFileIsTheSuiteOfDocsRobustness) {
  const ex::RobustnessOptions o =
      ex::robustnessOptionsOf(ex::loadSweepFile(sourceDir() / "config/sweeps/robustness.yaml"));
  // Every named case, in the order the sweep file can name them.
  const auto cells = ex::robustnessCells();
  ASSERT_EQ(o.cells.size(), cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    EXPECT_EQ(o.cells[i].name, cells[i].name);
    EXPECT_EQ(o.cells[i].kind, cells[i].kind);
    EXPECT_EQ(o.cells[i].value, cells[i].value);
    EXPECT_EQ(o.cells[i].law, cells[i].law);
  }
  // Table I's distinct ACC:TORQUE pairs in order of first appearance, indi:indi, recommended.
  std::vector<std::string> want;
  for (const auto& e : ex::tableOneExperiments()) {
    const std::string name = geaware::control::configurationName(e.controller());
    if (!e.recommended && std::find(want.begin(), want.end(), name) == want.end()) want.push_back(name);
  }
  want.push_back("indi:indi");
  want.push_back("recommended");
  EXPECT_EQ(names(o.controllers), want);
  // Exps 1's and 6's lemniscates, exactly as the campaign flies them.
  ASSERT_EQ(o.conditions.size(), 2u);
  const int rows[] = {1, 6};
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(o.conditions[i].experiment, rows[i]);
    expectSameLemniscate(o.conditions[i].lemniscate, ex::lemniscateFor(ex::tableOneExperiment(rows[i])));
  }
  EXPECT_EQ(o.conditions[0].describe(), "exp 1's lemniscate");
  // 5 seeds from 1, the campaign's hover, the built-in vehicle in its default world.
  EXPECT_EQ(o.seeds, 5);
  EXPECT_EQ(o.first_seed, 1u);
  EXPECT_EQ(o.start_hover_s, 3.0);
  ASSERT_TRUE(o.world.has_value());
  EXPECT_EQ(o.world->source, ex::defaultWorld(geaware::io::builtinVehicle(), true, "").source);
  EXPECT_EQ(o.vehicle.name, geaware::io::builtinVehicle().name);
  EXPECT_FALSE(o.controller_values.has_value());
}

TEST(SuiteSweep, TheShippedFaultFileIsTheCampaignOfDocsReliability) {
  const ex::FaultSuiteOptions o = ex::faultSuiteOptionsOf(ex::loadSweepFile(sourceDir() / "config/sweeps/faults.yaml"));
  // Every fault case, "none" first, with the suite's names ("gyro bias 2°/s", not the key's).
  const auto cases = ex::faultCases();
  ASSERT_EQ(o.cases.size(), cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    EXPECT_EQ(o.cases[i].name, cases[i].name);
    EXPECT_EQ(o.cases[i].faults.size(), cases[i].faults.size());
    EXPECT_EQ(o.cases[i].mass_scale, cases[i].mass_scale);
    EXPECT_EQ(o.cases[i].survivable, cases[i].survivable);
    EXPECT_EQ(o.cases[i].low_imu_ranges, cases[i].low_imu_ranges);
  }
  // Exp 2's, exp 5's and the recommended configuration, in Table I's order.
  EXPECT_EQ(names(o.controllers), (std::vector<std::string>{"indi:none", "model:model_indi", "recommended"}));
  // Exp 1's lemniscate at 0.12 m and 1 m, 1 m/s.
  ASSERT_EQ(o.conditions.size(), 2u);
  const double heights[] = {0.12, 1.0};
  for (std::size_t i = 0; i < 2; ++i) {
    auto want = ex::lemniscateFor(ex::tableOneExperiment(1));
    want.height_m = heights[i];
    EXPECT_EQ(o.conditions[i].experiment, 1);
    expectSameLemniscate(o.conditions[i].lemniscate, want);
  }
  // `bench --suite faults` has flown 5 seeds by default.
  EXPECT_EQ(o.seeds, 5);
  EXPECT_EQ(o.first_seed, 1u);
  EXPECT_EQ(o.start_hover_s, 3.0);
}

TEST(SuiteSweep, AFilesGridIsTheGridTheSuiteFlies) {
  const ex::RobustnessOptions r = ex::robustnessOptionsOf(parse(
      kHead + "start_hover_s: 1.5\n"
              "perturbations: [{name: mass+10%}, {kind: cog, value: 0.02, name: cog2}]\n"
              "controllers: [recommended, indi:none]\n"
              "scenarios: [" + kLow + ", {type: lemniscate, height_m: 0.4, speed_mps: 2.0, half_extent_x_m: 2.0, "
              "half_extent_y_m: 1.0, name: wide}]\n"
              "seeds: {first: 7, count: 2}\n"));
  ASSERT_EQ(r.cells.size(), 2u);
  EXPECT_EQ(r.cells[0].name, "mass+10%");
  EXPECT_EQ(r.cells[0].value, 0.10);
  EXPECT_EQ(r.cells[1].name, "cog2");
  EXPECT_EQ(r.cells[1].kind, ex::PerturbationKind::kCogOffset);
  EXPECT_EQ(r.cells[1].value, 0.02);
  EXPECT_EQ(names(r.controllers), (std::vector<std::string>{"recommended", "indi:none"}));
  ASSERT_EQ(r.conditions.size(), 2u);
  EXPECT_EQ(r.conditions[0].experiment, 1);
  EXPECT_EQ(r.conditions[1].name, "wide");
  EXPECT_EQ(r.conditions[1].experiment, 0);  // no Table I row's shape
  EXPECT_EQ(r.conditions[1].height_m(), 0.4);
  EXPECT_EQ(r.conditions[1].speed_mps(), 2.0);
  EXPECT_EQ(r.conditions[1].lemniscate.half_extent_x_m, 2.0);
  EXPECT_EQ(r.seeds, 2);
  EXPECT_EQ(r.first_seed, 7u);
  EXPECT_EQ(r.start_hover_s, 1.5);

  const ex::FaultSuiteOptions f = ex::faultSuiteOptionsOf(parse(
      kHead + "perturbations: [{fault: none}, {fault: motor 50%}, {fault: gust 2m/s, name: gust}]\n"
              "controllers: [recommended]\nscenarios: [" + kLow + "]\nseeds: {first: 3, count: 1}\n"));
  ASSERT_EQ(f.cases.size(), 3u);
  EXPECT_EQ(f.cases[0].name, "none");
  EXPECT_TRUE(f.cases[0].faults.empty());
  EXPECT_EQ(f.cases[1].name, "motor 50%");
  EXPECT_EQ(f.cases[2].name, "gust");  // the file's name for the suite's "gust 2m/s"
  ASSERT_EQ(f.cases[2].faults.size(), 1u);
  EXPECT_EQ(f.cases[2].faults[0].kind, geaware::experiments::FaultKind::kGust);
  EXPECT_EQ(names(f.controllers), std::vector<std::string>{"recommended"});
  EXPECT_EQ(f.seeds, 1);
  EXPECT_EQ(f.first_seed, 3u);
}

TEST(SuiteSweep, TheRobustnessSuiteRefusesFaultsOtherScenariosAndNoCalibration) {
  const auto problems = refusal(
      "format_version: 1\nvehicle: builtin\nworld: default\ncalibrate: false\n"
      "perturbations: [{name: none}, {fault: motor 80%}]\ncontrollers: [recommended]\n"
      "scenarios: [" + kLow + ", {type: file, file: ../../config/scenarios/step_5cm.yaml, name: step},\n"
      "  {type: lemniscate, height_m: 0.12, speed_mps: 2.0, half_extent_x_m: 2.0, half_extent_y_m: 1.0, name: fast}]\n"
      "seeds: {first: 1, count: 1}\n",
      &ex::robustnessOptionsOf);
  expectProblems(problems, {"calibrate: got false: the robustness suite calibrates the belief",
                            "perturbations[1]: 'motor 80%' is a case of the fault campaign",
                            "scenarios[1]: 'step': the robustness suite flies lemniscates over flat ground",
                            "scenarios[2]: 'fast' flies at 0.12 m like 'lem-0.12m-1mps': expected one scenario per "
                            "height"});
}

TEST(SuiteSweep, TheFaultCampaignRefusesTruthChangesAMissingBaselineAndNeuralControllers) {
  const auto problems = refusal(kHead + "perturbations: [{fault: motor 80%}, {name: mass+10%}]\n"
                                        "controllers: [neural:none, recommended]\nscenarios: [" + kLow + "]\n"
                                        "seeds: {first: 1, count: 1}\n",
                                &ex::faultSuiteOptionsOf);
  expectProblems(problems, {"perturbations[0]: got 'motor 80%': expected `fault: none` first",
                            "perturbations[1]: 'mass+10%' is a case of the robustness suite: the fault campaign breaks",
                            "controllers[0]: 'neural:none': the fault campaign trains no Neural-Lander"});
  // The baseline renamed is no baseline: the campaign's judgement needs "none".
  expectProblems(refusal(kHead + "perturbations: [{fault: none, name: base}]\ncontrollers: [recommended]\n"
                                 "scenarios: [" + kLow + "]\nseeds: {first: 1, count: 1}\n",
                         &ex::faultSuiteOptionsOf),
                 {"perturbations[0]: got 'base': expected `fault: none` first"});
}
