// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/tracking_metrics.hpp"

#include <algorithm>
#include <cmath>

#include "geaware/model/finite.hpp"

namespace geaware::experiments {

void TrackingAccumulator::add(const Eigen::Vector3d& e) noexcept {
  if (!model::allFinite(e)) {
    ++rejected_;
    return;
  }
  ++n_;
  sum_xy2_ += e.x() * e.x() + e.y() * e.y();
  sum_z2_ += e.z() * e.z();
  const double norm = e.norm();
  max_ = std::max(max_, norm);
  const double delta = norm - mean_norm_;
  mean_norm_ += delta / static_cast<double>(n_);
  m2_norm_ += delta * (norm - mean_norm_);
}

TrackingMetrics TrackingAccumulator::result() const noexcept {
  TrackingMetrics m;
  m.samples = n_;
  if (n_ == 0) return m;
  const double n = static_cast<double>(n_);
  m.rmse_xy_m = std::sqrt(sum_xy2_ / n);
  m.rmse_z_m = std::sqrt(sum_z2_ / n);
  m.rmse_all_m = std::sqrt((sum_xy2_ + sum_z2_) / n);
  m.max_m = max_;
  m.std_m = std::sqrt(m2_norm_ / n);
  return m;
}

}  // namespace geaware::experiments
