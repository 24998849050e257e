// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Tracking metrics of the paper's Table I: RMSE in XOY, in Z and overall, and the maximum and
// standard deviation of the position-error norm ‖E_P‖, accumulated sample by sample.

#include <cstddef>

#include <Eigen/Core>

namespace geaware::experiments {

/// Table I numbers of one flight [m] (print in cm).
struct TrackingMetrics {
  double rmse_xy_m = 0.0;   ///< √mean(e_x² + e_y²)
  double rmse_z_m = 0.0;    ///< √mean(e_z²)
  double rmse_all_m = 0.0;  ///< √mean(‖e‖²)
  double max_m = 0.0;       ///< max ‖e‖
  double std_m = 0.0;       ///< population standard deviation of ‖e‖
  std::size_t samples = 0;
};

/// Streaming accumulator (Welford for the norm's variance): constant memory for any length.
class TrackingAccumulator {
 public:
  /// Adds one error sample e = p_ref − p_true [m]; non-finite samples are ignored and counted.
  void add(const Eigen::Vector3d& error_m) noexcept;

  [[nodiscard]] TrackingMetrics result() const noexcept;
  [[nodiscard]] std::size_t rejected() const noexcept { return rejected_; }

 private:
  std::size_t n_ = 0;
  std::size_t rejected_ = 0;
  double sum_xy2_ = 0.0;
  double sum_z2_ = 0.0;
  double max_ = 0.0;
  double mean_norm_ = 0.0;
  double m2_norm_ = 0.0;
};

}  // namespace geaware::experiments
