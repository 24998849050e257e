// SPDX-License-Identifier: BSD-3-Clause
// Rotor-harmonic vibration at the IMU (sim/rotor_vibration.hpp): its standard deviation, its
// frequencies, its speed² scaling and what the flight controller's filter leaves of it.

#include <cmath>
#include <complex>
#include <numbers>

#include <gtest/gtest.h>

#include "geaware/model/units.hpp"
#include "geaware/sim/imu.hpp"
#include "geaware/sim/rotor_vibration.hpp"

namespace geaware::sim {
namespace {

constexpr double kRawRate_Hz = 1000.0;
constexpr double kRefRpm = 10200.0;

ImuParams quiet() {
  ImuParams p;
  p.gyro_noise_density_rad_per_s_sqrtHz = 0.0;
  p.gyro_bias_walk_rad_per_s2_sqrtHz = 0.0;
  p.gyro_initial_bias_std_rad_per_s = 0.0;
  p.accel_noise_density_m_per_s2_sqrtHz = 0.0;
  p.accel_bias_walk_m_per_s3_sqrtHz = 0.0;
  p.accel_initial_bias_std_m_per_s2 = 0.0;
  p.rotor_vibration.accel_std_m_per_s2 = 25.0;
  p.rotor_vibration.gyro_std_rad_per_s = 0.5;
  p.rotor_vibration.reference_rpm = kRefRpm;
  return p;
}

/// Hover at the given rotor speeds (slightly different per rotor, as a real vehicle's are).
PlantState hover(double t_s, double scale) {
  PlantState s;
  s.t_s = t_s;
  s.n_rpm = {scale * kRefRpm * 1.000, scale * kRefRpm * 1.013, scale * kRefRpm * 0.991, scale * kRefRpm * 1.021};
  return s;
}

struct Stats {
  Eigen::Vector3d accel_std = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_std = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_mean = Eigen::Vector3d::Zero();
  double x_power_at_1x = 0.0;  // fraction of accel_x's power at the first rotor's 1× line
};

/// Samples every output of 60 s of flight at the raw rate (the IMU's output rate set to it).
Stats measure(ImuParams p, double scale, std::uint64_t seed = 7) {
  p.rate_Hz = p.lowpass_cutoff_Hz > 0.0 ? 200.0 : kRawRate_Hz;
  Imu imu(p, seed);
  Stats st;
  Eigen::Vector3d sa = Eigen::Vector3d::Zero();
  Eigen::Vector3d sa2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d sg2 = Eigen::Vector3d::Zero();
  std::complex<double> line{0.0, 0.0};
  int n = 0;
  const double f1_Hz = scale * kRefRpm / 60.0;
  for (int k = 0; k < 60'000; ++k) {
    const PlantState s = hover(k / kRawRate_Hz, scale);
    const auto m = imu.sample(s);
    if (!m) continue;
    const Eigen::Vector3d a = m->accel_B - Eigen::Vector3d(0.0, 0.0, model::kGravity);
    sa += a;
    sa2 += a.cwiseProduct(a);
    sg2 += m->gyro_B.cwiseProduct(m->gyro_B);
    line += a.x() * std::polar(1.0, -2.0 * std::numbers::pi * f1_Hz * s.t_s);
    ++n;
  }
  st.accel_mean = sa / n;
  st.accel_std = (sa2 / n - st.accel_mean.cwiseProduct(st.accel_mean)).cwiseSqrt();
  st.gyro_std = (sg2 / n).cwiseSqrt();
  // A sinusoid of amplitude A has power A²/2 = 2|line/n|².
  st.x_power_at_1x = 2.0 * std::norm(line / static_cast<double>(n)) / (st.accel_std.x() * st.accel_std.x());
  return st;
}

TEST(RotorVibration, EachAxisHasTheConfiguredRawStdAtTheReferenceSpeed) {
  const Stats st = measure(quiet(), 1.0);
  // Four rotors at slightly different speeds: σ per axis = the parameter within the beat's
  // sampling error (60 s spans many beats).
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(st.accel_std[i] / 25.0, 1.0, 0.04) << "axis " << i;
    EXPECT_NEAR(st.gyro_std[i] / 0.5, 1.0, 0.04) << "axis " << i;
    EXPECT_NEAR(st.accel_mean[i], 0.0, 0.5) << "axis " << i;
  }
  // One rotor of four carries a quarter of the x power at its own rotation frequency.
  EXPECT_NEAR(st.x_power_at_1x, 0.25, 0.03);
}

TEST(RotorVibration, ItScalesWithTheSquareOfTheRotorSpeedAndStopsWithTheRotors) {
  const Stats half = measure(quiet(), 0.5);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(half.accel_std[i] / (25.0 / 4.0), 1.0, 0.04) << "axis " << i;
  const Stats stopped = measure(quiet(), 0.0);
  EXPECT_EQ(stopped.accel_std, Eigen::Vector3d::Zero());
  EXPECT_EQ(stopped.gyro_std, Eigen::Vector3d::Zero());
}

TEST(RotorVibration, TheFilterLeavesItsGainAtTheRotorHarmonics) {
  ImuParams p = quiet();
  p.lowpass_cutoff_Hz = 20.0;
  p.filter_rate_Hz = kRawRate_Hz;
  const Stats st = measure(p, 1.0);
  const LowPass2 lp(kRawRate_Hz, 20.0);
  const double f1_Hz = kRefRpm / 60.0;
  // x, y: imbalance at 1×; z: blade passage at 2× (two blades). The four rotors spread the
  // lines by ±2 %, the filter's gain by ±8 %: 10 % tolerance.
  EXPECT_NEAR(st.accel_std.x() / (25.0 * lp.gainAt(f1_Hz)), 1.0, 0.10);
  EXPECT_NEAR(st.accel_std.y() / (25.0 * lp.gainAt(f1_Hz)), 1.0, 0.10);
  EXPECT_NEAR(st.accel_std.z() / (25.0 * lp.gainAt(2.0 * f1_Hz)), 1.0, 0.10);
  EXPECT_LT(st.accel_std.z(), 0.2 * st.accel_std.x());
}

TEST(RotorVibration, GainAtIsTheButterworthResponse) {
  const LowPass2 lp(kRawRate_Hz, 20.0);
  EXPECT_NEAR(lp.gainAt(0.0), 1.0, 1e-12);
  EXPECT_NEAR(lp.gainAt(20.0), 1.0 / std::sqrt(2.0), 1e-9);  // pre-warped cutoff: exact
  // Bilinear map: |H| = 1/√(1 + (tan(πf/f_s)/tan(πf_c/f_s))⁴).
  for (double f : {5.0, 50.0, 170.0, 340.0, 450.0}) {
    const double r = std::tan(std::numbers::pi * f / kRawRate_Hz) / std::tan(std::numbers::pi * 20.0 / kRawRate_Hz);
    EXPECT_NEAR(lp.gainAt(f), 1.0 / std::sqrt(1.0 + r * r * r * r), 1e-9) << f;
  }
}

TEST(RotorVibration, TheSeedSetsThePhasesAndNothingElse) {
  const Stats a = measure(quiet(), 1.0, 7);
  const Stats b = measure(quiet(), 1.0, 7);
  const Stats c = measure(quiet(), 1.0, 8);
  EXPECT_EQ(a.accel_std, b.accel_std);
  EXPECT_NE(a.accel_std, c.accel_std);
  // The sensor's own noise stream is untouched by the vibration.
  ImuParams off;
  ImuParams on = off;
  on.rotor_vibration.accel_std_m_per_s2 = 25.0;
  Imu x(off, 5);
  Imu y(on, 5);
  for (int k = 0; k < 50; ++k) {
    (void)x.sample(hover(k / kRawRate_Hz, 1.0));
    (void)y.sample(hover(k / kRawRate_Hz, 1.0));
  }
  EXPECT_EQ(x.accelBias_B(), y.accelBias_B());
}

TEST(RotorVibration, InvalidParametersAreNamed) {
  ImuParams p;
  p.rotor_vibration.reference_rpm = 0.0;
  p.rotor_vibration.blade_count = 0;
  p.rotor_vibration.accel_std_m_per_s2 = -1.0;
  const auto errors = p.validate();
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_EQ(errors[0].field, "rotor_vibration_accel_std_m_per_s2");
  EXPECT_EQ(errors[1].field, "rotor_vibration_reference_rpm");
  EXPECT_EQ(errors[2].field, "rotor_vibration_blade_count");
}

}  // namespace
}  // namespace geaware::sim
