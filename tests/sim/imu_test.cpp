// SPDX-License-Identifier: BSD-3-Clause
// The simulated IMU: closed-form readings without noise (rest, tilt, free fall, lever arm),
// white-noise and bias-walk statistics against the configured densities, rate, validation.
#include "geaware/sim/imu.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "geaware/model/vehicle_model.hpp"
#include "geaware_test/eigen_matchers.hpp"

namespace geaware::sim {
namespace {

constexpr double kG = model::kGravity;

ImuParams noiseless() {
  ImuParams p;
  p.gyro_noise_density_rad_per_s_sqrtHz = 0.0;
  p.gyro_bias_walk_rad_per_s2_sqrtHz = 0.0;
  p.gyro_initial_bias_std_rad_per_s = 0.0;
  p.accel_noise_density_m_per_s2_sqrtHz = 0.0;
  p.accel_bias_walk_m_per_s3_sqrtHz = 0.0;
  p.accel_initial_bias_std_m_per_s2 = 0.0;
  return p;
}

PlantState at(double t_s) {
  PlantState s;
  s.t_s = t_s;
  return s;
}

TEST(Imu, NoiselessClosedForms) {
  Imu imu(noiseless(), 1);
  PlantState s = at(0.0);
  // At rest, level: specific force (0, 0, g), zero rate.
  auto m = imu.sample(s);
  ASSERT_TRUE(m);
  EXPECT_MATRIX_NEAR(m->accel_B, Eigen::Vector3d(0, 0, kG), 1e-12);
  EXPECT_MATRIX_NEAR(m->gyro_B, Eigen::Vector3d::Zero(), 0.0);
  // Rolled 30° at rest: gravity's reaction seen in the body frame, Rᵀ·g·z_W.
  s.t_s = 0.005;
  s.q_WB = Eigen::AngleAxisd(std::numbers::pi / 6, Eigen::Vector3d::UnitX());
  s.w_B = Eigen::Vector3d(0.1, -0.2, 0.3);
  m = imu.sample(s);
  ASSERT_TRUE(m);
  EXPECT_MATRIX_NEAR(m->accel_B, s.q_WB.toRotationMatrix().transpose() * Eigen::Vector3d(0, 0, kG), 1e-12);
  EXPECT_MATRIX_NEAR(m->gyro_B, s.w_B, 1e-15);
  // Free fall: no specific force.
  s.t_s = 0.010;
  s.a_W = Eigen::Vector3d(0, 0, -kG);
  m = imu.sample(s);
  ASSERT_TRUE(m);
  EXPECT_MATRIX_NEAR(m->accel_B, Eigen::Vector3d::Zero(), 1e-12);
}

TEST(Imu, LeverArmAddsCentripetalAndTangentialAcceleration) {
  ImuParams p = noiseless();
  p.lever_arm_B_m = Eigen::Vector3d(0.1, 0.0, 0.0);
  Imu imu(p, 1);
  PlantState s = at(0.0);
  s.w_B = Eigen::Vector3d(0, 0, 3.0);       // spinning about z: centripetal −ω²·r along x
  s.w_dot_B = Eigen::Vector3d(0, 0, 2.0);   // spinning up: tangential ω̇·r along y
  const auto m = imu.sample(s);
  ASSERT_TRUE(m);
  EXPECT_MATRIX_NEAR(m->accel_B, Eigen::Vector3d(-9.0 * 0.1, 2.0 * 0.1, kG), 1e-12);
}

TEST(Imu, SaturatesAtItsRange) {
  ImuParams p = noiseless();
  p.gyro_range_rad_per_s = 1.0;
  p.accel_range_m_per_s2 = 20.0;
  Imu imu(p, 1);
  PlantState s = at(0.0);
  s.w_B = Eigen::Vector3d(5, -5, 0.5);
  s.a_W = Eigen::Vector3d(0, 0, 30);
  const auto m = imu.sample(s);
  ASSERT_TRUE(m);
  EXPECT_MATRIX_NEAR(m->gyro_B, Eigen::Vector3d(1, -1, 0.5), 0.0);
  EXPECT_MATRIX_NEAR(m->accel_B, Eigen::Vector3d(0, 0, 20), 0.0);
}

TEST(Imu, AtRestReadsGravityAndZeroRatePlusBias) {
  // Defaults (turn-on bias, white noise), bias walk off so the bias stays put: the mean of
  // 20,000 samples is the truth plus the bias within 5 standard errors of the mean.
  ImuParams p;
  p.gyro_bias_walk_rad_per_s2_sqrtHz = 0.0;
  p.accel_bias_walk_m_per_s3_sqrtHz = 0.0;
  Imu imu(p, 11);
  constexpr int kN = 20'000;
  Eigen::Vector3d g_sum = Eigen::Vector3d::Zero(), a_sum = Eigen::Vector3d::Zero();
  for (int k = 0; k < kN; ++k) {
    const auto m = imu.sample(at(k / p.rate_Hz));
    ASSERT_TRUE(m);
    g_sum += m->gyro_B;
    a_sum += m->accel_B;
  }
  EXPECT_GT(imu.gyroBias_B().norm(), 0.0);
  const double g_se = p.gyro_noise_density_rad_per_s_sqrtHz * std::sqrt(p.rate_Hz / kN);
  const double a_se = p.accel_noise_density_m_per_s2_sqrtHz * std::sqrt(p.rate_Hz / kN);
  EXPECT_MATRIX_NEAR(g_sum / double(kN), imu.gyroBias_B(), 5 * g_se);
  EXPECT_MATRIX_NEAR(a_sum / double(kN), Eigen::Vector3d(0, 0, kG) + imu.accelBias_B(), 5 * a_se);
}

TEST(Imu, WhiteNoiseStdIsDensityTimesRootRate) {
  // σ_d = N·√rate. 100,000 samples per axis: std error of a std ≈ 0.22 %; allow 2 %.
  ImuParams p = noiseless();
  p.gyro_noise_density_rad_per_s_sqrtHz = 3e-4;
  p.accel_noise_density_m_per_s2_sqrtHz = 4e-3;
  Imu imu(p, 5);
  constexpr int kN = 100'000;
  Eigen::Array3d g2 = Eigen::Array3d::Zero(), a2 = Eigen::Array3d::Zero();
  for (int k = 0; k < kN; ++k) {
    const auto m = imu.sample(at(k / p.rate_Hz));
    ASSERT_TRUE(m);
    g2 += m->gyro_B.array().square();
    a2 += (m->accel_B - Eigen::Vector3d(0, 0, kG)).array().square();
  }
  const Eigen::Array3d g_std = (g2 / double(kN)).sqrt();
  const Eigen::Array3d a_std = (a2 / double(kN)).sqrt();
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(g_std[i] / (3e-4 * std::sqrt(200.0)), 1.0, 0.02) << "axis " << i;
    EXPECT_NEAR(a_std[i] / (4e-3 * std::sqrt(200.0)), 1.0, 0.02) << "axis " << i;
  }
}

TEST(Imu, BiasWalkVarianceGrowsLinearlyInTime) {
  // Var[b(t) − b(0)] = N_b²·t. An ensemble of 1,000 seeds × 3 axes: std error of a variance
  // ≈ 2.6 %; allow 10 % at 1, 2 and 4 s.
  ImuParams p = noiseless();
  p.gyro_bias_walk_rad_per_s2_sqrtHz = 4e-5;
  p.accel_bias_walk_m_per_s3_sqrtHz = 6e-3;
  const double times[] = {1.0, 2.0, 4.0};
  double g_var[3] = {}, a_var[3] = {};
  constexpr int kSeeds = 1000;
  for (int seed = 0; seed < kSeeds; ++seed) {
    Imu imu(p, static_cast<std::uint64_t>(seed));
    int next = 0;
    for (int k = 0; k <= 800; ++k) {
      ASSERT_TRUE(imu.sample(at(k * 0.005)));
      if (next < 3 && k == static_cast<int>(times[next] * 200.0)) {
        g_var[next] += imu.gyroBias_B().squaredNorm();
        a_var[next] += imu.accelBias_B().squaredNorm();
        ++next;
      }
    }
  }
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(g_var[i] / (3 * kSeeds) / (4e-5 * 4e-5 * times[i]), 1.0, 0.1) << "t = " << times[i];
    EXPECT_NEAR(a_var[i] / (3 * kSeeds) / (6e-3 * 6e-3 * times[i]), 1.0, 0.1) << "t = " << times[i];
  }
}

TEST(Imu, SamplesAtItsRateInsideTheSimulationLoop) {
  Imu imu(ImuParams{}, 3);
  int n = 0;
  for (int k = 0; k < 1000; ++k) {
    const auto m = imu.sample(at(k * 1e-3));
    if (m) {
      EXPECT_EQ(k % 5, 0);
      EXPECT_DOUBLE_EQ(m->t_s, k * 1e-3);
      ++n;
    }
  }
  EXPECT_EQ(n, 200);
}

TEST(Imu, RefusesNonFiniteStatesAndInvalidParameters) {
  Imu imu(ImuParams{}, 3);
  PlantState s = at(0.0);
  s.a_W.x() = std::nan("");
  EXPECT_FALSE(imu.sample(s));
  EXPECT_EQ(imu.rejected(), 1);

  ImuParams bad;
  bad.rate_Hz = 0.0;
  bad.accel_noise_density_m_per_s2_sqrtHz = -1.0;
  const auto errors = bad.validate();
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0].field, "rate_Hz");
  EXPECT_EQ(errors[1].field, "accel_noise_density_m_per_s2_sqrtHz");
  EXPECT_THROW(Imu(bad, 1), model::InvalidParameters);
}

}  // namespace
}  // namespace geaware::sim
