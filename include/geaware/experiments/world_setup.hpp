// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Which world a flight or a campaign flies in (sim::World, from a truth file: docs/truth-file.md)
// and how a flight scenario takes it: the truth, its per-flight variation, the sensors and the
// disturbances come from the world; the controller's vehicle stays the scenario's.

#include <string>

#include "geaware/experiments/flight.hpp"
#include "geaware/sim/world.hpp"

namespace geaware::experiments {

/// The built-in truth (io::builtinTruthNames) that `fly`, `bench` and scenario files fly in when
/// they name none and the controller's vehicle is the built-in one: the paper's quadrotor as
/// built (config/truths/paper_quad_as_built.yaml, docs/world.md).
inline constexpr const char* kDefaultTruth = "as_built";

/// The world when none is named: the built-in kDefaultTruth when the controller's vehicle is
/// the built-in one (`belief_is_builtin`), otherwise the ideal world of the controller's own
/// vehicle file (sim::idealWorld), so that `--vehicle FILE` alone flies FILE's vehicle.
[[nodiscard]] sim::World defaultWorld(const model::VehicleParams& belief, bool belief_is_builtin,
                                      const std::string& belief_source);

/// Sets the scenario's truth, per-flight variation, sensors and disturbances (turbulence and
/// room air) from `world`.
void applyWorld(FlightScenario& s, const sim::World& world);

}  // namespace geaware::experiments
