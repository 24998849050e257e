// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/sim/sensors.hpp"

#include <string>
#include <utility>

#include "geaware/model/vehicle_model.hpp"

namespace geaware::sim {
namespace {

void appendPrefixed(std::vector<model::FieldError>& out, const char* prefix, std::vector<model::FieldError> errors) {
  for (auto& e : errors) {
    e.field = std::string(prefix) + "." + e.field;
    out.push_back(std::move(e));
  }
}

}  // namespace

std::vector<model::FieldError> SensorSuiteParams::validate() const {
  std::vector<model::FieldError> out;
  appendPrefixed(out, "imu", imu.validate());
  appendPrefixed(out, "mocap", mocap.validate());
  appendPrefixed(out, "rotor_telemetry", rotor_telemetry.validate());
  appendPrefixed(out, "ranger", ranger.validate());
  return out;
}

SensorSuite::SensorSuite(const SensorSuiteParams& params, std::uint64_t scenario_seed)
    : imu_(model::validated(params).imu, scenario_seed),
      mocap_(params.mocap, scenario_seed),
      rotors_(params.rotor_telemetry, scenario_seed),
      ranger_(params.ranger, scenario_seed) {}

SensorReadings SensorSuite::step(const PlantState& state, const Terrain* terrain) noexcept {
  // Built in place, in this order (braced initialisers are evaluated left to right): the
  // ranger's optional frame (2.3 kB) is constructed directly in the result.
  return SensorReadings{imu_.sample(state), mocap_.step(state), rotors_.sample(state),
                        ranger_.sample(state, terrain)};
}

}  // namespace geaware::sim
