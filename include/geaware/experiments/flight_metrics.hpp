// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The metrics of a flight as observers of its control ticks (flight.hpp): each reads the tick
// (reference, estimate, truth) and writes its part of the FlightResult after the loop. The
// runner attaches them to every flight; anyone can attach them to a flight of their own.
// No allocation in onTick.

#include <cstdint>
#include <vector>

#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/tracking_metrics.hpp"

namespace geaware::experiments {

/// Streaming RMS of finite values (non-finite ones are skipped).
struct StreamingRms {
  double sum_sq = 0.0;
  std::uint64_t n = 0;
  void add(double e) noexcept {
    if (!std::isfinite(e)) return;
    sum_sq += e * e;
    ++n;
  }
  [[nodiscard]] double value() const noexcept {
    return n ? std::sqrt(sum_sq / static_cast<double>(n)) : 0.0;
  }
};

/// Table I metrics: reference vs TRUE position over the ticks of the trajectory.
class TrackingObserver final : public FlightObserver {
 public:
  void onTick(const FlightTick& tick) noexcept override;
  void writeTo(FlightResult& r) const { r.tracking = tracking_.result(); }

 private:
  TrackingAccumulator tracking_;
};

/// The hover experiment's angle error E(h) by true height (ticks of the trajectory on which
/// the controller ran).
class AngleErrorBinsObserver final : public FlightObserver {
 public:
  explicit AngleErrorBinsObserver(const HeightBinning& binning);
  void onTick(const FlightTick& tick) noexcept override;
  void writeTo(FlightResult& r) const;

 private:
  struct Bin {
    std::uint64_t n = 0;
    double sum = 0.0;
    double sum_sq = 0.0;
    double max = 0.0;
  };
  HeightBinning binning_;
  std::vector<Bin> bins_;
};

/// The estimators against the truth: position, velocity and attitude RMSE of the ESKF, and the
/// controller flags counted per tick.
class EstimationObserver final : public FlightObserver {
 public:
  void onTick(const FlightTick& tick) noexcept override;
  void writeTo(FlightResult& r) const;

 private:
  StreamingRms position_, velocity_, attitude_;
  std::array<std::uint64_t, kControllerFlagBits> flags_{};
};

}  // namespace geaware::experiments
