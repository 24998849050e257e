// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/model/height_table.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace geaware::model {
namespace {

int sign(double x) noexcept { return (x > 0.0) - (x < 0.0); }

/// Limits an end slope d so that the end interval (secant delta) stays monotone, as scipy's
/// PchipInterpolator does: a slope against the secant becomes 0; one steeper than 3·delta is
/// cut to 3·delta (the Fritsch–Carlson bound).
double limitEndSlope(double d, double delta) noexcept {
  if (sign(d) != sign(delta)) return 0.0;
  if (std::abs(d) > 3.0 * std::abs(delta)) return 3.0 * delta;
  return d;
}

}  // namespace

HeightTable::HeightTable(std::vector<double> heights_m, std::vector<double> values)
    : h_(std::move(heights_m)), v_(std::move(values)) {
  const std::size_t n = h_.size();
  if (n < 2 || v_.size() != n) {
    throw std::invalid_argument("HeightTable: needs at least 2 knots and one value per height (got " +
                                std::to_string(n) + " heights, " + std::to_string(v_.size()) +
                                " values)");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(h_[i]) || !(h_[i] > 0.0) || !std::isfinite(v_[i]) ||
        (i > 0 && !(h_[i] > h_[i - 1]))) {
      throw std::invalid_argument("HeightTable: knot " + std::to_string(i) +
                                  " is not finite, not positive or not above the previous one");
    }
  }
  d_.assign(n, 0.0);
  computeSlopes();
}

void HeightTable::setValues(const double* values) noexcept {
  for (std::size_t i = 0; i < v_.size(); ++i) v_[i] = values[i];
  computeSlopes();
}

void HeightTable::computeSlopes() noexcept {
  const std::size_t n = h_.size();
  const auto step = [&](std::size_t k) { return h_[k + 1] - h_[k]; };
  const auto delta = [&](std::size_t k) { return (v_[k + 1] - v_[k]) / step(k); };
  std::fill(d_.begin(), d_.end(), 0.0);
  // Interior knots: the weighted harmonic mean of the neighbouring secants when they have the
  // same sign, 0 at a local extremum of the data (Fritsch & Butland).
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double a = delta(k - 1);
    const double b = delta(k);
    if (sign(a) == 0 || sign(a) != sign(b)) continue;
    const double w1 = 2.0 * step(k) + step(k - 1);
    const double w2 = step(k) + 2.0 * step(k - 1);
    d_[k] = (w1 + w2) / (w1 / a + w2 / b);
  }
  if (n == 2) {
    d_[0] = delta(0);
  } else {
    // First knot: the three-point one-sided estimate, limited.
    const double d0 = ((2.0 * step(0) + step(1)) * delta(0) - step(0) * delta(1)) / (step(0) + step(1));
    d_[0] = limitEndSlope(d0, delta(0));
  }
  // Last knot: the slope of the inverse-square tail, limited.
  d_[n - 1] = limitEndSlope(-2.0 * v_[n - 1] / h_[n - 1], delta(n - 2));
}

std::size_t HeightTable::interval(double h_m) const noexcept {
  const auto it = std::upper_bound(h_.begin() + 1, h_.end() - 1, h_m);
  return static_cast<std::size_t>(it - h_.begin()) - 1;
}

double HeightTable::value(double h_m) const noexcept {
  if (std::isnan(h_m) || h_.empty()) return std::nan("");
  if (h_m <= h_.front()) return v_.front();
  if (h_m >= h_.back()) {
    const double r = h_.back() / h_m;
    return v_.back() * r * r;
  }
  const std::size_t k = interval(h_m);
  const double dx = h_[k + 1] - h_[k];
  const double t = (h_m - h_[k]) / dx;
  const double t2 = t * t;
  const double t3 = t2 * t;
  return (2.0 * t3 - 3.0 * t2 + 1.0) * v_[k] + (t3 - 2.0 * t2 + t) * dx * d_[k] +
         (-2.0 * t3 + 3.0 * t2) * v_[k + 1] + (t3 - t2) * dx * d_[k + 1];
}

double HeightTable::slope(double h_m) const noexcept {
  if (std::isnan(h_m) || h_.empty()) return std::nan("");
  if (h_m < h_.front()) return 0.0;
  if (h_m >= h_.back()) {
    const double r = h_.back() / h_m;
    return -2.0 * v_.back() * r * r / h_m;
  }
  const std::size_t k = interval(h_m);
  const double dx = h_[k + 1] - h_[k];
  const double t = (h_m - h_[k]) / dx;
  const double t2 = t * t;
  return (6.0 * t2 - 6.0 * t) * (v_[k] - v_[k + 1]) / dx + (3.0 * t2 - 4.0 * t + 1.0) * d_[k] +
         (3.0 * t2 - 2.0 * t) * d_[k + 1];
}

}  // namespace geaware::model
