// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Helpers shared by the flight runner (flight.cpp), the stepped world (stepped_world.cpp) and
// the scenario validation (scenario_validation.cpp); not part of the public API.

#include <cmath>
#include <memory>
#include <optional>

#include "geaware/experiments/flight.hpp"
#include "geaware/sim/disturbances.hpp"
#include "geaware/sim/plant.hpp"
#include "geaware/sim/terrains.hpp"

namespace geaware::experiments::detail {

/// Plant steps per control tick, or 0 when the plant rate is not a multiple of the control rate.
inline long decimationOf(double plant_rate_hz, double control_rate_hz) {
  if (!(std::isfinite(plant_rate_hz) && plant_rate_hz > 0.0 && std::isfinite(control_rate_hz) &&
        control_rate_hz > 0.0)) {
    return 0;
  }
  const double ratio = plant_rate_hz / control_rate_hz;
  const double n = std::round(ratio);
  if (n < 1.0 || std::abs(ratio - n) > 1e-9 * ratio) return 0;
  return static_cast<long>(n);
}

inline std::shared_ptr<const sim::Terrain> terrainOf(const FlightScenario& s) {
  return s.terrain ? s.terrain : std::make_shared<sim::FlatGround>(0.0);
}

/// Vertical distance from the rotor-plane centre to the terrain under it [m].
inline double heightAbove(const sim::Terrain& terrain, const Eigen::Vector3d& p_W) noexcept {
  return p_W.z() - terrain.heightAt(p_W.x(), p_W.y());
}

// --- The truth side's start (flight_start.cpp) ------------------------------------------------

/// The truth the scenario flies: its truth (or the nominal vehicle's), with the per-flight
/// variation drawn from the scenario's seed.
[[nodiscard]] sim::TruthParams truthOf(const FlightScenario& s);

/// The truth's starting state: hovering level (at the reference's yaw) at the first point of
/// the trajectory, rotors at the speed that carries the truth there.
/// Standing on the landing gear under the trajectory's first point (FlightScenario::start_on_ground):
/// level at the reference's yaw, each leg compressed by its share of the weight, motors stopped
/// (they spin up to the throttle-0 idle in the first steps).
[[nodiscard]] sim::PlantState restingState(const sim::TruthParams& truth, const sim::Terrain& terrain,
                                           const traj::Trajectory& trajectory);

[[nodiscard]] sim::PlantState initialState(const sim::TruthParams& truth, const sim::Terrain& terrain,
                                           const traj::Trajectory& trajectory);

/// The plant's configuration at the scenario's plant rate.
[[nodiscard]] sim::PlantConfig plantConfigOf(const FlightScenario& s);

/// The scenario's turbulence (per rotor or whole body) and unsteadiness added to `plant`, and
/// its wind model in `wind`, each seeded from the scenario.
void addDisturbances(const FlightScenario& s, const sim::TruthParams& truth, sim::Plant& plant,
                     std::optional<sim::Wind>& wind);

}  // namespace geaware::experiments::detail
