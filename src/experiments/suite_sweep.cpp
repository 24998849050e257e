// SPDX-License-Identifier: BSD-3-Clause
// The robustness suite and the fault campaign from sweep files (experiments/suite_sweep.hpp).

#include "geaware/experiments/suite_sweep.hpp"

#include <fmt/format.h>

#include <string>
#include <utility>
#include <vector>

#include "geaware/io/config_error.hpp"
#include "geaware/traj/lemniscate.hpp"

namespace geaware::experiments {
namespace {

using Problems = std::vector<io::ConfigProblem>;

std::string item(const char* list, std::size_t i) { return fmt::format("{}[{}]", list, i); }

/// The scenarios as the suite's heights/speeds: lemniscates over flat ground, one per height
/// (the suite tells a case's and controller's cells apart by their height).
std::vector<SuiteCondition> conditionsOf(const SweepSpec& spec, const std::string& suite, Problems& problems) {
  std::vector<SuiteCondition> out;
  for (std::size_t i = 0; i < spec.scenarios.size(); ++i) {
    const SweepScenario& s = spec.scenarios[i];
    const auto* lemniscate = dynamic_cast<const traj::Lemniscate*>(s.trajectory.get());
    if (lemniscate == nullptr || s.terrain || s.obstacles || !s.beam_rangers.empty()) {
      problems.push_back({0, item("scenarios", i),
                          fmt::format("'{}': the {} flies lemniscates over flat ground: expected `type: "
                                      "lemniscate` (fly other scenarios with `geaware sweep`)",
                                      s.name, suite)});
      continue;
    }
    const SuiteCondition c = suiteCondition(lemniscate->params(), s.name);
    for (const auto& other : out) {
      if (other.height_m() == c.height_m()) {
        problems.push_back({0, item("scenarios", i),
                            fmt::format("'{}' flies at {:g} m like '{}': expected one scenario per height "
                                        "(the {} tells its cells apart by their height)",
                                        c.name, c.height_m(), other.name, suite)});
      }
    }
    out.push_back(c);
  }
  return out;
}

/// What the two suites take alike from the file: the belief, the world, the controllers, the
/// scenarios and the seeds.
template <class Options>
void readCommon(const SweepSpec& spec, const std::string& suite, Options& o, Problems& problems) {
  if (!spec.calibrate) {
    problems.push_back({0, "calibrate",
                        "got false: the " + suite + " calibrates the belief in the unperturbed world: expected true "
                        "(fly an uncalibrated sweep with `geaware sweep`)"});
  }
  o.vehicle = spec.vehicle;
  o.world = spec.world;
  o.start_hover_s = spec.start_hover_s;
  o.controller_values = spec.controller_values;
  o.controllers = spec.controllers;
  o.conditions = conditionsOf(spec, suite, problems);
  o.seeds = static_cast<int>(spec.seed_count);  // at most 10⁶ (kSweepMaxFlights)
  o.first_seed = spec.first_seed;
}

void refuseIfAny(const SweepSpec& spec, Problems& problems) {
  if (!problems.empty()) throw io::ConfigError(spec.source, std::move(problems));
}

}  // namespace

RobustnessOptions robustnessOptionsOf(const SweepSpec& spec) {
  Problems problems;
  RobustnessOptions o;
  readCommon(spec, "robustness suite", o, problems);
  for (std::size_t i = 0; i < spec.cases.size(); ++i) {
    if (!spec.case_faults.at(i).name.empty()) {
      problems.push_back({0, item("perturbations", i),
                          fmt::format("'{}' is a case of the fault campaign: the robustness suite changes the "
                                      "truth: expected a case by name or with 'kind' (fly faults with "
                                      "`bench --suite faults`)",
                                      spec.cases[i].name)});
      continue;
    }
    o.cells.push_back(spec.cases[i]);
  }
  refuseIfAny(spec, problems);
  return o;
}

FaultSuiteOptions faultSuiteOptionsOf(const SweepSpec& spec) {
  Problems problems;
  FaultSuiteOptions o;
  readCommon(spec, "fault campaign", o, problems);
  for (std::size_t i = 0; i < spec.controllers.size(); ++i) {
    if (spec.controllers[i].params.acceleration == control::AccelerationCompensation::kNeural) {
      problems.push_back({0, item("controllers", i),
                          fmt::format("'{}': the fault campaign trains no Neural-Lander network: expected a "
                                      "configuration without neural",
                                      spec.controllers[i].name)});
    }
  }
  for (std::size_t i = 0; i < spec.cases.size(); ++i) {
    const FaultCase& f = spec.case_faults.at(i);
    if (f.name.empty()) {
      problems.push_back({0, item("perturbations", i),
                          fmt::format("'{}' is a case of the robustness suite: the fault campaign breaks the "
                                      "vehicle mid-flight: expected `fault: NAME` (fly changes of the truth "
                                      "with `bench --suite robustness`)",
                                      spec.cases[i].name)});
      continue;
    }
    if (i == 0 && f.name != "none") {
      problems.push_back({0, item("perturbations", 0),
                          fmt::format("got '{}': expected `fault: none` first, named none (the fault campaign "
                                      "compares every case with it)",
                                      f.name)});
    }
    o.cases.push_back(f);
  }
  refuseIfAny(spec, problems);
  return o;
}

}  // namespace geaware::experiments
