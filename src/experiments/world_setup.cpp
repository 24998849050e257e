// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/world_setup.hpp"

#include "geaware/io/truth_file.hpp"

namespace geaware::experiments {

sim::World defaultWorld(const model::VehicleParams& belief, bool belief_is_builtin,
                        const std::string& belief_source) {
  if (belief_is_builtin) return io::builtinTruth(kDefaultTruth);
  return sim::idealWorld(belief, "ideal world of " + belief_source);
}

void applyWorld(FlightScenario& s, const sim::World& world) {
  s.truth = world.truth;
  s.mismatch.reset();
  if (world.variesPerFlight()) s.mismatch = world.per_flight_variation;
  s.sensors = world.sensors;
  s.disturbances.turbulence = world.ground_turbulence;
  s.disturbances.turbulence_params = world.ground_turbulence_params;
  s.disturbances.unsteadiness = world.unsteadyAtAltitude();
  s.disturbances.unsteadiness_params = world.altitude_unsteadiness_params;
  s.disturbances.wind = world.room_air;
  s.disturbances.wind_params = world.room_air_params;
}

}  // namespace geaware::experiments
