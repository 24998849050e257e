// SPDX-License-Identifier: BSD-3-Clause
// Simulated motion capture: exact latency, dropout rates (isolated and bursts), pose noise
// statistics, the bounded delay ring, validation.
#include "geaware/sim/mocap.hpp"

#include <cmath>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "geaware/model/vehicle_model.hpp"

namespace geaware::sim {
namespace {

MocapParams clean() {
  MocapParams p;
  p.position_noise_std_m = 0.0;
  p.attitude_noise_std_rad = 0.0;
  p.dropout_probability = 0.0;
  p.burst_probability = 0.0;
  return p;
}

/// A state whose position encodes its time, so a delivered pose says when it was captured.
PlantState at(double t_s) {
  PlantState s;
  s.t_s = t_s;
  s.p_W = Eigen::Vector3d(t_s, 1.0, 2.0);
  return s;
}

TEST(Mocap, DeliversEveryPoseExactlyLatencyAfterCapture) {
  MocapParams p = clean();
  p.rate_Hz = 100.0;
  p.latency_s = 0.015;
  Mocap mocap(p, 1);
  int delivered = 0;
  for (int k = 0; k < 2000; ++k) {  // 2 s at 1 kHz
    const double t = k * 1e-3;
    const auto m = mocap.step(at(t));
    if (!m) continue;
    ++delivered;
    EXPECT_NEAR(t - m->t_s, p.latency_s, 1e-12) << "delivered at " << t;
    EXPECT_DOUBLE_EQ(m->p_W.x(), m->t_s);  // it is the pose of its capture time
    EXPECT_NEAR(std::remainder(m->t_s, 0.01), 0.0, 1e-12);
  }
  // Captures at 0, 10, …, 1990 ms; those after 1984 ms are still in flight.
  EXPECT_EQ(delivered, 199);
  EXPECT_EQ(mocap.pending(), 1);
}

TEST(Mocap, ZeroLatencyDeliversInTheSameStep) {
  MocapParams p = clean();
  p.latency_s = 0.0;
  Mocap mocap(p, 1);
  const auto m = mocap.step(at(0.0));
  ASSERT_TRUE(m);
  EXPECT_EQ(m->t_s, 0.0);
}

TEST(Mocap, IsolatedDropoutsOccurAtTheConfiguredRate) {
  // 100,000 captures at p = 0.1: std error of the fraction ≈ 0.001; allow 0.005.
  MocapParams p = clean();
  p.latency_s = 0.0;
  p.dropout_probability = 0.1;
  Mocap mocap(p, 17);
  long delivered = 0;
  for (int k = 0; k < 100'000; ++k) delivered += mocap.step(at(k / p.rate_Hz)).has_value();
  EXPECT_EQ(mocap.captured(), 100'000);
  EXPECT_EQ(delivered + mocap.dropped(), 100'000);
  EXPECT_NEAR(static_cast<double>(mocap.dropped()) / 100'000.0, 0.1, 0.005);
}

TEST(Mocap, BurstsLoseRunsOfTheConfiguredLength) {
  // Bursts only: every run of losses is a whole number of bursts, and the lost fraction is
  // L / (L + (1 − p)/p) = 10 / 109 (≈ 1,800 bursts: std error ≈ 0.002; allow 0.008).
  MocapParams p = clean();
  p.latency_s = 0.0;
  p.burst_probability = 0.01;
  p.burst_length_samples = 10;
  Mocap mocap(p, 23);
  std::vector<int> runs;
  int run = 0;
  constexpr int kN = 200'000;
  for (int k = 0; k < kN; ++k) {
    if (mocap.step(at(k / p.rate_Hz))) {
      if (run > 0) runs.push_back(run);
      run = 0;
    } else {
      ++run;
    }
  }
  ASSERT_GT(runs.size(), 1000u);
  for (int r : runs) EXPECT_EQ(r % 10, 0) << r;
  EXPECT_NEAR(static_cast<double>(mocap.dropped()) / kN, 10.0 / 109.0, 0.008);
}

TEST(Mocap, PoseNoiseHasTheConfiguredStatistics) {
  // 50,000 poses: std error of a std ≈ 0.3 %; allow 3 %. The attitude error is the body-frame
  // rotation vector of q_true⁻¹·q_measured.
  MocapParams p = clean();
  p.latency_s = 0.0;
  p.position_noise_std_m = 1e-3;
  p.attitude_noise_std_rad = 0.01;
  Mocap mocap(p, 29);
  const Eigen::Quaterniond q_true(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  Eigen::Array3d p2 = Eigen::Array3d::Zero(), a2 = Eigen::Array3d::Zero();
  constexpr int kN = 50'000;
  for (int k = 0; k < kN; ++k) {
    PlantState s = at(k / p.rate_Hz);
    s.q_WB = q_true;
    const auto m = mocap.step(s);
    ASSERT_TRUE(m);
    p2 += (m->p_W - s.p_W).array().square();
    const Eigen::AngleAxisd e(q_true.conjugate() * m->q_WB);
    a2 += (e.angle() * e.axis()).array().square();
    EXPECT_NEAR(m->q_WB.norm(), 1.0, 1e-12);
  }
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(std::sqrt(p2[i] / kN) / 1e-3, 1.0, 0.03) << "axis " << i;
    EXPECT_NEAR(std::sqrt(a2[i] / kN) / 0.01, 1.0, 0.03) << "axis " << i;
  }
}

TEST(Mocap, DropoutsDoNotChangeTheNoiseOfThePosesThatArrive) {
  MocapParams a = clean();
  a.latency_s = 0.0;
  a.position_noise_std_m = 1e-3;
  MocapParams b = a;
  b.dropout_probability = 0.3;
  Mocap ma(a, 5), mb(b, 5);
  int compared = 0;
  for (int k = 0; k < 1000; ++k) {
    const auto ra = ma.step(at(k / a.rate_Hz));
    const auto rb = mb.step(at(k / a.rate_Hz));
    ASSERT_TRUE(ra);
    if (rb) {
      EXPECT_EQ(ra->p_W, rb->p_W);
      ++compared;
    }
  }
  EXPECT_GT(compared, 600);
}

TEST(Mocap, EveryPoseInFlightFitsTheRing) {
  // Validation keeps latency·rate + 2 within the ring, so nothing in flight is ever lost.
  MocapParams p = clean();
  p.rate_Hz = 100.0;
  p.latency_s = 0.6;  // 60 in flight, fits
  Mocap mocap(p, 1);
  for (int k = 0; k < 60; ++k) EXPECT_FALSE(mocap.step(at(k * 0.01)));
  EXPECT_EQ(mocap.pending(), 60);
  EXPECT_EQ(mocap.overflowed(), 0);
  p.latency_s = 1.0;  // 100 in flight: refused
  EXPECT_THROW(Mocap(p, 1), model::InvalidParameters);
}

TEST(Mocap, ValidationNamesTheFields) {
  MocapParams p;
  p.dropout_probability = 1.5;
  p.burst_length_samples = 0;
  const auto e = p.validate();
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].field, "dropout_probability");
  EXPECT_EQ(e[1].field, "burst_length_samples");
}

TEST(Mocap, NonFiniteStateCapturesNothing) {
  Mocap mocap(clean(), 1);
  PlantState s = at(0.0);
  s.q_WB.w() = std::nan("");
  EXPECT_FALSE(mocap.step(s));
  EXPECT_EQ(mocap.rejected(), 1);
  EXPECT_EQ(mocap.captured(), 0);
}

}  // namespace
}  // namespace geaware::sim
