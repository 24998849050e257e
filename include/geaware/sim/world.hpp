// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The simulated world of a flight or a campaign, in one aggregate: the vehicle as it is built
// (sim::TruthParams), its sensors, the disturbances of the room it flies in, how much it varies
// from flight to flight and how well the team weighs it. A truth file fills it
// (io/truth_file.hpp, docs/truth-file.md); the flights and the campaign take their truth,
// sensors and disturbances from it (experiments/world_setup.hpp). The controller never sees it.
//
// The defaults are today's world built from a vehicle file (idealWorld): the nominal truth of
// the file, the default sensors, near-ground turbulence on, no room air, no per-flight
// variation, an exact scale. The calibrated aerodynamics, motor and turbulence are carried over
// to the file's vehicle by similarity (sim/similarity.hpp).

#include <string>
#include <utility>

#include "geaware/model/vehicle_params.hpp"
#include "geaware/sim/disturbances.hpp"
#include "geaware/sim/sensors.hpp"
#include "geaware/sim/similarity.hpp"
#include "geaware/sim/truth_params.hpp"

namespace geaware::sim {

struct World {
  /// Where it came from: the truth file's path, "<built-in ideal>", or "ideal world of <file>".
  std::string source;
  /// The truth file's vehicle part (the vehicle-file schema): the body the truth was built
  /// from (fromNominal), and what the rigs mount.
  model::VehicleParams vehicle;
  /// The vehicle as it is: fromNominal(vehicle) with the truth section's values.
  TruthParams truth;
  SensorSuiteParams sensors;
  /// Near-ground recirculation buffeting (truth.disturbances.ground_turbulence).
  bool ground_turbulence = true;
  GroundTurbulenceParams ground_turbulence_params;
  /// Buffeting at every height (blade imbalance…; truth.disturbances.altitude_unsteadiness): on
  /// when either σ is positive.
  UnsteadinessParams altitude_unsteadiness_params;
  /// Air moving in the room: a mean and gusts (truth.disturbances.room_air).
  bool room_air = false;
  WindParams room_air_params;
  /// Seeded per-flight variation of the truth (truth.per_flight_variation); all bounds zero:
  /// none (every flight flies the same vehicle).
  MismatchSpec per_flight_variation;
  /// 1σ of the team's scale reading of the mass (truth.team.scale_error_std_kg) [kg].
  double team_scale_error_std_kg = 0.0;

  [[nodiscard]] bool unsteadyAtAltitude() const noexcept {
    return altitude_unsteadiness_params.torque_std_Nm > 0.0 ||
           altitude_unsteadiness_params.force_std_N > 0.0;
  }
  /// Whether any per-flight variation bound is non-zero.
  [[nodiscard]] bool variesPerFlight() const noexcept {
    const MismatchSpec& m = per_flight_variation;
    return m.mass_rel != 0.0 || m.inertia_rel != 0.0 || m.cog_offset_m != 0.0 ||
           m.cog_offset_z_m != 0.0 || m.thrust_spread_rel != 0.0;
  }
};

/// Today's world of a (validated) vehicle file: its nominal truth and every other default.
[[nodiscard]] inline World idealWorld(const model::VehicleParams& vehicle, std::string source = {}) {
  World w;
  w.source = std::move(source);
  w.vehicle = vehicle;
  w.truth = fromNominal(vehicle);
  w.ground_turbulence_params = scaledGroundTurbulence(GroundTurbulenceParams{}, similarityToReference(vehicle));
  return w;
}

}  // namespace geaware::sim
