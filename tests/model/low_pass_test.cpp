// SPDX-License-Identifier: BSD-3-Clause
// The filter type of the controller and the disturbance observer: a second-order Butterworth low-pass.
#include "geaware/model/low_pass.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace {

using geaware::model::LowPass2;
using Vec1 = Eigen::Matrix<double, 1, 1>;

/// Steady-state amplitude of the filter's response to a sine at f_hz.
double gainAt(double f_hz, double cutoff_hz, double rate_hz) {
  LowPass2<1> lp(cutoff_hz, rate_hz);
  double peak = 0.0;
  const int n = static_cast<int>(rate_hz * 20.0);
  for (int k = 0; k < n; ++k) {
    const double y = lp.update(Vec1(std::sin(2.0 * std::numbers::pi * f_hz * k / rate_hz)))(0);
    if (k > n / 2) peak = std::max(peak, std::abs(y));
  }
  return peak;
}

TEST(LowPass2, UnityDcGainAndSteadyStart) {
  LowPass2<3> lp(30.0, 200.0);
  const Eigen::Vector3d x(1.0, -2.0, 3.0);
  // First sample initialises in steady state: no transient.
  EXPECT_TRUE(lp.update(x).isApprox(x, 1e-15));
  for (int k = 0; k < 10; ++k) EXPECT_TRUE(lp.update(x).isApprox(x, 1e-12));
}

TEST(LowPass2, ButterworthMagnitudeResponse) {
  // −3 dB (1/√2) at the cut-off exactly, thanks to pre-warping; strong attenuation an octave
  // and more above (second order: ≈ −12 dB/octave), and a flat pass band.
  EXPECT_NEAR(gainAt(30.0, 30.0, 200.0), 1.0 / std::sqrt(2.0), 0.01);
  EXPECT_NEAR(gainAt(2.0, 30.0, 200.0), 1.0, 0.005);
  EXPECT_LT(gainAt(80.0, 30.0, 200.0), 0.2);
}

TEST(LowPass2, StepResponseSettlesWithSmallOvershoot) {
  LowPass2<1> lp(30.0, 200.0);
  lp.reset(Vec1(0.0));
  double peak = 0.0, last = 0.0;
  for (int k = 0; k < 200; ++k) peak = std::max(peak, last = lp.update(Vec1(1.0))(0));
  EXPECT_NEAR(last, 1.0, 1e-9);
  // Continuous Butterworth: 4.3 % overshoot; the bilinear transform at fc/fs = 0.15 gives 6.2 %.
  EXPECT_LT(peak, 1.07);
  EXPECT_GT(peak, 1.0);
}

}  // namespace
