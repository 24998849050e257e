// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The IMU's white-noise densities from a hover log, as a team sets its estimator's process
// noise (docs/identification.md, "IMU noise"): the overlapping Allan deviation σ_A(τ) of each
// gyro and accelerometer axis at cluster times τ = 0.05, 0.1 and 0.2 s, and the density of the
// white noise that would give them, N = σ_A(τ)·√τ (IEEE Std 952-1997, Annex C: the τ^(−1/2)
// branch of an Allan plot is angle/velocity random walk, read as N). The τ are above the flight
// controller's low-pass (a 20 Hz filter correlates samples over ≈ 10 ms) and below where a
// hover's own motion dominates: what is read is the noise the estimator integrates between
// motion-capture updates, vibration that reaches it included. A hover's real motion (the control
// loop's work against disturbances) adds to σ_A: N is an upper bound, on the safe side for a
// filter's process noise.

#include <array>
#include <string>
#include <vector>

#include "geaware/ident/least_squares.hpp"

namespace geaware::ident {

struct ImuNoiseFit {
  std::array<double, 3> gyro_density_rad_per_s_sqrtHz{};     ///< per body axis [rad/s/√Hz]
  std::array<double, 3> accel_density_m_per_s2_sqrtHz{};     ///< per body axis [m/s²/√Hz]
  double gyro_noise_density_rad_per_s_sqrtHz = kNaN;    ///< RMS over the axes [rad/s/√Hz]
  double accel_noise_density_m_per_s2_sqrtHz = kNaN;    ///< RMS over the axes [m/s²/√Hz]
  double sample_interval_s = kNaN;  ///< median interval between samples [s]
  std::size_t samples = 0;
  std::vector<std::string> warnings;
};

/// t_s strictly increasing; gyro_B and accel_B one vector per body axis, each as long as t_s.
/// Throws IdentError when the log is too short for τ = 0.2 s with 10 clusters, has non-finite
/// values or times that do not increase.
[[nodiscard]] ImuNoiseFit fitImuNoise(const std::vector<double>& t_s,
                                      const std::array<std::vector<double>, 3>& gyro_B,
                                      const std::array<std::vector<double>, 3>& accel_B);

/// The overlapping Allan deviation of `x` (uniform interval dt_s) at cluster size m samples:
/// σ_A² = Σ_k (x̄_{k+m} − x̄_k)² / (2·(n − 2m + 1)) over the running means x̄ of m samples.
/// Requires n ≥ 2m + 1.
[[nodiscard]] double overlappingAllanDeviation(const std::vector<double>& x, std::size_t m);

}  // namespace geaware::ident
