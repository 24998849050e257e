// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The truth side of a flight without DDS, for `geaware sitl`: the plant, its disturbances and
// the sensors of the scenario's world, stepped like the in-process runner (experiments/flight.hpp,
// stages 1 and 5) with the throttles PX4 would send; the tracking metrics from the truth. The
// estimator and controller are somewhere else (a bridge process).

#include <array>
#include <cstdint>
#include <memory>
#include <optional>

#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/flight_metrics.hpp"
#include "geaware/sim/disturbances.hpp"
#include "geaware/sim/plant.hpp"
#include "geaware/sim/sensors.hpp"

namespace geaware::bridge {

class SitlCore {
 public:
  /// Refuses (std::invalid_argument) a scenario with faults or open loop: not flown here.
  explicit SitlCore(const experiments::FlightScenario& s);

  /// Stage 1 at the current step: every sensor sampled at the true state.
  const sim::SensorReadings& sense() noexcept;
  [[nodiscard]] bool controlTickDue() const noexcept { return k_ % decimation_ == 0; }
  [[nodiscard]] bool lastStep() const noexcept { return k_ >= last_step_; }
  [[nodiscard]] double time_s() const noexcept { return static_cast<double>(k_) * dt_; }
  [[nodiscard]] double batteryVoltage_V() const noexcept { return plant_.motors().voltageV(); }
  [[nodiscard]] double plantStep_s() const noexcept { return dt_; }
  [[nodiscard]] double controlPeriod_s() const noexcept { return dt_ * static_cast<double>(decimation_); }
  /// The throttles held until the next tick; the tick is recorded in the metrics.
  void setThrottle(const std::array<double, 4>& throttle) noexcept;
  /// Stage 5: one plant step; false after a ground strike (the flight is over).
  bool step() noexcept;
  [[nodiscard]] const std::array<double, 4>& throttle() const noexcept { return throttle_; }
  /// The result so far (tracking against the truth, crash).
  [[nodiscard]] experiments::FlightResult finish(double wall_s);

 private:
  const experiments::FlightScenario& s_;
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
  experiments::TrackingObserver tracking_;
  experiments::FlightTick tick_;
  experiments::FlightResult result_;
};

}  // namespace geaware::bridge
