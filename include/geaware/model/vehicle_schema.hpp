// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The vehicle parameters' schema (model/param_schema.hpp): every key of the vehicle file
// (docs/vehicle-file.md) with its unit, range and accessor into VehicleParams, in file order.
// VehicleParams::validate, the vehicle-file loader and writer, merges and the parameter rows
// printed by the command line all go through it.

#include <string>
#include <string_view>
#include <vector>

#include "geaware/model/param_schema.hpp"
#include "geaware/model/vehicle_params.hpp"

namespace geaware::model {

/// The table (built once).
[[nodiscard]] const ParamSchema<VehicleParams>& vehicleSchema();

/// Calls fn(key, unit, value) for every parameter in use, in file order; value is a double, a
/// const std::vector<double>& (a table column) or a const std::string& (the name). A curve
/// given as a table is visited by its table's columns, otherwise by its formula's keys.
template <class Fn>
void forEachParameter(const VehicleParams& params, Fn&& fn) {
  visitParameters(vehicleSchema(), params, [&](const ParamSpec<VehicleParams>& s,
                                               const auto& value) { fn(s.key, s.unit, value); });
}

/// `base` with the parameters at `keys` taken from `update` (ParamSchema's mergeParameters:
/// a key is a parameter's key or a table's, "drag" or "ground_effect.<curve>.table").
[[nodiscard]] VehicleParams mergeParameters(const VehicleParams& base, const VehicleParams& update,
                                            const std::vector<std::string>& keys);

}  // namespace geaware::model
