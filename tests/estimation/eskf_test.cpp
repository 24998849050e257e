// SPDX-License-Identifier: BSD-3-Clause
// Error-state Kalman filter with delayed motion capture. No simulator here: the truth is a
// smooth analytic motion (sinusoidal position and ZYX Euler angles) whose specific force and
// body rates are exact, sampled by a seeded IMU (white noise + constant biases) and a seeded
// motion-capture system (noise + latency).
#include "geaware/estimation/eskf.hpp"
#include "geaware/model/rotation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <limits>
#include <numbers>
#include <random>

#include "geaware_test/eigen_matchers.hpp"

namespace {

using namespace geaware::estimation;
using Eigen::Quaterniond;
using geaware::model::expMap;
using geaware::model::logMap;
using Eigen::Vector3d;
using geaware::model::ImuSample;
using geaware::model::MocapSample;

constexpr double kG = geaware::model::kGravity;
constexpr double kDeg = std::numbers::pi / 180.0;

/// The truth at one instant.
struct Truth {
  Vector3d p, v, a;
  Quaterniond q;
  Vector3d w_B;
};

/// p(t) = (0.8 sin 1.5t, 0.6 sin(2t + 0.3), 1 + 0.2 sin 1.2t): up to 1.5 m/s;
/// roll 0.3 sin 2t, pitch 0.25 sin(1.7t + 0.5), yaw 0.4 + 0.5 sin 0.8t: up to ~0.7 rad/s.
Truth truthAt(double t) {
  Truth s;
  s.p = {0.8 * std::sin(1.5 * t), 0.6 * std::sin(2.0 * t + 0.3), 1.0 + 0.2 * std::sin(1.2 * t)};
  s.v = {1.2 * std::cos(1.5 * t), 1.2 * std::cos(2.0 * t + 0.3), 0.24 * std::cos(1.2 * t)};
  s.a = {-1.8 * std::sin(1.5 * t), -2.4 * std::sin(2.0 * t + 0.3), -0.288 * std::sin(1.2 * t)};
  const double ph = 0.3 * std::sin(2.0 * t), dph = 0.6 * std::cos(2.0 * t);
  const double th = 0.25 * std::sin(1.7 * t + 0.5), dth = 0.425 * std::cos(1.7 * t + 0.5);
  const double ps = 0.4 + 0.5 * std::sin(0.8 * t), dps = 0.4 * std::cos(0.8 * t);
  s.q = Eigen::AngleAxisd(ps, Vector3d::UnitZ()) * Eigen::AngleAxisd(th, Vector3d::UnitY()) *
        Eigen::AngleAxisd(ph, Vector3d::UnitX());
  // Body rates of ZYX Euler angles.
  s.w_B = {dph - dps * std::sin(th), dth * std::cos(ph) + dps * std::sin(ph) * std::cos(th),
           -dth * std::sin(ph) + dps * std::cos(ph) * std::cos(th)};
  return s;
}

double angleBetween(const Quaterniond& a, const Quaterniond& b) {
  return logMap(a.conjugate() * b).norm();
}

struct SensorConfig {
  double imu_rate_hz = 200.0;
  double accel_noise_std = 0.02 * std::sqrt(200.0);   // per sample: density·√rate [m/s²]
  double gyro_noise_std = 1.0e-3 * std::sqrt(200.0);  // [rad/s]
  Vector3d accel_bias{0.15, -0.10, 0.20};             // [m/s²]
  Vector3d gyro_bias{0.02, -0.015, 0.01};             // [rad/s]
  double mocap_period_s = 0.01;
  double mocap_phase_s = 0.0023;  // capture times fall between IMU samples
  double mocap_latency_s = 0.02;
  double mocap_pos_std = 1.0e-3;
  double mocap_att_std = 3.0e-3;
  std::uint64_t seed = 42;
};

/// Error statistics over a window.
struct RunStats {
  double rms_pos = 0.0, max_pos = 0.0, rms_att = 0.0, max_att = 0.0;
  double along_track_mean = 0.0;  // mean of (p̂ − p)·v/|v|: negative = lagging [m]
  Vector3d accel_bias_err = Vector3d::Zero(), gyro_bias_err = Vector3d::Zero();
  bool finite = true;
};

/// Runs the filter over [0, duration] and accumulates errors for t ≥ t_eval.
/// `tamper(mocap)` may alter each pose before delivery.
template <typename Tamper>
RunStats run(Eskf& f, const SensorConfig& c, double duration, double t_eval, Tamper tamper) {
  std::mt19937_64 rng(c.seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  const auto noise = [&](double s) { return Vector3d(s * n01(rng), s * n01(rng), s * n01(rng)); };
  std::deque<MocapSample> in_flight;
  double next_capture = c.mocap_phase_s;
  RunStats st;
  int count = 0;
  const int steps = static_cast<int>(std::round(duration * c.imu_rate_hz));
  for (int k = 0; k <= steps; ++k) {
    const double t = k / c.imu_rate_hz;
    const Truth x = truthAt(t);
    ImuSample imu;
    imu.t_s = t;
    imu.gyro_B = x.w_B + c.gyro_bias + noise(c.gyro_noise_std);
    imu.accel_B =
        x.q.conjugate() * (x.a + kG * Vector3d::UnitZ()) + c.accel_bias + noise(c.accel_noise_std);
    (void)f.addImu(imu);
    // Captures up to now enter the pipe; those older than the latency come out.
    while (next_capture <= t) {
      const Truth xc = truthAt(next_capture);
      MocapSample m;
      m.t_s = next_capture;
      m.p_W = xc.p + noise(c.mocap_pos_std);
      m.q_WB = xc.q * expMap(noise(c.mocap_att_std));
      in_flight.push_back(m);
      next_capture += c.mocap_period_s;
    }
    while (!in_flight.empty() && in_flight.front().t_s + c.mocap_latency_s <= t + 1e-12) {
      MocapSample m = in_flight.front();
      in_flight.pop_front();
      if (tamper(m)) (void)f.addMocap(m);
    }
    const EskfOutput o = f.output();
    st.finite = st.finite && o.estimate.p_W.allFinite() && o.estimate.v_W.allFinite() &&
                o.estimate.q_WB.coeffs().allFinite() && o.covariance_diagonal.allFinite();
    if (t >= t_eval) {
      const Vector3d e = o.estimate.p_W - x.p;
      const double ea = angleBetween(o.estimate.q_WB, x.q);
      st.rms_pos += e.squaredNorm();
      st.rms_att += ea * ea;
      st.max_pos = std::max(st.max_pos, e.norm());
      st.max_att = std::max(st.max_att, ea);
      st.along_track_mean += e.dot(x.v.normalized());
      ++count;
    }
  }
  st.rms_pos = std::sqrt(st.rms_pos / count);
  st.rms_att = std::sqrt(st.rms_att / count);
  st.along_track_mean /= count;
  st.accel_bias_err = f.state().accel_bias_B - c.accel_bias;
  st.gyro_bias_err = f.state().gyro_bias_B - c.gyro_bias;
  return st;
}

RunStats run(Eskf& f, const SensorConfig& c, double duration, double t_eval) {
  return run(f, c, duration, t_eval, [](MocapSample&) { return true; });
}

EskfState truthState(double t) {
  const Truth x = truthAt(t);
  EskfState s;
  s.p_W = x.p;
  s.v_W = x.v;
  s.q_WB = x.q;
  return s;
}

/// The truth's kinematics are self-consistent: finite differences of p, v and q match v, a, ω.
TEST(EskfTruth, AnalyticMotionIsConsistent) {
  const double h = 1e-6;
  for (double t : {0.0, 0.7, 2.3, 5.1}) {
    const Truth a = truthAt(t - h), b = truthAt(t + h), x = truthAt(t);
    EXPECT_MATRIX_NEAR((b.p - a.p) / (2 * h), x.v, 1e-7);
    EXPECT_MATRIX_NEAR((b.v - a.v) / (2 * h), x.a, 1e-7);
    EXPECT_MATRIX_NEAR(logMap(a.q.conjugate() * b.q) / (2 * h), x.w_B, 1e-7);
  }
}

TEST(EskfParams, ValidateNamesOffendingFields) {
  EskfParams p;
  EXPECT_TRUE(p.validate().empty());
  p.accel_noise_density = -1.0;
  p.max_mocap_latency_s = 1.0;  // beyond the 64-sample history at 200 Hz
  const auto e = p.validate();
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].field, "eskf.accel_noise_density");
  EXPECT_EQ(e[1].field, "eskf.max_mocap_latency_s");
  EXPECT_THROW(Eskf{p}, std::invalid_argument);
}

/// Closed form: at rest and level with a perfect IMU, the filter started at the truth stays
/// there exactly and its position variance grows only by the process noise.
TEST(Eskf, HoverAtRestStaysPut) {
  Eskf f{EskfParams{}};
  EskfState s;
  s.p_W = {1.0, 2.0, 0.5};
  f.initialise(s, 0.0);
  for (int k = 1; k <= 400; ++k) {
    ImuSample imu;
    imu.t_s = k * 0.005;
    imu.accel_B = {0.0, 0.0, kG};
    ASSERT_EQ(f.addImu(imu), EskfStatus::kOk);
  }
  EXPECT_MATRIX_NEAR(f.state().p_W, s.p_W, 1e-12);
  EXPECT_MATRIX_NEAR(f.state().v_W, Vector3d::Zero(), 1e-12);
  EXPECT_LT(angleBetween(f.state().q_WB, Quaterniond::Identity()), 1e-12);
  EXPECT_GT(f.output().covariance_diagonal(0), 1.0);  // init 1 m² plus growth
  EXPECT_EQ(f.counters().imu_propagated, 400u);
}

/// Dead reckoning with a perfect IMU over 1 s of the aggressive motion: the midpoint scheme
/// keeps the drift below a millimetre and a hundredth of a degree.
TEST(Eskf, NoiseFreeDeadReckoningIsAccurate) {
  Eskf f{EskfParams{}};
  f.initialise(truthState(0.0), 0.0);
  for (int k = 0; k <= 200; ++k) {
    const double t = k * 0.005;
    const Truth x = truthAt(t);
    ImuSample imu;
    imu.t_s = t;
    imu.gyro_B = x.w_B;
    imu.accel_B = x.q.conjugate() * (x.a + kG * Vector3d::UnitZ());
    (void)f.addImu(imu);
  }
  const Truth x = truthAt(1.0);
  EXPECT_LT((f.state().p_W - x.p).norm(), 1e-3);
  EXPECT_LT((f.state().v_W - x.v).norm(), 2e-3);
  EXPECT_LT(angleBetween(f.state().q_WB, x.q), 0.01 * kDeg);
}

/// The requirement: from 0.5 m and 10° off, zero velocity and unknown biases, with
/// 20 ms mocap latency, the filter is within a centimetre and half a degree after 1 s (the
/// issue asks for a few cm and a degree in a few seconds), then tracks to millimetres; the
/// biases are recovered.
TEST(Eskf, ConvergesFromWrongInitialState) {
  Eskf f{EskfParams{}};
  EskfState s = truthState(0.0);
  s.p_W += 0.5 * Vector3d(1.0, 1.0, -1.0).normalized();
  s.q_WB = s.q_WB * expMap(10.0 * kDeg * Vector3d(1.0, 2.0, 3.0).normalized());
  s.v_W.setZero();
  f.initialise(s, 0.0);
  const SensorConfig c;
  const RunStats st = run(f, c, 8.0, 1.0);
  EXPECT_TRUE(st.finite);
  EXPECT_LT(st.max_pos, 0.01) << "within 1 cm from 1 s on";
  EXPECT_LT(st.max_att, 0.5 * kDeg);
  EXPECT_LT(st.rms_pos, 0.003);
  EXPECT_LT(st.rms_att, 0.2 * kDeg);
  EXPECT_LT(st.gyro_bias_err.norm(), 0.003);
  EXPECT_LT(st.accel_bias_err.norm(), 0.05);
  EXPECT_EQ(f.counters().mocap_gate_rejected, 0u);
  EXPECT_EQ(f.counters().mocap_too_old, 0u);
}

/// With 20 ms latency the delay-compensating filter does not lag the truth; the naive filter
/// that fuses each pose as if it were current does, and is clearly worse.
TEST(Eskf, DelayCompensationRemovesLag) {
  const SensorConfig c;
  EskfParams p;
  Eskf good{p};
  p.compensate_delay = false;
  Eskf naive{p};
  good.initialise(truthState(0.0), 0.0);
  naive.initialise(truthState(0.0), 0.0);
  const RunStats g = run(good, c, 8.0, 2.0);
  const RunStats n = run(naive, c, 8.0, 2.0);
  EXPECT_LT(g.rms_pos, 0.002);
  EXPECT_LT(std::abs(g.along_track_mean), 0.0005)
      << "compensated estimate lags by " << g.along_track_mean;
  EXPECT_GT(n.rms_pos, 3.0 * g.rms_pos);
  EXPECT_LT(n.along_track_mean, -0.005) << "the naive filter lags";
  EXPECT_GT(n.rms_att, 1.5 * g.rms_att);
}

TEST(Eskf, ChiSquareGateRejectsOneMetreOutlier) {
  Eskf f{EskfParams{}};
  f.initialise(truthState(0.0), 0.0);
  const SensorConfig c;
  int n = 0;
  const RunStats st = run(f, c, 6.0, 3.0, [&](MocapSample& m) {
    if (++n == 300) m.p_W.x() += 1.0;  // one bad pose at ≈ 3 s
    return true;
  });
  EXPECT_EQ(f.counters().mocap_gate_rejected, 1u);
  EXPECT_LT(st.max_pos, 0.01) << "the outlier did not pull the estimate";
}

/// A persistent jump (the mocap frame moved) is first rejected, then accepted after
/// max_consecutive_rejections poses, and the filter follows.
TEST(Eskf, RecoversFromPersistentJump) {
  Eskf f{EskfParams{}};
  f.initialise(truthState(0.0), 0.0);
  const SensorConfig c;
  int n = 0;
  const RunStats st = run(f, c, 6.0, 5.0, [&](MocapSample& m) {
    if (++n >= 200) m.p_W.y() += 0.5;
    return true;
  });
  EXPECT_EQ(f.counters().gate_recoveries, 1u);
  EXPECT_EQ(f.counters().mocap_gate_rejected,
            static_cast<std::uint64_t>(EskfParams{}.max_consecutive_rejections));
  EXPECT_LT(std::abs(f.state().p_W.y() - truthAt(6.0).p.y() - 0.5), 0.01);
  EXPECT_TRUE(st.finite);
}

TEST(Eskf, NonFiniteSamplesAreRejectedAndCounted) {
  Eskf f{EskfParams{}};
  f.initialise(truthState(0.0), 0.0);
  const SensorConfig c;
  run(f, c, 1.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ImuSample bad;
  bad.t_s = 1.0025;
  bad.gyro_B = {nan, 0, 0};
  EXPECT_EQ(f.addImu(bad), EskfStatus::kNonFinite);
  bad.gyro_B.setZero();
  bad.accel_B = {0, std::numeric_limits<double>::infinity(), 0};
  EXPECT_EQ(f.addImu(bad), EskfStatus::kNonFinite);
  bad.accel_B.setZero();
  bad.t_s = nan;
  EXPECT_EQ(f.addImu(bad), EskfStatus::kNonFinite);
  MocapSample m;
  m.t_s = 0.99;
  m.p_W = {nan, 0, 0};
  EXPECT_EQ(f.addMocap(m), EskfStatus::kNonFinite);
  m.p_W.setZero();
  m.q_WB = Quaterniond(0, 0, 0, 0);
  EXPECT_EQ(f.addMocap(m), EskfStatus::kNonFinite);
  EXPECT_EQ(f.counters().imu_non_finite, 3u);
  EXPECT_EQ(f.counters().mocap_non_finite, 2u);
  const EskfOutput o = f.output();
  EXPECT_TRUE(o.estimate.p_W.allFinite() && o.estimate.q_WB.coeffs().allFinite() &&
              o.covariance_diagonal.allFinite());
  EXPECT_LT((o.estimate.p_W - truthAt(1.0).p).norm(), 0.01);

  // A stream with 5 % NaN IMU samples still tracks.
  Eskf g{EskfParams{}};
  g.initialise(truthState(0.0), 0.0);
  std::mt19937_64 rng(7);
  std::bernoulli_distribution drop(0.05);
  std::normal_distribution<double> n01;
  for (int k = 0; k <= 1000; ++k) {
    const double t = k * 0.005;
    const Truth x = truthAt(t);
    ImuSample imu;
    imu.t_s = t;
    imu.gyro_B = x.w_B;
    imu.accel_B = x.q.conjugate() * (x.a + kG * Vector3d::UnitZ());
    if (drop(rng)) imu.accel_B.x() = nan;
    (void)g.addImu(imu);
    if (k % 2 == 0) {
      MocapSample mm;
      mm.t_s = t;
      mm.p_W = x.p;
      mm.q_WB = x.q;
      (void)g.addMocap(mm);
    }
  }
  EXPECT_GT(g.counters().imu_non_finite, 20u);
  EXPECT_LT((g.state().p_W - truthAt(5.0).p).norm(), 0.005);
}

TEST(Eskf, TimeGoingBackwardsIsRejected) {
  Eskf f{EskfParams{}};
  f.initialise(truthState(0.0), 0.0);
  ImuSample imu;
  imu.accel_B = {0, 0, kG};
  imu.t_s = 0.005;
  EXPECT_EQ(f.addImu(imu), EskfStatus::kOk);
  imu.t_s = 0.004;
  EXPECT_EQ(f.addImu(imu), EskfStatus::kTimeNotIncreasing);
  imu.t_s = 0.005;
  EXPECT_EQ(f.addImu(imu), EskfStatus::kTimeNotIncreasing);
  EXPECT_EQ(f.counters().imu_time_rejected, 2u);
  EXPECT_DOUBLE_EQ(f.output().t_s, 0.005);

  MocapSample m;
  m.p_W = truthAt(0.0).p;
  m.q_WB = truthAt(0.0).q;
  m.t_s = 0.004;
  EXPECT_EQ(f.addMocap(m), EskfStatus::kOk);
  m.t_s = 0.003;  // older than the last fused pose
  EXPECT_EQ(f.addMocap(m), EskfStatus::kTimeNotIncreasing);
  EXPECT_EQ(f.counters().mocap_out_of_order, 1u);
}

TEST(Eskf, TooOldAndFuturePoses) {
  EskfParams p;
  p.max_mocap_latency_s = 0.05;
  Eskf f{p};
  f.initialise(truthState(0.0), 0.0);
  ImuSample imu;
  imu.accel_B = {0, 0, kG};
  for (int k = 1; k <= 40; ++k) {
    imu.t_s = k * 0.005;
    (void)f.addImu(imu);
  }
  MocapSample m;
  m.q_WB = truthAt(0.0).q;
  m.p_W = truthAt(0.0).p;
  m.t_s = 0.2 - 0.06;
  EXPECT_EQ(f.addMocap(m), EskfStatus::kTooOld);
  EXPECT_EQ(f.counters().mocap_too_old, 1u);
  // Captured after the newest IMU sample: waits, then is fused when the IMU passes it.
  m.t_s = 0.2012;
  EXPECT_EQ(f.addMocap(m), EskfStatus::kDeferred);
  const auto fused = f.counters().mocap_fused;
  imu.t_s = 0.205;
  EXPECT_EQ(f.addImu(imu), EskfStatus::kOk);
  EXPECT_EQ(f.counters().mocap_fused, fused + 1);
}

TEST(Eskf, InitialisesFromFirstPose) {
  Eskf f{EskfParams{}};
  ImuSample imu;
  imu.t_s = 0.0;
  imu.accel_B = {0, 0, kG};
  EXPECT_EQ(f.addImu(imu), EskfStatus::kNotInitialised);
  EXPECT_FALSE(f.output().initialised);
  MocapSample m;
  m.t_s = 0.0;
  m.p_W = {0.3, -0.2, 1.0};
  m.q_WB = expMap(Vector3d(0, 0, 0.5));
  EXPECT_EQ(f.addMocap(m), EskfStatus::kInitialised);
  EXPECT_TRUE(f.output().initialised);
  EXPECT_MATRIX_NEAR(f.state().p_W, m.p_W, 1e-15);
  imu.t_s = 0.005;
  imu.accel_B = {0, 0, kG};
  EXPECT_EQ(f.addImu(imu), EskfStatus::kOk);
  EXPECT_MATRIX_NEAR(f.state().p_W, m.p_W, 1e-12);
}

/// The controller-facing output: bias-corrected rates and specific force.
TEST(Eskf, OutputIsBiasCorrected) {
  Eskf f{EskfParams{}};
  EskfState s;
  s.accel_bias_B = {0.1, 0.2, 0.3};
  s.gyro_bias_B = {0.01, 0.02, 0.03};
  f.initialise(s, 0.0);
  ImuSample imu;
  imu.t_s = 0.005;
  imu.gyro_B = {0.5, 0.6, 0.7};
  imu.accel_B = {1.0, 2.0, 10.0};
  ASSERT_EQ(f.addImu(imu), EskfStatus::kOk);
  const EskfOutput o = f.output();
  EXPECT_MATRIX_NEAR(o.gyro_B, imu.gyro_B - s.gyro_bias_B, 1e-15);
  EXPECT_MATRIX_NEAR(o.accel_B, imu.accel_B - s.accel_bias_B, 1e-15);
  EXPECT_DOUBLE_EQ(o.t_s, 0.005);
}

}  // namespace
