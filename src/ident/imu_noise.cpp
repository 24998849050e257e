// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/ident/imu_noise.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace geaware::ident {
namespace {

/// Cluster times of the fit [s] (header: above the filter's correlation, below the hover's
/// own motion) and the clusters the longest needs.
constexpr std::array<double, 3> kTau_s = {0.05, 0.1, 0.2};
constexpr double kMinClusters = 10.0;

double rmsOf(const std::array<double, 3>& v) {
  return std::sqrt((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) / 3.0);
}

/// N = σ_A(τ)·√τ, averaged over the cluster times in the log (in variance: N² averaged).
double densityOf(const std::vector<double>& x, double dt_s) {
  double sum = 0.0;
  int count = 0;
  for (double tau : kTau_s) {
    const auto m = static_cast<std::size_t>(std::lround(tau / dt_s));
    if (m < 1 || x.size() < 2 * m + 1) continue;
    const double tau_m = static_cast<double>(m) * dt_s;
    const double adev = overlappingAllanDeviation(x, m);
    sum += adev * adev * tau_m;
    ++count;
  }
  return std::sqrt(sum / count);
}

}  // namespace

double overlappingAllanDeviation(const std::vector<double>& x, std::size_t m) {
  const std::size_t n = x.size();
  if (m == 0 || n < 2 * m + 1) return kNaN;
  // Prefix sums: the mean of x[k, k+m) is (S[k+m] − S[k])/m.
  std::vector<double> S(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) S[i + 1] = S[i] + x[i];
  const double md = static_cast<double>(m);
  double sum = 0.0;
  for (std::size_t k = 0; k + 2 * m <= n; ++k) {
    const double d = (S[k + 2 * m] - 2.0 * S[k + m] + S[k]) / md;
    sum += d * d;
  }
  return std::sqrt(sum / (2.0 * static_cast<double>(n - 2 * m + 1)));
}

ImuNoiseFit fitImuNoise(const std::vector<double>& t_s, const std::array<std::vector<double>, 3>& gyro_B,
                        const std::array<std::vector<double>, 3>& accel_B) {
  const std::size_t n = t_s.size();
  for (std::size_t a = 0; a < 3; ++a) {
    if (gyro_B[a].size() != n || accel_B[a].size() != n) {
      throw IdentError(fmt::format("IMU noise: axis {} has {} gyro and {} accelerometer samples for {} times",
                                   a, gyro_B[a].size(), accel_B[a].size(), n));
    }
  }
  if (n < 2) throw IdentError(fmt::format("IMU noise: {} samples; need a hover log", n));
  std::vector<double> dt(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    dt[i] = t_s[i + 1] - t_s[i];
    if (!(dt[i] > 0.0) || !std::isfinite(dt[i])) {
      throw IdentError(fmt::format("IMU noise: time does not increase at sample {} (t = {} s, then {} s)",
                                   i, t_s[i], t_s[i + 1]));
    }
  }
  for (std::size_t a = 0; a < 3; ++a) {
    for (std::size_t i = 0; i < n; ++i) {
      if (!std::isfinite(gyro_B[a][i]) || !std::isfinite(accel_B[a][i])) {
        throw IdentError(fmt::format("IMU noise: a non-finite IMU value at sample {} (t = {} s)", i, t_s[i]));
      }
    }
  }
  ImuNoiseFit f;
  f.samples = n;
  std::vector<double> sorted = dt;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  f.sample_interval_s = sorted[sorted.size() / 2];
  const double needed_s = kMinClusters * kTau_s.back();
  if (t_s.back() - t_s.front() < needed_s) {
    throw IdentError(fmt::format("IMU noise: the log spans {:.3f} s; τ = {} s with {} clusters needs {:.2f} s",
                                 t_s.back() - t_s.front(), kTau_s.back(), kMinClusters, needed_s));
  }
  const auto [lo, hi] = std::minmax_element(dt.begin(), dt.end());
  if (*hi > 1.5 * f.sample_interval_s || *lo < 0.5 * f.sample_interval_s) {
    f.warnings.push_back(fmt::format(
        "IMU noise: sample intervals from {:.4f} to {:.4f} s around a median of {:.4f} s; the Allan "
        "deviation assumes uniform sampling", *lo, *hi, f.sample_interval_s));
  }
  for (std::size_t a = 0; a < 3; ++a) {
    f.gyro_density_rad_per_s_sqrtHz[a] = densityOf(gyro_B[a], f.sample_interval_s);
    f.accel_density_m_per_s2_sqrtHz[a] = densityOf(accel_B[a], f.sample_interval_s);
  }
  f.gyro_noise_density_rad_per_s_sqrtHz = rmsOf(f.gyro_density_rad_per_s_sqrtHz);
  f.accel_noise_density_m_per_s2_sqrtHz = rmsOf(f.accel_density_m_per_s2_sqrtHz);
  return f;
}

}  // namespace geaware::ident
