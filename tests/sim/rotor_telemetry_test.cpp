// SPDX-License-Identifier: BSD-3-Clause
// Simulated rotor-speed telemetry: rate, noise statistics, quantisation, no negative speeds.
#include "geaware/sim/rotor_telemetry.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "geaware/model/vehicle_model.hpp"

namespace geaware::sim {
namespace {

PlantState spinning(double t_s, double n_rpm) {
  PlantState s;
  s.t_s = t_s;
  s.n_rpm = {n_rpm, n_rpm + 100, n_rpm + 200, n_rpm + 300};
  return s;
}

TEST(RotorTelemetry, SamplesAtItsRate) {
  RotorTelemetrySensor tel(RotorTelemetryParams{}, 1);
  int n = 0;
  for (int k = 0; k < 1000; ++k) n += tel.sample(spinning(k * 1e-3, 10'000)).has_value();
  EXPECT_EQ(n, 200);
}

TEST(RotorTelemetry, NoiseHasTheConfiguredStdAndNoBias) {
  // 50,000 samples, no quantisation: std error of the std ≈ 0.3 % (allow 3 %), of the mean
  // 0.045 rpm (allow 0.25 rpm).
  RotorTelemetryParams p;
  p.noise_std_rpm = 10.0;
  p.resolution_rpm = 0.0;
  RotorTelemetrySensor tel(p, 2);
  constexpr int kN = 50'000;
  Eigen::Array4d s1 = Eigen::Array4d::Zero(), s2 = Eigen::Array4d::Zero();
  for (int k = 0; k < kN; ++k) {
    const PlantState s = spinning(k / p.rate_Hz, 10'000);
    const auto m = tel.sample(s);
    ASSERT_TRUE(m);
    const Eigen::Array4d e = m->n_rpm.array() - Eigen::Array4d(10'000, 10'100, 10'200, 10'300);
    s1 += e;
    s2 += e.square();
  }
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(s1[i] / kN, 0.0, 0.25) << "rotor " << i;
    EXPECT_NEAR(std::sqrt(s2[i] / kN) / 10.0, 1.0, 0.03) << "rotor " << i;
  }
}

TEST(RotorTelemetry, QuantisedToItsResolutionAndNeverNegative) {
  RotorTelemetryParams p;  // defaults: 100/7 rpm steps
  RotorTelemetrySensor tel(p, 3);
  for (int k = 0; k < 200; ++k) {
    const auto m = tel.sample(spinning(k / p.rate_Hz, 9'876.5));
    ASSERT_TRUE(m);
    for (int i = 0; i < 4; ++i) {
      const double steps = m->n_rpm[i] / p.resolution_rpm;
      EXPECT_NEAR(steps, std::round(steps), 1e-9);
    }
  }
  PlantState stopped;
  stopped.t_s = 10.0;
  const auto m = tel.sample(stopped);
  ASSERT_TRUE(m);
  EXPECT_TRUE((m->n_rpm.array() >= 0.0).all());
}

TEST(RotorTelemetry, RefusesInvalidParametersAndStates) {
  RotorTelemetryParams p;
  p.noise_std_rpm = -1.0;
  ASSERT_EQ(p.validate().size(), 1u);
  EXPECT_EQ(p.validate()[0].field, "noise_std_rpm");
  EXPECT_THROW(RotorTelemetrySensor(p, 1), model::InvalidParameters);
  RotorTelemetrySensor tel(RotorTelemetryParams{}, 1);
  PlantState s;
  s.n_rpm[0] = std::nan("");
  EXPECT_FALSE(tel.sample(s));
  EXPECT_EQ(tel.rejected(), 1);
}

}  // namespace
}  // namespace geaware::sim
