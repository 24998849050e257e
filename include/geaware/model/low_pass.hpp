// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Second-order Butterworth low-pass filter on fixed-size vectors (bilinear transform with
// pre-warping), the one filter type of the controller and the disturbance observer: incremental
// inversion needs the filtered angular acceleration ω̇_f and the filtered rotor torque τ̂_B to be
// delayed alike, so both use one instance type with one cut-off (Smeur et al. 2016; Tal &
// Karaman 2020).

#include <cmath>
#include <numbers>

#include <Eigen/Core>

namespace geaware::model {

template <int N>
class LowPass2 {
 public:
  using Vector = Eigen::Matrix<double, N, 1>;

  /// cutoff_hz must lie in (0, sample_rate_hz/2); checked by the owner's params validation.
  LowPass2(double cutoff_hz, double sample_rate_hz) noexcept {
    const double k = std::tan(std::numbers::pi * cutoff_hz / sample_rate_hz);
    const double q = std::numbers::sqrt2;  // 1/Q of a Butterworth section
    const double norm = 1.0 / (1.0 + q * k + k * k);
    b0_ = k * k * norm;
    b1_ = 2.0 * b0_;
    b2_ = b0_;
    a1_ = 2.0 * (k * k - 1.0) * norm;
    a2_ = (1.0 - q * k + k * k) * norm;
  }

  /// Starts the filter in steady state at `x` (no transient from zero).
  void reset(const Vector& x) noexcept {
    x1_ = x2_ = y1_ = y2_ = x;
    initialised_ = true;
  }

  /// Filters one sample; the first sample initialises the filter in steady state.
  const Vector& update(const Vector& x) noexcept {
    if (!initialised_) reset(x);
    const Vector y = b0_ * x + b1_ * x1_ + b2_ * x2_ - a1_ * y1_ - a2_ * y2_;
    x2_ = x1_;
    x1_ = x;
    y2_ = y1_;
    y1_ = y;
    return y1_;
  }

  [[nodiscard]] const Vector& value() const noexcept { return y1_; }
  [[nodiscard]] bool initialised() const noexcept { return initialised_; }

 private:
  double b0_, b1_, b2_, a1_, a2_;
  Vector x1_ = Vector::Zero(), x2_ = Vector::Zero(), y1_ = Vector::Zero(), y2_ = Vector::Zero();
  bool initialised_ = false;
};

}  // namespace geaware::model
