// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/hover_experiment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace geaware::experiments {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

traj::HoverDescentParams hoverDescentFor(const HoverSettings& s) {
  traj::HoverDescentParams p;
  p.from_height_m = s.from_height_m;
  p.to_height_m = s.to_height_m;
  p.descent_rate_mps = s.descent_rate_mps;
  p.hold_start_s = s.hold_start_s;
  p.hold_end_s = s.hold_end_s;
  return p;
}

HeightBinning hoverBinning(const HoverSettings& s) {
  HeightBinning b;
  b.bin_width_m = s.bin_width_m;
  b.max_height_m = s.max_height_m;
  return b;
}

HoverCurve summariseHover(control::TorqueCompensation torque,
                          const std::vector<std::uint64_t>& seeds,
                          const std::vector<FlightResult>& flights) {
  if (seeds.size() != flights.size()) {
    throw std::invalid_argument("summariseHover: one flight per seed expected");
  }
  HoverCurve c;
  c.torque = torque;
  c.seeds = seeds;
  if (flights.empty()) return c;
  for (const auto& f : flights) {
    if (f.crash) ++c.crashes;
  }
  const std::size_t nbins = flights.front().angle_error_by_height.size();
  for (std::size_t b = 0; b < nbins; ++b) {
    HoverBin bin;
    bin.h_low_m = flights.front().angle_error_by_height[b].h_low_m;
    bin.h_high_m = flights.front().angle_error_by_height[b].h_high_m;
    double sum = 0.0;
    double sum2 = 0.0;
    int n = 0;
    for (const auto& f : flights) {
      const AngleErrorBin& a = f.angle_error_by_height.at(b);
      bin.samples += a.samples;
      if (a.samples == 0) {
        bin.per_seed_deg.push_back(kNaN);
        continue;
      }
      bin.per_seed_deg.push_back(a.mean_deg);
      ++bin.seeds_visited;
      sum += a.mean_deg;
      sum2 += a.mean_deg * a.mean_deg;
      ++n;
    }
    if (n == 0) continue;
    bin.angle_err_deg = sum / n;
    bin.angle_err_std_deg = std::sqrt(std::max(0.0, sum2 / n - bin.angle_err_deg * bin.angle_err_deg));
    c.bins.push_back(std::move(bin));
  }
  return c;
}

double bandMean(const HoverCurve& c, double from_m, double to_m) {
  double sum = 0.0;
  double w = 0.0;
  for (const auto& b : c.bins) {
    if (b.centre_m() < from_m || b.centre_m() >= to_m) continue;
    sum += b.angle_err_deg * static_cast<double>(b.samples);
    w += static_cast<double>(b.samples);
  }
  return w > 0.0 ? sum / w : kNaN;
}

double hoverNearHighRatio(const HoverCurve& c) { return bandMean(c, 0.1, 0.3) / bandMean(c, 1.0, 1.5); }

double bandMax(const HoverCurve& c, double from_m, double to_m) {
  double m = kNaN;
  for (const auto& b : c.bins) {
    if (b.centre_m() < from_m || b.centre_m() >= to_m) continue;
    if (!(b.angle_err_deg <= m)) m = b.angle_err_deg;
  }
  return m;
}

double peakHeight(const HoverCurve& c) {
  double h = kNaN;
  double best = -1.0;
  for (const auto& b : c.bins) {
    if (b.seeds_visited < c.seeds.size()) continue;
    if (b.angle_err_deg > best) {
      best = b.angle_err_deg;
      h = b.centre_m();
    }
  }
  return h;
}

}  // namespace geaware::experiments
