// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The truth side of a flight, stepped by a caller that supplies the throttles: the plant, its
// disturbances and the sensors of the scenario's world, started and stepped exactly as the
// in-process runner (flight.hpp, stages 1 and 5) does, with the tracking metrics taken from the
// truth. No estimator and no controller: those are the caller's (`geaware sitl` behind DDS, the
// Python `geaware.Sim` / `geaware.VecSim` for learning and sweeps). Given the throttles a
// runFlight() of the same scenario commanded on each tick, it reproduces that flight's truth bit
// for bit (tests/experiments/stepped_world_test.cpp).
//
// Order per plant step k, as in runFlight: sense() (every sensor sampled at the true state); on
// a control tick (controlTickDue()) the caller reads the samples and calls setThrottle(); then
// step() advances the plant by one step with the held throttles.

#include <array>
#include <memory>
#include <optional>

#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/flight_metrics.hpp"
#include "geaware/sim/disturbances.hpp"
#include "geaware/sim/plant.hpp"
#include "geaware/sim/sensors.hpp"
#include "geaware/sim/terrain.hpp"

namespace geaware::experiments {

class SteppedWorld {
 public:
  /// The scenario must outlive the object. Refuses (std::invalid_argument) a scenario with
  /// faults or open loop (not flown here), and an invalid one (InvalidScenario, every problem).
  explicit SteppedWorld(const FlightScenario& s);

  /// Stage 1 at the current step: every sensor sampled at the true state. No allocation.
  const sim::SensorReadings& sense() noexcept;
  [[nodiscard]] bool controlTickDue() const noexcept { return k_ % decimation_ == 0; }
  /// Whether the scenario's duration (start hover + trajectory + settle) has been flown.
  [[nodiscard]] bool lastStep() const noexcept { return k_ >= last_step_; }
  /// Whether a ground strike ended the flight.
  [[nodiscard]] bool crashed() const noexcept { return result_.crash.has_value(); }
  /// Plant time of the current step [s].
  [[nodiscard]] double time_s() const noexcept { return static_cast<double>(k_) * dt_; }
  /// Time on the trajectory (negative during the start hover) [s].
  [[nodiscard]] double trajectoryTime_s() const noexcept { return time_s() - s_.start_hover_s; }
  [[nodiscard]] double batteryVoltage_V() const noexcept { return plant_.motors().voltageV(); }
  [[nodiscard]] double plantStep_s() const noexcept { return dt_; }
  [[nodiscard]] double controlPeriod_s() const noexcept { return dt_ * static_cast<double>(decimation_); }
  [[nodiscard]] long plantStepsPerTick() const noexcept { return decimation_; }
  /// The true state (for metrics, rewards and tests; never for a controller).
  [[nodiscard]] const sim::PlantState& truth() const noexcept { return plant_.state(); }
  [[nodiscard]] const sim::Terrain& terrain() const noexcept { return *terrain_; }
  [[nodiscard]] const FlightScenario& scenario() const noexcept { return s_; }
  /// The throttles held until the next tick, in [0, 1] (the motors clamp); the tick is
  /// recorded in the metrics.
  void setThrottle(const std::array<double, 4>& throttle) noexcept;
  /// Stage 5: one plant step; false after a ground strike (the flight is over).
  bool step() noexcept;
  [[nodiscard]] const std::array<double, 4>& throttle() const noexcept { return throttle_; }
  /// The result so far (tracking against the truth, crash).
  [[nodiscard]] FlightResult finish(double wall_s);

 private:
  const FlightScenario& s_;
  std::shared_ptr<const sim::Terrain> terrain_;
  double dt_;
  long decimation_;
  long last_step_;
  sim::TruthParams truth_;
  sim::PlantState x0_;
  sim::Plant plant_;
  std::optional<sim::Wind> wind_;
  sim::SensorSuite sensors_;
  sim::SensorReadings readings_;
  std::array<double, 4> throttle_{};
  long k_ = 0;
  TrackingObserver tracking_;
  FlightTick tick_;
  FlightResult result_;
};

}  // namespace geaware::experiments
