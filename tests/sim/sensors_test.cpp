// SPDX-License-Identifier: BSD-3-Clause
// The sensor suite: every sensor at its own rate in one loop, determinism (same seed →
// bit-identical samples, another seed → other noise), independence of the noise streams, and
// validation with prefixed key paths.
#include "geaware/sim/sensors.hpp"

#include <cmath>
#include <cstring>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "geaware/model/vehicle_model.hpp"
#include "geaware/sim/terrains.hpp"

namespace geaware::sim {
namespace {

/// A vehicle swinging over the ground: every field changes, so every sensor has work to do.
PlantState moving(int k) {
  const double t = k * 1e-3;
  PlantState s;
  s.t_s = t;
  s.p_W = Eigen::Vector3d(std::sin(t), 0.5 * std::cos(t), 0.3 + 0.1 * std::sin(2 * t));
  s.v_W = Eigen::Vector3d(std::cos(t), -0.5 * std::sin(t), 0.2 * std::cos(2 * t));
  s.q_WB = Eigen::AngleAxisd(0.2 * std::sin(3 * t), Eigen::Vector3d::UnitX()) *
           Eigen::AngleAxisd(0.1 * std::cos(t), Eigen::Vector3d::UnitY());
  s.w_B = Eigen::Vector3d(0.6 * std::cos(3 * t), -0.1 * std::sin(t), 0.0);
  s.a_W = Eigen::Vector3d(-std::sin(t), -0.5 * std::cos(t), -0.4 * std::sin(2 * t));
  s.n_rpm = {10'000 + 100 * std::sin(t), 10'100.0, 9'900.0, 10'000 - 100 * std::sin(t)};
  return s;
}

/// Every sample of a run, flattened to doubles (bools as 0/1) in a fixed order.
std::vector<double> record(const SensorSuiteParams& params, std::uint64_t seed, int steps) {
  const FlatGround ground(0.0);
  SensorSuite suite(params, seed);
  std::vector<double> out;
  for (int k = 0; k < steps; ++k) {
    const SensorReadings r = suite.step(moving(k), &ground);
    if (r.imu) {
      out.push_back(r.imu->t_s);
      for (double v : r.imu->gyro_B) out.push_back(v);
      for (double v : r.imu->accel_B) out.push_back(v);
    }
    if (r.mocap) {
      out.push_back(r.mocap->t_s);
      for (double v : r.mocap->p_W) out.push_back(v);
      for (double v : r.mocap->q_WB.coeffs()) out.push_back(v);
    }
    if (r.rotors) {
      out.push_back(r.rotors->t_s);
      for (double v : r.rotors->n_rpm) out.push_back(v);
    }
    if (r.ranger) {
      out.push_back(r.ranger->t_s);
      for (int z = 0; z < r.ranger->side * r.ranger->side; ++z) {
        out.push_back(r.ranger->range_m[z]);
        out.push_back(r.ranger->valid[z] ? 1.0 : 0.0);
      }
    }
  }
  return out;
}

TEST(SensorSuite, EverySensorAtItsOwnRate) {
  const FlatGround ground(0.0);
  SensorSuiteParams p;
  p.mocap.dropout_probability = 0.0;
  SensorSuite suite(p, 1);
  int imu = 0, mocap = 0, rotors = 0, ranger = 0;
  for (int k = 0; k < 1000; ++k) {
    const SensorReadings r = suite.step(moving(k), &ground);
    imu += r.imu.has_value();
    mocap += r.mocap.has_value();
    rotors += r.rotors.has_value();
    ranger += r.ranger.has_value();
  }
  EXPECT_EQ(imu, 200);
  EXPECT_EQ(rotors, 200);
  EXPECT_EQ(ranger, 100);
  EXPECT_EQ(mocap, 99);  // 100 captures, the last one still in flight (10 ms latency)
}

TEST(SensorSuite, SameSeedBitIdenticalOtherSeedDifferent) {
  const SensorSuiteParams p;
  const std::vector<double> a = record(p, 2024, 2000);
  const std::vector<double> b = record(p, 2024, 2000);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 50'000u);
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
  const std::vector<double> c = record(p, 2025, 2000);
  std::size_t same = 0;
  const std::size_t n = std::min(a.size(), c.size());
  for (std::size_t i = 0; i < n; ++i) same += a[i] == c[i];
  // Times, validity flags and quantised or zero values may coincide; noisy values must not.
  EXPECT_LT(static_cast<double>(same), 0.7 * static_cast<double>(n));
}

TEST(SensorSuite, ReconfiguringOneSensorLeavesTheOthersNoiseAlone) {
  SensorSuiteParams a;
  SensorSuiteParams b = a;
  b.ranger.outlier_probability = 0.2;
  b.ranger.side = 8;
  b.mocap.dropout_probability = 0.5;
  const FlatGround ground(0.0);
  SensorSuite sa(a, 77), sb(b, 77);
  for (int k = 0; k < 500; ++k) {
    const SensorReadings ra = sa.step(moving(k), &ground);
    const SensorReadings rb = sb.step(moving(k), &ground);
    ASSERT_EQ(ra.imu.has_value(), rb.imu.has_value());
    if (ra.imu) {
      EXPECT_EQ(ra.imu->gyro_B, rb.imu->gyro_B);
      EXPECT_EQ(ra.imu->accel_B, rb.imu->accel_B);
    }
    ASSERT_EQ(ra.rotors.has_value(), rb.rotors.has_value());
    if (ra.rotors) {
      EXPECT_EQ(ra.rotors->n_rpm, rb.rotors->n_rpm);
    }
  }
}

TEST(SensorSuite, ValidationPrefixesTheSensor) {
  SensorSuiteParams p;
  p.imu.rate_Hz = -1.0;
  p.ranger.side = 0;
  const auto e = p.validate();
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].field, "imu.rate_Hz");
  EXPECT_EQ(e[1].field, "ranger.side");
  try {
    SensorSuite suite(p, 1);
    FAIL() << "accepted invalid parameters";
  } catch (const model::InvalidParameters& ex) {
    EXPECT_EQ(ex.errors().size(), 2u);
  }
}

}  // namespace
}  // namespace geaware::sim
