// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/flight_metrics.hpp"

#include <algorithm>
#include <cmath>

#include "geaware/model/rotation.hpp"
#include "geaware/model/units.hpp"

namespace geaware::experiments {
namespace {
constexpr double kRadToDeg = 1.0 / model::kDegToRad;
}  // namespace

void TrackingObserver::onTick(const FlightTick& k) noexcept {
  if (k.in_trajectory) tracking_.add(k.input.reference.p_W - k.truth.p_W);
}

AngleErrorBinsObserver::AngleErrorBinsObserver(const HeightBinning& binning)
    : binning_(binning),
      bins_(static_cast<std::size_t>(std::ceil(binning.max_height_m / binning.bin_width_m - 1e-9))) {}

void AngleErrorBinsObserver::onTick(const FlightTick& k) noexcept {
  if (!k.in_trajectory || !k.controller_active) return;
  const double h = k.true_height_m;
  if (!(h >= 0.0 && h < binning_.max_height_m)) return;
  const auto i = std::min(static_cast<std::size_t>(h / binning_.bin_width_m), bins_.size() - 1);
  Bin& b = bins_[i];
  const double deg = k.attitude_error_rad * kRadToDeg;
  ++b.n;
  b.sum += deg;
  b.sum_sq += deg * deg;
  b.max = std::max(b.max, deg);
}

void AngleErrorBinsObserver::writeTo(FlightResult& r) const {
  r.angle_error_by_height.resize(bins_.size());
  for (std::size_t i = 0; i < bins_.size(); ++i) {
    AngleErrorBin& b = r.angle_error_by_height[i];
    const Bin& a = bins_[i];
    b.h_low_m = static_cast<double>(i) * binning_.bin_width_m;
    b.h_high_m = std::min(static_cast<double>(i + 1) * binning_.bin_width_m, binning_.max_height_m);
    b.samples = a.n;
    if (a.n > 0) {
      const auto n = static_cast<double>(a.n);
      b.mean_deg = a.sum / n;
      b.rms_deg = std::sqrt(a.sum_sq / n);
      b.max_deg = a.max;
    }
  }
}

void EstimationObserver::onTick(const FlightTick& k) noexcept {
  if (!k.controller_active) return;
  for (int b = 0; b < kControllerFlagBits; ++b) {
    if ((k.output.flags >> b) & 1u) ++flags_[static_cast<std::size_t>(b)];
  }
  if (!k.in_trajectory) return;
  const auto& e = k.input.estimate;
  position_.add((e.p_W - k.truth.p_W).norm());
  velocity_.add((e.v_W - k.truth.v_W).norm());
  attitude_.add(model::angleBetween(e.q_WB, k.truth.q_WB) * kRadToDeg);
}

void EstimationObserver::writeTo(FlightResult& r) const {
  r.flag_counts = flags_;
  r.estimation.position_rmse_m = position_.value();
  r.estimation.velocity_rmse_mps = velocity_.value();
  r.estimation.attitude_rmse_deg = attitude_.value();
}

}  // namespace geaware::experiments
