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
  SensorReadings r;
  r.imu = imu_.sample(state);
  r.mocap = mocap_.step(state);
  r.rotors = rotors_.sample(state);
  r.ranger = ranger_.sample(state, terrain);
  return r;
}

}  // namespace geaware::sim
