// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A curve of height given at measured points ("knots"), for ground-effect curves that the
// paper's closed forms do not follow (docs/vehicle-file.md, "Tables instead of formulas").
//
//  - Between the knots: monotone piecewise-cubic Hermite interpolation (PCHIP, Fritsch–Carlson
//    slopes as in Fritsch & Butland 1984). It is C¹, passes through every knot, and never
//    overshoots: on each interval it stays between the two knot values, so a table that rises
//    to a peak and falls has its maximum at a knot.
//  - Below the first knot: the first value, held (slope 0). Heights below the table were not
//    measured; GroundEffectModel clamps h to the landing-gear height anyway.
//  - Above the last knot: an inverse-square tail v_N·(h_N/h)², the far-field decay of a
//    ground cushion (F_G of the paper's own form falls as 1/h² too). The last knot's slope is
//    the tail's, −2·v_N/h_N, limited as the interior slopes are, so the curve is C¹ there
//    whenever the data allow.
//
// Construction allocates; value(), slope() and setValues() do not; the first two cost one
// binary search.

#include <cstddef>
#include <vector>

namespace geaware::model {

class HeightTable {
 public:
  HeightTable() = default;

  /// Requires at least 2 knots, strictly increasing positive finite heights [m] and finite
  /// values of the same count (VehicleParams::validate() checks this for vehicle files);
  /// throws std::invalid_argument otherwise.
  HeightTable(std::vector<double> heights_m, std::vector<double> values);

  [[nodiscard]] bool empty() const noexcept { return h_.empty(); }
  [[nodiscard]] std::size_t size() const noexcept { return h_.size(); }
  [[nodiscard]] const std::vector<double>& heights() const noexcept { return h_; }
  [[nodiscard]] const std::vector<double>& values() const noexcept { return v_; }
  /// The interpolation slope at each knot [value unit per m].
  [[nodiscard]] const std::vector<double>& knotSlopes() const noexcept { return d_; }

  /// The curve at height h [value unit]. NaN for a NaN h.
  [[nodiscard]] double value(double h_m) const noexcept;
  /// Its derivative d/dh [value unit per m].
  [[nodiscard]] double slope(double h_m) const noexcept;

  /// New values at the same knots (size() of them, finite): the curve a table built from them
  /// would be, bit for bit. No allocation (a curve learned in flight, control/ground_effect_learner).
  void setValues(const double* values) noexcept;

 private:
  void computeSlopes() noexcept;
  /// Index k of the interval [h_k, h_k+1] holding h (h_0 ≤ h < h_N).
  [[nodiscard]] std::size_t interval(double h_m) const noexcept;

  std::vector<double> h_;
  std::vector<double> v_;
  std::vector<double> d_;
};

}  // namespace geaware::model
