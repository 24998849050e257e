// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The simulated motion-capture system: the pose of the body origin (geometric
// centre) at a fixed rate, with noise, latency and dropouts.
//
// Noise: position + N(0, σ_p²·I); attitude q ⊗ Exp(δθ), δθ ~ N(0, σ_θ²·I) in the body frame
// (a small random rotation; the angle error is Rayleigh-like with mean ≈ 1.6·σ_θ).
//
// Latency: a pose captured at t_s (MocapSample::t_s) is delivered by the first step() at or
// after t_s + latency_s. Pending poses wait in a fixed-capacity ring (no allocation); step()
// hands out at most one pose per call, oldest first, so call it at least at the capture rate
// (every plant step). A full ring drops its oldest pose (counted in overflowed()).
//
// Stamps (docs/world.md): the estimator only knows the latency the driver stamps. With
// reported_latency_s < 0 (default) a pose carries its true capture time; otherwise it carries
// the time it is handed out minus reported_latency_s, so a wrong reported latency is an unknown
// delay. Jitter: each capture's latency is latency_s + N(0, latency_jitter_std_s²), at least 0,
// drawn from its own stream (salt::kMocapJitter; the pose noise does not change); poses are still
// handed out in capture order (a late one holds back the next, as on one network link).
//
// Dropouts: each capture is lost independently with dropout_probability; in addition, a
// capture starts a burst with burst_probability, losing it and the next
// burst_length_samples − 1 captures (occlusion). With bursts alone the lost fraction is
// L / (L + (1 − p_b)/p_b). Every capture draws the same numbers whether or not it is lost, so
// switching dropouts on or off does not change the noise of the poses that arrive.
//
// Defaults: a Vicon/OptiTrack-class system at 100 Hz, 0.5 mm and 0.1° noise, 10 ms latency,
// 1 % isolated dropouts, no bursts.

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "geaware/model/sensor_data.hpp"
#include "geaware/model/field_error.hpp"
#include "geaware/sim/plant_state.hpp"
#include "geaware/sim/sampling.hpp"

namespace geaware::sim {

struct MocapParams {
  double rate_Hz = 100.0;                 ///< capture rate [Hz]
  double latency_s = 0.010;               ///< capture → delivery delay [s]
  double position_noise_std_m = 5.0e-4;   ///< position noise, 1σ per axis [m]
  double attitude_noise_std_rad = 1.75e-3;///< attitude noise, 1σ per body axis (0.1°) [rad]
  double dropout_probability = 0.01;      ///< independent loss of one capture [-]
  double burst_probability = 0.0;         ///< a capture starts a burst of losses [-]
  int burst_length_samples = 10;          ///< captures lost per burst, the first included [-]
  double reported_latency_s = -1.0;       ///< latency the driver stamps; < 0: the true one, exact [s]
  double latency_jitter_std_s = 0.0;      ///< 1σ of each capture's latency around latency_s [s]

  /// Every offending field; empty when usable. The latency must fit the delay ring:
  /// (latency_s + 4·latency_jitter_std_s)·rate_Hz + 2 ≤ Mocap::kQueueCapacity.
  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

class Mocap {
 public:
  static constexpr int kQueueCapacity = 64;  ///< poses in flight at most

  /// Throws model::InvalidParameters listing every invalid field. Noise stream:
  /// (scenario_seed, salt::kMocap).
  Mocap(const MocapParams& params, std::uint64_t scenario_seed);

  /// Capture when due (possibly lost), then deliver the oldest pending pose whose delivery time
  /// has come, if any. A non-finite state captures nothing (counted in rejected()) but still
  /// delivers. No allocation.
  [[nodiscard]] std::optional<model::MocapSample> step(const PlantState& state) noexcept;

  [[nodiscard]] long captured() const noexcept { return captured_; }   ///< captures attempted
  [[nodiscard]] long dropped() const noexcept { return dropped_; }     ///< captures lost
  [[nodiscard]] long overflowed() const noexcept { return overflowed_; }
  [[nodiscard]] long rejected() const noexcept { return rejected_; }
  [[nodiscard]] int pending() const noexcept { return count_; }        ///< poses in flight
  [[nodiscard]] const MocapParams& params() const noexcept { return params_; }

 private:
  struct Pending {
    model::MocapSample sample;
    double deliver_s = 0.0;
  };
  void capture(const PlantState& s) noexcept;

  MocapParams params_;
  NoiseSource noise_;
  NoiseSource jitter_noise_;  // (scenario_seed, salt::kMocapJitter)
  SampleClock clock_;
  std::array<Pending, kQueueCapacity> ring_{};
  int head_ = 0;   // oldest pending
  int count_ = 0;
  int burst_left_ = 0;
  long captured_ = 0;
  long dropped_ = 0;
  long overflowed_ = 0;
  long rejected_ = 0;
};

}  // namespace geaware::sim
