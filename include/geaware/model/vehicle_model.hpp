// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The controller-side vehicle model in one object: parameters plus the ground-effect, drag,
// mixer and throttle models built from them. Construction validates; an invalid parameter set
// cannot produce a VehicleModel.

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "geaware/model/ground_effect.hpp"
#include "geaware/model/mixer.hpp"
#include "geaware/model/motor.hpp"
#include "geaware/model/rotor_drag.hpp"
#include "geaware/model/vehicle_params.hpp"

namespace geaware::model {

/// Thrown when a VehicleModel is built from parameters that fail validate().
class InvalidParameters : public std::invalid_argument {
 public:
  explicit InvalidParameters(std::vector<FieldError> errors);
  [[nodiscard]] const std::vector<FieldError>& errors() const noexcept { return errors_; }

 private:
  std::vector<FieldError> errors_;
};

/// `params` itself when `params.validate()` finds nothing; otherwise throws InvalidParameters
/// listing every offending field. For initialiser lists: `params_(model::validated(params))`.
template <typename Params>
const Params& validated(const Params& params) {
  auto errors = params.validate();
  if (!errors.empty()) throw InvalidParameters(std::move(errors));
  return params;
}

class VehicleModel {
 public:
  /// Validates and builds; throws InvalidParameters listing every offending field.
  explicit VehicleModel(VehicleParams params);

  [[nodiscard]] const VehicleParams& params() const noexcept { return params_; }
  [[nodiscard]] const GroundEffectModel& groundEffect() const noexcept { return ground_effect_; }
  [[nodiscard]] const RotorDragModel& drag() const noexcept { return drag_; }
  [[nodiscard]] const Mixer& mixer() const noexcept { return mixer_; }
  [[nodiscard]] const ThrottleCurve& throttleCurve() const noexcept { return throttle_; }

  /// Rotor speed that holds a level hover at rotor-plane height h, with ground effect:
  /// n = √(m·g / (4·k_T·(1 + F_G(h)))) [rpm].
  [[nodiscard]] double hoverSpeedRpm(double h_m) const noexcept;

 private:
  VehicleParams params_;
  GroundEffectModel ground_effect_;
  RotorDragModel drag_;
  Mixer mixer_;
  ThrottleCurve throttle_;
};

}  // namespace geaware::model
