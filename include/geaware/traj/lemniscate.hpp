// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The figure-eight of the paper's tracking experiments (Table I): a Lemniscate of Gerono
//   P(θ) = centre + (A·sin θ, B·sin 2θ, 0),   z = height (+ swing·(1 − cos θ)/2, optional),
// flown with a phase θ(t) that follows a SmoothProfile over 2π·laps, so the flight starts and
// ends at rest at the centre and its references are continuous up to snap. The cruise phase
// rate is Ω = v_peak / max_θ |dP/dθ| = v_peak / √(A² + 4B²) (the maximum is at θ = 0, π, where
// both cosines are ±1), so the speed reaches v_peak exactly at each crossing of the centre.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "geaware/traj/smooth_profile.hpp"
#include "geaware/traj/trajectory.hpp"

namespace geaware::traj {

/// Defaults: the paper's experiment 7 (±4 m × ±1.7 m at 0.18 m, 3 m/s peak, one lap).
struct LemniscateParams {
  Eigen::Vector2d centre_xy_m = Eigen::Vector2d::Zero();  ///< centre (x, y), world frame [m]
  double half_extent_x_m = 4.0;                           ///< A: the curve spans centre.x ± A [m]
  double half_extent_y_m = 1.7;                           ///< B: the curve spans centre.y ± B [m]
  double height_m = 0.18;       ///< z of the flight (its lowest with a swing), world frame [m]
  /// The height's swing over each lap: z = height_m + swing·(1 − cos θ)/2, from height_m at
  /// the start (θ = 0) to height_m + swing at the middle of each lap and back (0: a level
  /// flight, the paper's); at most 2·half_extent_x_m, so that the peak speed stays v_peak [m].
  double height_swing_m = 0.0;
  double peak_speed_mps = 3.0;  ///< speed at the centre crossings during the cruise [m/s]
  int laps = 1;                 ///< number of full figure-eights [-]
  double ramp_time_s = 2.0;     ///< duration of the start and of the stop ramp of θ̇ [s]
  double yaw_rad = 0.0;         ///< constant yaw ψ [rad]

  /// Every offending field as "field = value (expected ...)"; empty when usable. Includes the
  /// joint condition that the two ramps fit into the laps: Ω·ramp_time_s ≤ 2π·laps.
  [[nodiscard]] std::vector<std::string> validate() const;
};

class Lemniscate final : public Trajectory {
 public:
  /// Throws std::invalid_argument listing every problem validate() reports.
  explicit Lemniscate(const LemniscateParams& params);

  [[nodiscard]] FlatOutput sample(double t_s) const noexcept override;
  [[nodiscard]] double duration() const noexcept override { return phase_.duration(); }

  [[nodiscard]] const LemniscateParams& params() const noexcept { return params_; }
  /// Cruise phase rate Ω [rad/s].
  [[nodiscard]] double cruisePhaseRate() const noexcept { return phase_.cruiseRate(); }
  /// The phase profile θ(t) [rad].
  [[nodiscard]] const SmoothProfile& phase() const noexcept { return phase_; }

 private:
  LemniscateParams params_;
  SmoothProfile phase_;
};

}  // namespace geaware::traj
