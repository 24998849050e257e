// SPDX-License-Identifier: BSD-3-Clause
// The truth side of src/experiments/flight.cpp (its FlightLoop's plant, disturbances, sensors and
// initial state), for the simulator process.
#include "geaware/bridge/sitl_core.hpp"

#include <cmath>
#include <stdexcept>

#include "geaware/sim/rotor_aerodynamics.hpp"
#include "geaware/sim/rotor_turbulence.hpp"
#include "geaware/sim/terrains.hpp"

namespace geaware::bridge {
namespace {

// The same start as the in-process runner (flight.cpp: truthHoverSpeed, initialState).
double truthHoverSpeed(const sim::TruthParams& truth, const sim::Terrain& terrain,
                       const Eigen::Vector3d& p_W, const Eigen::Quaterniond& q_WB) {
  const sim::RotorGeometry geometry = truth.rotorGeometry();
  const sim::RotorAerodynamics aero(geometry, truth.aero);
  const Eigen::Matrix3d R = q_WB.toRotationMatrix();
  const Eigen::Vector3d p_com = p_W + R * truth.cog_offset_B;
  const sim::RotorSurroundings around = sim::rotorSurroundings(&terrain, p_com, R, geometry.position_B);
  constexpr double kRef = 1000.0;  // [rpm]
  const sim::RotorAeroOutput out =
      aero.compute({kRef, kRef, kRef, kRef}, R, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                   aero.flightFactors(around.ground_distance_m));
  return kRef * std::sqrt(truth.mass_kg * truth.gravity_mps2 / out.wrench.force_B.z());
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

sim::TruthParams truthOf(const experiments::FlightScenario& s) {
  sim::TruthParams truth = s.truth ? *s.truth : sim::fromNominal(s.vehicle);
  if (s.mismatch) truth = sim::perturbed(truth, *s.mismatch, s.seed);
  return truth;
}

sim::PlantConfig plantConfigOf(const experiments::FlightScenario& s) {
  sim::PlantConfig c = s.plant;
  c.step_s = 1.0 / s.plant_rate_hz;
  return c;
}

const experiments::FlightScenario& checked(const experiments::FlightScenario& s) {
  if (!s.faults.empty()) throw std::invalid_argument("geaware sitl does not inject faults (scenario.faults)");
  if (s.loop != experiments::LoopMode::kClosed) throw std::invalid_argument("geaware sitl flies closed loop only");
  if (auto problems = experiments::validate(s); !problems.empty()) {
    throw experiments::InvalidScenario(std::move(problems));
  }
  return s;
}

std::shared_ptr<const sim::Terrain> terrainOf(const experiments::FlightScenario& s) {
  return s.terrain ? s.terrain : std::make_shared<sim::FlatGround>(0.0);
}

}  // namespace

SitlCore::SitlCore(const experiments::FlightScenario& s)
    : s_(checked(s)),
      terrain_(terrainOf(s)),
      dt_(1.0 / s.plant_rate_hz),
      decimation_(std::lround(s.plant_rate_hz / s.controller.rate_hz)),
      last_step_(static_cast<long>(std::ceil(
          (s.start_hover_s + s.trajectory->duration() + s.settle_s) * s.plant_rate_hz - 1e-9))),
      truth_(truthOf(s)),
      x0_(initialState(truth_, *terrain_, *s.trajectory)),
      plant_(truth_, terrain_, plantConfigOf(s), x0_),
      sensors_(s.sensors, s.seed) {
  if (s.disturbances.turbulence && s.disturbances.turbulence_params.per_rotor) {
    plant_.addContribution(
        std::make_unique<sim::RotorTurbulence>(s.disturbances.turbulence_params, truth_, s.seed));
  } else if (s.disturbances.turbulence) {
    plant_.addContribution(
        std::make_unique<sim::GroundTurbulence>(s.disturbances.turbulence_params, s.seed));
  }
  if (s.disturbances.unsteadiness) {
    plant_.addContribution(
        std::make_unique<sim::Unsteadiness>(s.disturbances.unsteadiness_params, s.seed));
  }
  if (s.disturbances.wind) wind_.emplace(s.disturbances.wind_params, s.seed);
  throttle_.fill(plant_.throttleForSteadySpeed(x0_.n_rpm[0]));
}

const sim::SensorReadings& SitlCore::sense() noexcept {
  readings_ = sensors_.step(plant_.state(), terrain_.get());
  return readings_;
}

void SitlCore::setThrottle(const std::array<double, 4>& throttle) noexcept {
  throttle_ = throttle;
  const sim::PlantState& x = plant_.state();
  const double t_traj = time_s() - s_.start_hover_s;
  const double duration = s_.trajectory->duration();
  tick_.t_s = x.t_s;
  tick_.t_traj_s = t_traj;
  tick_.in_trajectory = t_traj >= -0.5 * dt_ && t_traj <= duration + 0.5 * dt_;
  tick_.truth = x;
  tick_.input.reference = s_.trajectory->sample(t_traj);
  tick_.throttle = throttle;
  tracking_.onTick(tick_);
  ++result_.control_ticks;
}

bool SitlCore::step() noexcept {
  if (wind_) plant_.setWind_W(wind_->advance(dt_));
  const sim::StepResult r = plant_.step(throttle_);
  ++k_;
  if (r.crash) {
    result_.crash = r.crash;
    return false;
  }
  return true;
}

experiments::FlightResult SitlCore::finish(double wall_s) {
  tracking_.writeTo(result_);
  if (result_.crash) result_.crash_description = sim::describe(*result_.crash);
  result_.completed = !result_.crash.has_value() && k_ >= last_step_;
  result_.throttle_faults = plant_.throttleFaults();
  result_.simulated_s = plant_.state().t_s;
  result_.wall_s = wall_s;
  result_.real_time_factor = wall_s > 0.0 ? result_.simulated_s / wall_s : 0.0;
  return result_;
}

}  // namespace geaware::bridge
