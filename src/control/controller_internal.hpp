// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Helpers shared by controller.cpp and controller_learning.cpp; not part of the public API.

#include <vector>

#include "geaware/control/controller_params.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::control::detail {

/// Whether F_G is learned in flight ("+learn", "+learn0").
[[nodiscard]] inline bool learning(const ControllerParams& p) noexcept {
  return p.learn_ground_effect != GroundEffectLearning::kOff;
}

/// The learner's starting curve at its knots: the vehicle file's F_G, or none at all.
[[nodiscard]] std::vector<double> learnerPrior(const model::VehicleModel& vehicle, const ControllerParams& p);

/// The vehicle with F_G as a table on the learner's knots, at the prior (learning on only).
[[nodiscard]] model::VehicleModel learningVehicle(const model::VehicleModel& vehicle, const ControllerParams& p);

}  // namespace geaware::control::detail
