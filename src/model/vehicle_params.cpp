// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/model/vehicle_params.hpp"

#include "geaware/model/field_check.hpp"
#include "geaware/model/vehicle_schema.hpp"

namespace geaware::model {

std::vector<FieldError> VehicleParams::validate() const {
  std::vector<FieldError> errors;
  // Every check names the key path as written in the vehicle file; the ranges and the rules
  // across parameters are the schema's (src/model/vehicle_schema.cpp).
  FieldChecker c(errors);
  vehicleSchema().validate(*this, c, errors);
  return errors;
}

}  // namespace geaware::model
