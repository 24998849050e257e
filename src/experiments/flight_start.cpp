// SPDX-License-Identifier: BSD-3-Clause
// The truth side's start, shared by the in-process runner (flight.cpp) and the stepped world
// (stepped_world.cpp): one definition, so the two start every flight from the same state.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "flight_internal.hpp"
#include "geaware/sim/rotor_aerodynamics.hpp"
#include "geaware/sim/rotor_turbulence.hpp"
#include "geaware/traj/touchdown.hpp"

namespace geaware::experiments::detail {
namespace {

/// Rotor speed at which the truth hovers level at its initial pose (with its own ground
/// effect): the thrust is exactly quadratic in a common rotor speed at rest, so one
/// evaluation of the truth aerodynamics at a reference speed gives it.
double truthHoverSpeed(const sim::TruthParams& truth, const sim::Terrain& terrain,
                       const Eigen::Vector3d& p_W, const Eigen::Quaterniond& q_WB) {
  const sim::RotorGeometry geometry = truth.rotorGeometry();
  const sim::RotorAerodynamics aero(geometry, truth.aero);
  const Eigen::Matrix3d R = q_WB.toRotationMatrix();
  const Eigen::Vector3d p_com = p_W + R * truth.cog_offset_B;
  const sim::RotorSurroundings around =
      sim::rotorSurroundings(&terrain, p_com, R, geometry.position_B);
  constexpr double kRef = 1000.0;  // [rpm]
  const sim::RotorAeroOutput out =
      aero.compute({kRef, kRef, kRef, kRef}, R, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                   aero.flightFactors(around.ground_distance_m));  // the in-flight cushion
  const double thrust = out.wrench.force_B.z();
  return kRef * std::sqrt(truth.mass_kg * truth.gravity_mps2 / thrust);
}

}  // namespace

sim::TruthParams truthOf(const FlightScenario& s) {
  sim::TruthParams truth = s.truth ? *s.truth : sim::fromNominal(s.vehicle);
  if (s.mismatch) truth = sim::perturbed(truth, *s.mismatch, s.seed);
  return truth;
}

sim::PlantState initialState(const sim::TruthParams& truth, const sim::Terrain& terrain,
                             const traj::Trajectory& trajectory) {
  const traj::FlatOutput first = trajectory.sample(0.0);
  sim::PlantState x0;
  x0.p_W = first.p_W;
  x0.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(first.yaw_rad, Eigen::Vector3d::UnitZ()));
  const double n0 = truthHoverSpeed(truth, terrain, x0.p_W, x0.q_WB);
  x0.n_rpm = {n0, n0, n0, n0};
  return x0;
}

sim::PlantState restingState(const sim::TruthParams& truth, const sim::Terrain& terrain,
                             const traj::Trajectory& trajectory) {
  const traj::FlatOutput first = trajectory.sample(0.0);
  sim::PlantState x0;
  x0.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(first.yaw_rad, Eigen::Vector3d::UnitZ()));
  // Level, so that the foot standing highest above its own patch of surface touches it and no
  // foot starts under the surface (uneven ground: the others hang until the legs settle).
  const Eigen::Matrix3d R = x0.q_WB.toRotationMatrix();
  double z = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& f : truth.landing_feet_B) {
    const Eigen::Vector3d r_W = R * f;
    z = std::max(z, terrain.heightAt(first.p_W.x() + r_W.x(), first.p_W.y() + r_W.y()) - r_W.z());
  }
  const double n_feet = static_cast<double>(std::max<std::size_t>(1, truth.landing_feet_B.size()));
  const double sag_m = truth.landing_gear.stiffness_N_per_m > 0.0
                           ? truth.mass_kg * truth.gravity_mps2 /
                                 (n_feet * truth.landing_gear.stiffness_N_per_m)
                           : 0.0;
  if (!std::isfinite(z)) z = terrain.heightAt(first.p_W.x(), first.p_W.y());  // no feet (refused by validate)
  x0.p_W = Eigen::Vector3d(first.p_W.x(), first.p_W.y(), z - sag_m);
  x0.n_rpm = {0.0, 0.0, 0.0, 0.0};
  return x0;
}

sim::PlantConfig plantConfigOf(const FlightScenario& s) {
  sim::PlantConfig c = s.plant;
  c.step_s = 1.0 / s.plant_rate_hz;
  return c;
}

void addDisturbances(const FlightScenario& s, const sim::TruthParams& truth, sim::Plant& plant,
                     std::optional<sim::Wind>& wind) {
  if (s.disturbances.turbulence && s.disturbances.turbulence_params.per_rotor) {
    plant.addContribution(
        std::make_unique<sim::RotorTurbulence>(s.disturbances.turbulence_params, truth, s.seed));
  } else if (s.disturbances.turbulence) {
    plant.addContribution(
        std::make_unique<sim::GroundTurbulence>(s.disturbances.turbulence_params, s.seed));
  }
  if (s.disturbances.unsteadiness) {
    plant.addContribution(
        std::make_unique<sim::Unsteadiness>(s.disturbances.unsteadiness_params, s.seed));
  }
  if (s.disturbances.wind) wind.emplace(s.disturbances.wind_params, s.seed);
}

}  // namespace geaware::experiments::detail

namespace geaware::experiments {

void applyTouchdown(FlightScenario& s) {
  const bool landing = dynamic_cast<const traj::Landing*>(s.trajectory.get()) != nullptr;
  const bool takeoff = dynamic_cast<const traj::TakeOff*>(s.trajectory.get()) != nullptr;
  if (!landing && !takeoff) return;
  s.plant.ground_contact = true;
  s.controller.clearance_guard = false;
  if (landing && !s.land_detector) s.land_detector = control::LandDetectorParams{};
  if (takeoff) s.start_on_ground = true;
}

}  // namespace geaware::experiments
