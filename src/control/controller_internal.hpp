// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Helpers shared by the controller's sources (controller*.cpp, controller_params.cpp); not part
// of the public API.

#include <vector>

#include "geaware/control/controller_params.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::control::detail {

/// Height assumed before the first valid ranger reading: far enough that every ground-effect
/// term has vanished (F_G(100 m) ≈ 7e-7), finite so the models stay finite [m].
inline constexpr double kFarFromGroundM = 100.0;

/// Whether the torque side uses the model's J'(h) (torque `model`, `model_indi`).
[[nodiscard]] inline bool usesJPrime(TorqueCompensation t) noexcept {
  return t == TorqueCompensation::kModel || t == TorqueCompensation::kModelIndi;
}

/// Whether the torque side is incremental, on the measured τ̂_B (torque `indi`, `model_indi`).
[[nodiscard]] inline bool usesIncrementalTorque(TorqueCompensation t) noexcept {
  return t == TorqueCompensation::kIndi || t == TorqueCompensation::kModelIndi;
}

/// Whether F_G is learned in flight ("+learn", "+learn0").
[[nodiscard]] inline bool learning(const ControllerParams& p) noexcept {
  return p.learn_ground_effect != GroundEffectLearning::kOff;
}

/// The learner's starting curve at its knots: the vehicle file's F_G, or none at all.
[[nodiscard]] std::vector<double> learnerPrior(const model::VehicleModel& vehicle, const ControllerParams& p);

/// The leveling scale's start: 1 (the vehicle file's M_G) for "+learn", 0 for "+learn0".
[[nodiscard]] inline double levelingPrior(const ControllerParams& p) noexcept {
  return p.learn_ground_effect == GroundEffectLearning::kFromVehicle ? 1.0 : 0.0;
}

/// The vehicle with F_G as a table on the learner's knots, at the prior (learning on only).
[[nodiscard]] model::VehicleModel learningVehicle(const model::VehicleModel& vehicle, const ControllerParams& p);

}  // namespace geaware::control::detail
