// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/model/vehicle_model.hpp"

#include <cmath>

#include "geaware/model/field_check.hpp"
#include "geaware/model/units.hpp"

namespace geaware::model {

InvalidParameters::InvalidParameters(std::vector<FieldError> errors)
    : std::invalid_argument(describeErrors("invalid vehicle parameters:", errors)),
      errors_(std::move(errors)) {}

VehicleModel::VehicleModel(VehicleParams params)
    : params_(std::move(params)),
      ground_effect_(validated(params_)),
      drag_(params_.drag),
      mixer_(params_),
      throttle_(params_.throttle) {}

double VehicleModel::hoverSpeedRpm(double h_m) const noexcept {
  const double thrust_per_rotor =
      params_.mass_kg * kGravity / (4.0 * (1.0 + ground_effect_.thrustRatio(h_m)));
  return std::sqrt(thrust_per_rotor / params_.rotor.k_T_N_per_rpm2);
}

}  // namespace geaware::model
