// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The paper's quadrotor for tests: the built-in default vehicle (config/vehicles/paper_quad.yaml).

#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware_test {

inline const geaware::model::VehicleParams& paperParams() {
  static const geaware::model::VehicleParams p = geaware::io::builtinVehicle();
  return p;
}

inline const geaware::model::VehicleModel& paperVehicle() {
  static const geaware::model::VehicleModel v(paperParams());
  return v;
}

}  // namespace geaware_test
