// SPDX-License-Identifier: BSD-3-Clause
// The as-built world's sensor and disturbance effects (docs/world.md) against closed forms: the
// flight controller's low-pass (attenuation, delay, white-noise gain), IMU vibration after the
// filter, the motion-capture stamp with an unknown latency and its jitter, and the
// unsteadiness at altitude. Each is off by default and draws from its own stream.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "geaware/model/units.hpp"
#include "geaware/sim/disturbances.hpp"
#include "geaware/sim/imu.hpp"
#include "geaware/sim/mocap.hpp"
#include "geaware_test/eigen_matchers.hpp"

namespace geaware::sim {
namespace {

constexpr double kFs = 1000.0;
constexpr double kFc = 20.0;

PlantState at(double t_s) {
  PlantState s;
  s.t_s = t_s;
  return s;
}

// --- The flight controller's low-pass --------------------------------------------------------------

TEST(LowPass2, HalfPowerAtTheCutoffAndUnitGainAtDc) {
  LowPass2 lp(kFs, kFc);
  lp.reset(Eigen::Vector3d(2.0, -1.0, 0.5));
  for (int k = 0; k < 100; ++k) lp.apply(Eigen::Vector3d(2.0, -1.0, 0.5));
  EXPECT_MATRIX_NEAR(lp.value(), Eigen::Vector3d(2.0, -1.0, 0.5), 1e-12);
  // A sine at the cutoff: amplitude 1/√2 once settled (pre-warping puts −3 dB exactly there);
  // at 5·f_c a second-order filter gives ≈ 1/25.
  const auto amplitude = [](double f_Hz) {
    LowPass2 f(kFs, kFc);
    f.reset(Eigen::Vector3d::Zero());
    double peak = 0.0;
    for (int k = 0; k < 4000; ++k) {
      const double y = f.apply(Eigen::Vector3d::Constant(std::sin(2.0 * std::numbers::pi * f_Hz * k / kFs))).x();
      if (k >= 2000) peak = std::max(peak, std::abs(y));
    }
    return peak;
  };
  EXPECT_NEAR(amplitude(kFc), 1.0 / std::sqrt(2.0), 3e-3);
  EXPECT_NEAR(amplitude(5.0 * kFc), 1.0 / 25.0, 0.006);
}

TEST(LowPass2, ARampLagsByTheGroupDelay) {
  // Continuous second-order Butterworth: τ = √2/(2π·f_c) = 11.25 ms at 20 Hz; the bilinear
  // version is within a few per cent of it, and a ramp lags by exactly its DC group delay.
  LowPass2 lp(kFs, kFc);
  EXPECT_NEAR(lp.groupDelay_s(), std::sqrt(2.0) / (2.0 * std::numbers::pi * kFc), 0.3e-3);
  lp.reset(Eigen::Vector3d::Zero());
  double y = 0.0;
  for (int k = 0; k <= 2000; ++k) y = lp.apply(Eigen::Vector3d::Constant(k / kFs)).x();
  EXPECT_NEAR(2000 / kFs - y, lp.groupDelay_s(), 1e-9);
}

TEST(LowPass2, WhiteNoiseGainIsTheEquivalentNoiseBandwidth) {
  // Σh² ≈ B_n/(f_s/2) with B_n = f_c·(π/4)/sin(π/4) for a second-order Butterworth.
  const LowPass2 lp(kFs, kFc);
  const double enbw = kFc * (std::numbers::pi / 4.0) / std::sin(std::numbers::pi / 4.0);
  EXPECT_NEAR(lp.noiseGain(), enbw / (kFs / 2.0), 0.03 * enbw / (kFs / 2.0));
}

// --- IMU vibration through the filter -------------------------------------------------------------

ImuParams quiet() {
  ImuParams p;
  p.gyro_noise_density_rad_per_s_sqrtHz = 0.0;
  p.gyro_bias_walk_rad_per_s2_sqrtHz = 0.0;
  p.gyro_initial_bias_std_rad_per_s = 0.0;
  p.accel_noise_density_m_per_s2_sqrtHz = 0.0;
  p.accel_bias_walk_m_per_s3_sqrtHz = 0.0;
  p.accel_initial_bias_std_m_per_s2 = 0.0;
  return p;
}

TEST(ImuVibration, TheOutputCarriesTheConfiguredStdAfterTheFilter) {
  for (double cutoff : {0.0, kFc}) {
    ImuParams p = quiet();
    p.vibration_gyro_std_rad_per_s = 3.0 * model::kDegToRad;
    p.vibration_accel_std_m_per_s2 = 0.4;
    p.lowpass_cutoff_Hz = cutoff;
    Imu imu(p, 11);
    double sg = 0.0;
    double sa = 0.0;
    int n = 0;
    for (int k = 0; k < 300'000; ++k) {  // 300 s at 1 kHz, 60,000 samples at 200 Hz
      const auto m = imu.sample(at(k / kFs));
      if (!m) continue;
      sg += m->gyro_B.squaredNorm();
      sa += (m->accel_B - Eigen::Vector3d(0.0, 0.0, model::kGravity)).squaredNorm();
      n += 3;
    }
    EXPECT_NEAR(std::sqrt(sg / n), p.vibration_gyro_std_rad_per_s,
                0.03 * p.vibration_gyro_std_rad_per_s) << "cutoff " << cutoff;
    EXPECT_NEAR(std::sqrt(sa / n), 0.4, 0.03 * 0.4) << "cutoff " << cutoff;
  }
}

TEST(ImuVibration, TheFilterDelaysTheRateAndLeavesTheOtherStreamsAlone) {
  // A rate ramp ω_x = α·t reads α·(t − τ) once the filter has settled.
  ImuParams p = quiet();
  p.lowpass_cutoff_Hz = kFc;
  Imu imu(p, 3);
  const double alpha = 2.0;  // [rad/s²]
  double last = 0.0;
  double t_last = 0.0;
  for (int k = 0; k <= 1000; ++k) {
    PlantState s = at(k / kFs);
    s.w_B = Eigen::Vector3d(alpha * s.t_s, 0.0, 0.0);
    if (const auto m = imu.sample(s)) {
      last = m->gyro_B.x();
      t_last = m->t_s;
    }
  }
  ASSERT_NE(imu.gyroFilter(), nullptr);
  EXPECT_NEAR(last, alpha * (t_last - imu.gyroFilter()->groupDelay_s()), 1e-9);
  // The sensor's own noise (bias, white) is the same stream with vibration on or off.
  ImuParams noisy;
  ImuParams shaking = noisy;
  shaking.vibration_gyro_std_rad_per_s = 0.05;
  Imu a(noisy, 5);
  Imu b(shaking, 5);
  for (int k = 0; k < 50; ++k) {
    (void)a.sample(at(k / kFs));
    (void)b.sample(at(k / kFs));
  }
  EXPECT_EQ(a.gyroBias_B(), b.gyroBias_B());
  EXPECT_EQ(a.accelBias_B(), b.accelBias_B());
  // Validation: a cutoff above the filter's Nyquist band is refused.
  p.lowpass_cutoff_Hz = 480.0;
  EXPECT_FALSE(p.validate().empty());
}

// --- Motion capture: the stamped latency and jitter ------------------------------------------------

MocapParams clean() {
  MocapParams p;
  p.position_noise_std_m = 0.0;
  p.attitude_noise_std_rad = 0.0;
  p.dropout_probability = 0.0;
  return p;
}

PlantState moving(double t_s) {  // the position encodes the capture time
  PlantState s = at(t_s);
  s.p_W = Eigen::Vector3d(t_s, 0.0, 1.0);
  return s;
}

TEST(MocapStamp, AWrongReportedLatencyShiftsTheStampByTheDifference) {
  MocapParams p = clean();
  p.latency_s = 0.012;
  p.reported_latency_s = 0.007;
  Mocap mocap(p, 1);
  int n = 0;
  for (int k = 0; k < 1000; ++k) {
    const auto m = mocap.step(moving(k / kFs));
    if (!m) continue;
    ++n;
    EXPECT_NEAR(m->t_s - m->p_W.x(), 0.005, 1e-9);  // stamped 5 ms after the true capture
  }
  EXPECT_GT(n, 90);
  p.reported_latency_s = 2.0;
  EXPECT_FALSE(p.validate().empty());
}

TEST(MocapStamp, JitterSpreadsTheLatencyAndKeepsThePoseNoise) {
  MocapParams p;
  p.dropout_probability = 0.0;
  p.latency_s = 0.012;
  p.latency_jitter_std_s = 0.002;
  MocapParams steady = p;
  steady.latency_jitter_std_s = 0.0;
  Mocap jittery(p, 9);
  Mocap still(steady, 9);
  std::vector<double> delay;
  std::vector<Eigen::Vector3d> pose_a;
  std::vector<Eigen::Vector3d> pose_b;
  double last_capture = -1.0;
  for (int k = 0; k < 200'000; ++k) {
    const PlantState s = at(k / kFs);
    if (const auto m = jittery.step(s)) {
      EXPECT_GT(m->t_s, last_capture);  // in capture order
      last_capture = m->t_s;
      delay.push_back(s.t_s - m->t_s);
      pose_a.push_back(m->p_W);
    }
    if (const auto m = still.step(s)) pose_b.push_back(m->p_W);
  }
  double mean = 0.0;
  for (double d : delay) mean += d / static_cast<double>(delay.size());
  double var = 0.0;
  for (double d : delay) var += (d - mean) * (d - mean) / static_cast<double>(delay.size());
  // Delivery at the first 1 ms step after the drawn latency: mean ≈ 12.5 ms, σ ≈ √(2² + 1/12) ms.
  EXPECT_NEAR(mean, 0.0125, 0.0004);
  EXPECT_NEAR(std::sqrt(var), std::sqrt(0.002 * 0.002 + 1e-6 / 12.0), 0.0003);
  const std::size_t common = std::min(pose_a.size(), pose_b.size());
  ASSERT_GT(common, 19'000u);
  for (std::size_t i = 0; i < common; ++i) ASSERT_EQ(pose_a[i], pose_b[i]) << i;
}

// --- Unsteadiness at altitude ------------------------------------------------------------------

TEST(Unsteadiness, ItsStatisticsAreTheConfiguredOnesAtAnyHeight) {
  UnsteadinessParams p;
  p.torque_std_Nm = 0.008;
  p.force_std_N = 0.15;
  p.correlation_time_s = 0.02;
  Unsteadiness u(p, 21);
  ContributionContext ctx;
  ctx.surroundings.ground_distance_m = {50.0, 50.0, 50.0, 50.0};
  Eigen::Vector3d sum_t2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum_f2 = Eigen::Vector3d::Zero();
  double lag1 = 0.0;
  double prev = 0.0;
  constexpr int kSteps = 400'000;  // 400 s at 1 kHz: 20,000 correlation times
  for (int k = 0; k < kSteps; ++k) {
    u.beginStep(k / kFs, 1.0 / kFs, PlantState{});
    const Wrench w = u.wrench(ctx);
    sum_t2 += w.torque_B.cwiseAbs2();
    sum_f2 += w.force_B.cwiseAbs2();
    lag1 += w.torque_B.x() * prev;
    prev = w.torque_B.x();
  }
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(std::sqrt(sum_t2[a] / kSteps), 0.008, 0.05 * 0.008);
    EXPECT_NEAR(std::sqrt(sum_f2[a] / kSteps), 0.15, 0.05 * 0.15);
  }
  // One-step correlation e^(−dt/τ_c).
  EXPECT_NEAR(lag1 / sum_t2.x(), std::exp(-1e-3 / 0.02), 0.01);
  EXPECT_FALSE(u.readsSurroundings());
  p.correlation_time_s = 0.0;
  EXPECT_FALSE(p.validate().empty());
}

TEST(Unsteadiness, ItsStreamIsItsOwn) {
  EXPECT_NE(salt::kUnsteadiness, salt::kGroundTurbulence);
  EXPECT_NE(salt::kImuVibration, salt::kImu);
  EXPECT_NE(salt::kMocapJitter, salt::kMocap);
  // Default: no buffeting.
  Unsteadiness u(UnsteadinessParams{}, 1);
  u.beginStep(0.0, 1e-3, PlantState{});
  const Wrench w = u.wrench(ContributionContext{});
  EXPECT_EQ(w.force_B, Eigen::Vector3d::Zero());
  EXPECT_EQ(w.torque_B, Eigen::Vector3d::Zero());
}

}  // namespace
}  // namespace geaware::sim
