// SPDX-License-Identifier: BSD-3-Clause
// The truth side of runFlight (flight.cpp: its FlightLoop's plant, disturbances, sensors and
// initial state, from flight_start.cpp), stepped by a caller.
#include "geaware/experiments/stepped_world.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "flight_internal.hpp"

namespace geaware::experiments {
namespace {

const FlightScenario& checked(const FlightScenario& s) {
  if (!s.faults.empty()) {
    throw std::invalid_argument("the stepped simulator does not inject faults (scenario.faults)");
  }
  if (s.loop != LoopMode::kClosed) {
    throw std::invalid_argument("the stepped simulator flies closed loop only (scenario.loop)");
  }
  if (s.start_on_ground || s.land_detector) {
    throw std::invalid_argument(
        "the stepped simulator does not fly landings and take-offs yet (scenario.start_on_ground, "
        "scenario.land_detector): fly them with runFlight (`geaware fly`, `geaware sweep`)");
  }
  if ((s.obstacles && !s.obstacles->empty()) || !s.beam_rangers.empty()) {
    throw std::invalid_argument(
        "the stepped simulator does not fly obstacles or beam rangers yet (scenario.obstacles, "
        "scenario.beam_rangers): fly them with runFlight (`geaware fly`, `geaware sweep`)");
  }
  if (auto problems = validate(s); !problems.empty()) throw InvalidScenario(std::move(problems));
  return s;
}

}  // namespace

SteppedWorld::SteppedWorld(const FlightScenario& s)
    : s_(checked(s)),
      terrain_(detail::terrainOf(s)),
      dt_(1.0 / s.plant_rate_hz),
      decimation_(detail::decimationOf(s.plant_rate_hz, s.controller.rate_hz)),
      last_step_(static_cast<long>(std::ceil(
          (s.start_hover_s + s.trajectory->duration() + s.settle_s) * s.plant_rate_hz - 1e-9))),
      truth_(detail::truthOf(s)),
      x0_(detail::initialState(truth_, *terrain_, *s.trajectory)),
      plant_(truth_, terrain_, detail::plantConfigOf(s), x0_),
      sensors_(s.sensors, s.seed) {
  detail::addDisturbances(s, truth_, plant_, wind_);
  throttle_.fill(plant_.throttleForSteadySpeed(x0_.n_rpm[0]));
}

const sim::SensorReadings& SteppedWorld::sense() noexcept {
  readings_ = sensors_.step(plant_.state(), terrain_.get());
  return readings_;
}

void SteppedWorld::setThrottle(const std::array<double, 4>& throttle) noexcept {
  throttle_ = throttle;
  const sim::PlantState& x = plant_.state();
  const double t_traj = trajectoryTime_s();
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

bool SteppedWorld::step() noexcept {
  if (result_.crash) return false;
  if (wind_) plant_.setWind_W(wind_->advance(dt_));
  const sim::StepResult r = plant_.step(throttle_);
  ++k_;
  if (r.crash) {
    result_.crash = r.crash;
    return false;
  }
  return true;
}

FlightResult SteppedWorld::finish(double wall_s) {
  tracking_.writeTo(result_);
  if (result_.crash) result_.crash_description = sim::describe(*result_.crash);
  result_.completed = !result_.crash.has_value() && k_ >= last_step_;
  result_.throttle_faults = plant_.throttleFaults();
  result_.simulated_s = plant_.state().t_s;
  result_.wall_s = wall_s;
  result_.real_time_factor = wall_s > 0.0 ? result_.simulated_s / wall_s : 0.0;
  return result_;
}

}  // namespace geaware::experiments
