// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Simulated rotor-speed telemetry (the paper: bidirectional DShot at 200 Hz): the
// true rotor speeds plus white noise, quantised to the telemetry's resolution, never negative.
//
// Resolution: bidirectional DShot reports the electrical period, which the flight controller
// turns into eRPM/100; with the 7 pole pairs of a typical 7-inch motor (14 magnets) one step
// is 100/7 ≈ 14.3 mechanical rpm. 0 disables the quantisation.

#include <cstdint>
#include <optional>
#include <vector>

#include "geaware/model/sensor_data.hpp"
#include "geaware/model/field_error.hpp"
#include "geaware/sim/plant_state.hpp"
#include "geaware/sim/sampling.hpp"

namespace geaware::sim {

struct RotorTelemetryParams {
  double rate_Hz = 200.0;              ///< sample rate [Hz]
  double noise_std_rpm = 10.0;         ///< white noise, 1σ per rotor [rpm]
  double resolution_rpm = 100.0 / 7.0; ///< quantisation step (0: none) [rpm]

  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

class RotorTelemetrySensor {
 public:
  /// Throws model::InvalidParameters listing every invalid field. Noise stream:
  /// (scenario_seed, salt::kRotorTelemetry).
  RotorTelemetrySensor(const RotorTelemetryParams& params, std::uint64_t scenario_seed);

  /// A sample when one is due at state.t_s, else nothing (also for a non-finite state,
  /// counted in rejected()). No allocation.
  [[nodiscard]] std::optional<model::RotorTelemetry> sample(const PlantState& state) noexcept;

  [[nodiscard]] const RotorTelemetryParams& params() const noexcept { return params_; }
  [[nodiscard]] long rejected() const noexcept { return rejected_; }

 private:
  RotorTelemetryParams params_;
  NoiseSource noise_;
  SampleClock clock_;
  long rejected_ = 0;
};

}  // namespace geaware::sim
