// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The controller parameters' schema (model/param_schema.hpp): every key of a controller-
// parameters file (config/controller-params/*.yaml, docs/controller-params.md) with its unit,
// range and accessor into ControllerParams. The file holds the numbers a user of another vehicle
// tunes: gains, the rate, the filter cut-off, limits, the thrust correction and the settings of
// geaware's additions. The configuration (acceleration and torque compensation, which additions
// are on) stays with `--controller` (control/controller_params.hpp, parseConfiguration).

#include <optional>

#include "geaware/control/controller_params.hpp"
#include "geaware/model/param_schema.hpp"

namespace geaware::control {

/// The table (built once).
[[nodiscard]] const model::ParamSchema<ControllerParams>& controllerSchema();

/// The values a controller-parameters file holds by default: today's compiled defaults exactly,
/// i.e. ControllerParams{}'s gains, rate, cut-off and limits, and the additions' settings of
/// recommendedControllerParams() (the values they take when a configuration switches them on).
/// config/controller-params/default.yaml is these values.
[[nodiscard]] ControllerParams defaultParameterValues();

/// `configuration` (its switches: acceleration, torque, which additions are on) with the file's
/// `values`: the gains, rate, cut-off, tilt limit and thrust correction always, and the settings
/// of each addition that `configuration` switches on (the disturbance feed-forward when its time
/// constant is > 0, the integral when K^I ≠ 0, the guard when on). Additions that are off stay
/// off. applyParameters(c, defaultParameterValues()) == c for every configuration
/// parseConfiguration makes from ControllerParams{}.
[[nodiscard]] ControllerParams applyParameters(const ControllerParams& configuration,
                                               const ControllerParams& values);

/// applyParameters(configuration, *values), or `configuration` when there are no values.
[[nodiscard]] inline ControllerParams applyParameters(const ControllerParams& configuration,
                                                      const std::optional<ControllerParams>& values) {
  return values ? applyParameters(configuration, *values) : configuration;
}

/// Whether every parameter of the schema has the same value in `a` and `b` (bit for bit).
[[nodiscard]] bool sameParameterValues(const ControllerParams& a, const ControllerParams& b);

}  // namespace geaware::control
