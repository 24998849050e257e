// SPDX-License-Identifier: BSD-3-Clause
// The IMU noise fit: known white noise, noise through the flight controller's low-pass (whose
// density at low frequency is the raw one: the filter's DC gain is 1), the Allan deviation's
// closed form for a pure random walk, and refused logs.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "geaware/ident/imu_noise.hpp"
#include "geaware/model/low_pass.hpp"

namespace geaware::ident {
namespace {

struct Log {
  std::vector<double> t;
  std::array<std::vector<double>, 3> gyro, accel;
};

/// n samples at rate_hz of white noise with per-sample σ, gyro and accelerometer.
Log whiteLog(std::size_t n, double rate_hz, double gyro_std, double accel_std, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> z(0.0, 1.0);
  Log l;
  for (std::size_t i = 0; i < n; ++i) {
    l.t.push_back(static_cast<double>(i) / rate_hz);
    for (std::size_t a = 0; a < 3; ++a) {
      l.gyro[a].push_back(0.1 * static_cast<double>(a) + gyro_std * z(rng));  // a constant rate too
      l.accel[a].push_back((a == 2 ? 9.81 : 0.0) + accel_std * z(rng));
    }
  }
  return l;
}

TEST(ImuNoise, RecoversTheDensityOfWhiteNoise) {
  // σ per sample at 200 Hz is N·√200: N = 0.02 m/s²/√Hz, 0.001 rad/s/√Hz.
  const double rate = 200.0;
  const Log l = whiteLog(6000, rate, 1e-3 * std::sqrt(rate), 0.02 * std::sqrt(rate), 7);
  const ImuNoiseFit f = fitImuNoise(l.t, l.gyro, l.accel);
  EXPECT_NEAR(f.sample_interval_s, 0.005, 1e-12);
  EXPECT_EQ(f.samples, 6000u);
  EXPECT_TRUE(f.warnings.empty());
  for (std::size_t a = 0; a < 3; ++a) {
    // 30 s: the estimate at τ = 0.2 s averages ≈ 150 independent clusters, a few % of scatter.
    EXPECT_NEAR(f.accel_density_m_per_s2_sqrtHz[a], 0.02, 0.02 * 0.08) << a;
    EXPECT_NEAR(f.gyro_density_rad_per_s_sqrtHz[a], 1e-3, 1e-3 * 0.08) << a;
  }
  EXPECT_NEAR(f.accel_noise_density_m_per_s2_sqrtHz, 0.02, 0.02 * 0.05);
}

TEST(ImuNoise, ReadsTheLowFrequencyDensityBehindTheFlightControllersFilter) {
  // White vibration at 1 kHz, σ_raw per sample, through a 20 Hz Butterworth, sampled at 200 Hz:
  // the output's per-sample σ is σ_raw·√Σh² ≈ 0.21·σ_raw, but its density at the estimator's
  // time scales is the raw one, σ_raw/√1000 (DC gain 1). A fit that took the output's σ as
  // white at 200 Hz would read 0.21·σ_raw/√200 ≈ 0.47 of it.
  const double raw_rate = 1000.0, sigma_raw = 2.0;
  std::mt19937_64 rng(11);
  std::normal_distribution<double> z(0.0, 1.0);
  model::LowPass2<3> lp(20.0, raw_rate);
  lp.reset(Eigen::Vector3d::Zero());
  Log l;
  for (std::size_t i = 0; i < 30000; ++i) {
    const Eigen::Vector3d y = lp.update(sigma_raw * Eigen::Vector3d(z(rng), z(rng), z(rng)));
    if (i % 5 != 4) continue;
    l.t.push_back(static_cast<double>(i) / raw_rate);
    for (std::size_t a = 0; a < 3; ++a) {
      l.accel[a].push_back(y(static_cast<Eigen::Index>(a)));
      l.gyro[a].push_back(0.0);
    }
  }
  const ImuNoiseFit f = fitImuNoise(l.t, l.gyro, l.accel);
  EXPECT_NEAR(f.accel_noise_density_m_per_s2_sqrtHz, sigma_raw / std::sqrt(raw_rate),
              0.1 * sigma_raw / std::sqrt(raw_rate));
  EXPECT_EQ(f.gyro_noise_density_rad_per_s_sqrtHz, 0.0);
}

TEST(ImuNoise, AllanDeviationOfALineAndOfAConstant) {
  // A line x = c·k: every pair of adjacent cluster means differs by c·m, so σ_A = c·m/√2.
  std::vector<double> line;
  for (int k = 0; k < 101; ++k) line.push_back(0.5 * k);
  EXPECT_NEAR(overlappingAllanDeviation(line, 10), 0.5 * 10 / std::sqrt(2.0), 1e-9);
  // A constant has none; too few samples for the cluster size is NaN, not a number.
  EXPECT_EQ(overlappingAllanDeviation(std::vector<double>(50, 3.0), 5), 0.0);
  EXPECT_TRUE(std::isnan(overlappingAllanDeviation(std::vector<double>(20, 1.0), 10)));
}

TEST(ImuNoise, RefusesLogsItCannotRead) {
  Log l = whiteLog(300, 200.0, 0.01, 0.1, 3);  // 1.5 s: τ = 0.2 s needs 2 s for 10 clusters
  EXPECT_THROW((void)fitImuNoise(l.t, l.gyro, l.accel), IdentError);
  l = whiteLog(1000, 200.0, 0.01, 0.1, 3);
  l.t[500] = l.t[499];
  EXPECT_THROW((void)fitImuNoise(l.t, l.gyro, l.accel), IdentError);
  l = whiteLog(1000, 200.0, 0.01, 0.1, 3);
  l.accel[1][7] = std::nan("");
  EXPECT_THROW((void)fitImuNoise(l.t, l.gyro, l.accel), IdentError);
  l = whiteLog(1000, 200.0, 0.01, 0.1, 3);
  l.gyro[2].pop_back();
  EXPECT_THROW((void)fitImuNoise(l.t, l.gyro, l.accel), IdentError);
}

}  // namespace
}  // namespace geaware::ident
