// SPDX-License-Identifier: BSD-3-Clause
// The estimators fed garbage (issue 16 item 3): 10⁵ seeded calls each of Eskf::addImu/addMocap,
// LatticeHeightEstimator::estimate and DisturbanceObserver::update with NaN, ±∞, huge, denormal
// and random values, bad frame sizes, zero and non-unit quaternions and non-increasing times,
// mixed with valid stretches. Nothing may throw (the functions are noexcept: a throw would end
// this executable in std::terminate), allocate, or hand out a non-finite value marked valid, and
// once the garbage stops each estimator must give correct values again.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "geaware/estimation/disturbance_observer.hpp"
#include "geaware/estimation/eskf.hpp"
#include "geaware/estimation/lattice_height.hpp"
#include "geaware_test/allocation_counter.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace {

using namespace geaware::estimation;
using Eigen::Quaterniond;
using Eigen::Vector3d;
using Eigen::Vector4d;
using geaware::model::ImuSample;
using geaware::model::MocapSample;
using geaware::model::RangerFrame;
using geaware_test::paperVehicle;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kG = geaware::model::kGravity;
constexpr double kDt = 0.005;  // 200 Hz
constexpr std::uint64_t kSeed = 0x6a7ba6e16ULL;
constexpr int kCalls = 100000;

/// One scalar of garbage: NaN, ±∞, ±huge, ±denormal, zero, or a random value over 16 decades.
double garbage(std::mt19937_64& rng, double typical) {
  std::uniform_int_distribution<int> kind(0, 9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  switch (kind(rng)) {
    case 0: return kNaN;
    case 1: return kInf;
    case 2: return -kInf;
    case 3: return u(rng) < 0 ? -1e300 : 1e300;
    case 4: return u(rng) < 0 ? -std::numeric_limits<double>::max() : std::numeric_limits<double>::max();
    case 5: return u(rng) * std::numeric_limits<double>::denorm_min() * 1e6;
    case 6: return 0.0;
    default: return u(rng) * typical * std::pow(10.0, 8.0 * u(rng));
  }
}

template <typename Vec>
void garble(std::mt19937_64& rng, Vec&& v, double typical, double p) {
  std::bernoulli_distribution hit(p);
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (hit(rng)) v(i) = garbage(rng, typical);
  }
}

/// Stretch lengths: valid 1-100 calls, then garbage 1-200 calls with a garbling probability.
struct Schedule {
  explicit Schedule(std::uint64_t seed, bool garbage_first = false)
      : rng(seed), garbage_now(!garbage_first) {}
  std::mt19937_64 rng;
  int left = 0;
  bool garbage_now;
  double p = 0.1;
  /// Whether the next call is garbage.
  bool next() {
    if (left-- <= 0) {
      garbage_now = !garbage_now;
      left = garbage_now ? std::uniform_int_distribution<int>(1, 200)(rng)
                         : std::uniform_int_distribution<int>(1, 100)(rng);
      p = std::uniform_real_distribution<double>(0.02, 0.6)(rng);
    }
    return garbage_now;
  }
};

// ---------------------------------------------------------------------------- ESKF

const Vector3d kHoverP(0.4, -0.2, 0.3);

bool covarianceSane(const Eskf::Cov& P) {
  return P.allFinite() && (P - P.transpose()).cwiseAbs().maxCoeff() <= 1e-9 * (1.0 + P.cwiseAbs().maxCoeff()) &&
         (P.diagonal().array() >= 0.0).all();
}

/// false: the default filter, initialised at the hover; true: the naive filter (no delay
/// compensation), initialised by the first pose it accepts, which may be garbage.
class EskfGarbage : public ::testing::TestWithParam<bool> {};

TEST_P(EskfGarbage, ImuAndMocapGarbageNeverPoisonTheFilterAndItRecovers) {
  const bool naive = GetParam();
  EskfParams params;
  params.compensate_delay = !naive;
  Eskf f{params};
  if (!naive) {
    EskfState s;
    s.p_W = kHoverP;
    f.initialise(s, 0.0);
  }
  Schedule sched(kSeed, /*garbage_first=*/naive);  // the naive filter may start from garbage
  std::mt19937_64 rng(kSeed + 1);
  std::normal_distribution<double> n(0.0, 1.0);
  double t = 0.0;
  int bad_outputs = 0, bad_covariances = 0;
  const long before = geaware_test::allocationCount();
  for (int k = 0; k < kCalls; ++k) {
    const bool g = sched.next();
    t += kDt;
    ImuSample imu;
    imu.t_s = t;
    imu.gyro_B = 1e-3 * Vector3d(n(rng), n(rng), n(rng));
    imu.accel_B = Vector3d(0.0, 0.0, kG) + 0.02 * Vector3d(n(rng), n(rng), n(rng));
    MocapSample m;
    m.t_s = t - 0.01;
    m.p_W = kHoverP + 1e-3 * Vector3d(n(rng), n(rng), n(rng));
    if (g) {
      const double p = sched.p;
      std::bernoulli_distribution hit(p);
      garble(rng, imu.gyro_B, 1.0, p);
      garble(rng, imu.accel_B, 10.0, p);
      if (hit(rng)) imu.t_s = hit(rng) ? garbage(rng, 1.0) : t - 0.5 * kDt;
      garble(rng, m.p_W, 1.0, p);
      garble(rng, m.q_WB.coeffs(), 1.0, p);
      if (hit(rng)) m.q_WB.coeffs().setZero();
      if (hit(rng)) m.t_s = hit(rng) ? garbage(rng, 1.0) : t - 0.5;
    }
    (void)f.addImu(imu);
    if (k % 2 == 0) (void)f.addMocap(m);
    const EskfOutput out = f.output();
    if (out.initialised &&
        !(out.estimate.p_W.allFinite() && out.estimate.v_W.allFinite() &&
          out.estimate.q_WB.coeffs().allFinite() && out.gyro_B.allFinite() &&
          out.accel_B.allFinite() && out.covariance_diagonal.allFinite())) {
      ++bad_outputs;
    }
    if (k % 97 == 0 && !covarianceSane(f.covariance())) ++bad_covariances;
  }
  EXPECT_EQ(geaware_test::allocationCount() - before, 0);
  EXPECT_EQ(bad_outputs, 0) << "non-finite estimates from an initialised filter";
  EXPECT_EQ(bad_covariances, 0);
  EXPECT_GT(f.counters().imu_non_finite, 1000u);
  EXPECT_GT(f.counters().mocap_non_finite, 1000u);
  // Clean data again: 3 s of hover and poses; the estimate returns to the hover point.
  for (int k = 0; k < 600; ++k) {
    t += kDt;
    ImuSample imu;
    imu.t_s = t;
    imu.accel_B = Vector3d(0.0, 0.0, kG);
    ASSERT_EQ(f.addImu(imu), EskfStatus::kOk) << "the filter no longer takes valid IMU samples";
    if (k % 2 == 0) {
      MocapSample m;
      m.t_s = t - 0.01;
      m.p_W = kHoverP;
      (void)f.addMocap(m);
    }
  }
  const EskfOutput out = f.output();
  ASSERT_TRUE(out.initialised);
  EXPECT_LT((out.estimate.p_W - kHoverP).norm(), 0.01);
  EXPECT_LT(out.estimate.v_W.norm(), 0.05);
  EXPECT_LT(out.estimate.q_WB.angularDistance(Quaterniond::Identity()), 0.02);
  EXPECT_TRUE(covarianceSane(f.covariance()));
}

TEST_P(EskfGarbage, AFirstPoseOfGarbageIsOutlivedByCleanData) {
  // A pose that is finite but absurd (1e300 m) initialises the filter; 3 s of clean IMU data
  // and poses must bring it back.
  EskfParams params;
  params.compensate_delay = !GetParam();
  for (double x : {1e300, -1e150, 1e12}) {
    Eskf f{params};
    MocapSample bad;
    bad.p_W = Vector3d(x, 0.0, 0.0);
    ASSERT_EQ(f.addMocap(bad), EskfStatus::kInitialised);
    double t = 0.0;
    for (int k = 0; k < 600; ++k) {
      t += kDt;
      ImuSample imu;
      imu.t_s = t;
      imu.accel_B = Vector3d(0.0, 0.0, kG);
      (void)f.addImu(imu);
      if (k % 2 == 0) {
        MocapSample m;
        m.t_s = t - 0.01;
        m.p_W = kHoverP;
        (void)f.addMocap(m);
      }
    }
    SCOPED_TRACE(x);
    EXPECT_LT((f.output().estimate.p_W - kHoverP).norm(), 0.01);
    EXPECT_TRUE(covarianceSane(f.covariance()));
  }
}

INSTANTIATE_TEST_SUITE_P(Filters, EskfGarbage, ::testing::Values(false, true),
                         [](const auto& p) { return p.param ? "NaiveSelfInitialised" : "Default"; });

// ---------------------------------------------------------------------------- lattice ranger

/// A level floor h below the rotor plane, seen by an 8×8 ranger looking down.
RangerFrame floorFrame(double h) {
  RangerFrame fr;
  fr.side = 8;
  fr.fov_rad = 0.785;
  for (int i = 0; i < fr.side; ++i) {
    for (int j = 0; j < fr.side; ++j) {
      const auto k = static_cast<std::size_t>(fr.index(i, j));
      fr.valid[k] = true;
      fr.range_m[k] = h / -fr.zoneDirection_B(i, j).z();
    }
  }
  return fr;
}

bool latticeSane(const LatticeHeight& r) {
  if (!r.valid) return true;
  bool ok = std::isfinite(r.height_m) && r.height_m >= 0.0 && r.normal_W.allFinite() &&
            std::isfinite(r.rms_residual_m);
  for (int i = 0; i < 4; ++i) {
    ok = ok && std::isfinite(r.rotor_height_m[static_cast<std::size_t>(i)]) &&
         std::isfinite(r.rotor_support_distance_m[static_cast<std::size_t>(i)]);
  }
  for (int i = 0; i < r.surfaces; ++i) {
    const GroundPlane& pl = r.planes[static_cast<std::size_t>(i)];
    ok = ok && pl.normal_W.allFinite() && std::isfinite(pl.offset_m);
  }
  return ok;
}

TEST(LatticeHeightGarbage, FramesOfGarbageNeverGiveAValidNonFiniteHeight) {
  LatticeHeightParams params = LatticeHeightParams::forVehicle(geaware_test::paperParams());
  const LatticeHeightEstimator est(params);
  Schedule sched(kSeed + 2);
  std::mt19937_64 rng(kSeed + 3);
  int bad = 0, valid_garbage = 0;
  const RangerFrame clean = floorFrame(0.3);
  const long before = geaware_test::allocationCount();
  // A frame costs ~10× an ESKF update: 8×8 frames keep the 10⁵ calls under a second.
  for (int k = 0; k < kCalls; ++k) {
    RangerFrame fr = clean;
    Quaterniond q = Quaterniond::Identity();
    const bool g = sched.next();
    if (g) {
      const double p = sched.p;
      std::bernoulli_distribution hit(p);
      if (hit(rng)) {
        const int sides[] = {0, -1, -100000, 1, 2, 17, 1 << 30, std::numeric_limits<int>::min(), 16};
        fr.side = sides[std::uniform_int_distribution<int>(0, 8)(rng)];
      }
      if (hit(rng)) fr.fov_rad = garbage(rng, 1.0);
      garble(rng, fr.mount_B, 0.1, p);
      std::bernoulli_distribution zone_hit(p);
      for (std::size_t z = 0; z < fr.range_m.size(); ++z) {
        if (zone_hit(rng)) fr.range_m[z] = garbage(rng, 0.3);
        if (zone_hit(rng)) fr.valid[z] = !fr.valid[z];
      }
      garble(rng, q.coeffs(), 1.0, p);
      if (hit(rng)) q.coeffs().setZero();
    }
    const LatticeHeight r = est.estimate(fr, q);
    if (!latticeSane(r)) ++bad;
    if (g && r.valid) ++valid_garbage;
  }
  EXPECT_EQ(geaware_test::allocationCount() - before, 0);
  EXPECT_EQ(bad, 0) << "valid results with non-finite or negative values";
  EXPECT_GT(valid_garbage, 0);  // lightly garbled frames still give a height
  // Stateless, but checked: a clean frame afterwards gives the floor's height.
  const LatticeHeight r = est.estimate(clean, Quaterniond::Identity());
  ASSERT_TRUE(r.valid) << toString(r.status);
  EXPECT_NEAR(r.height_m, 0.3, 1e-6);
}

// ---------------------------------------------------------------------------- disturbance observer

bool estimateSane(const DisturbanceEstimate& d) {
  if (!d.valid) return true;
  return std::isfinite(d.t_s) && d.a_ext_W.allFinite() && d.a_ext_B.allFinite() &&
         d.tau_ext_B.allFinite() && std::isfinite(d.thrust_f_N) && d.tau_B_f.allFinite() &&
         d.w_f_B.allFinite() && d.w_dot_f_B.allFinite() && (!d.f_g_valid || std::isfinite(d.f_g_ratio));
}

TEST(DisturbanceObserverGarbage, NeverAValidNonFiniteEstimateAndZeroAgainAtHover) {
  DisturbanceObserver obs(paperVehicle(), {});
  const auto& vp = paperVehicle().params();
  const double n_hover = std::sqrt(vp.mass_kg * kG / (4.0 * vp.rotor.k_T_N_per_rpm2));
  Schedule sched(kSeed + 4);
  std::mt19937_64 rng(kSeed + 5);
  std::normal_distribution<double> n(0.0, 1.0);
  int bad = 0;
  double t = 0.0;
  const long before = geaware_test::allocationCount();
  for (int k = 0; k < kCalls; ++k) {
    t += kDt;
    DisturbanceObserverInput in;
    in.t_s = t;
    in.gyro_B = 0.1 * Vector3d(n(rng), n(rng), n(rng));
    in.accel_B = Vector3d(0.0, 0.0, kG) + 0.3 * Vector3d(n(rng), n(rng), n(rng));
    in.rotor_speeds_rpm = Vector4d::Constant(n_hover) + 100.0 * Vector4d(n(rng), n(rng), n(rng), n(rng));
    if (sched.next()) {
      const double p = sched.p;
      std::bernoulli_distribution hit(p);
      garble(rng, in.gyro_B, 1.0, p);
      garble(rng, in.accel_B, 10.0, p);
      garble(rng, in.rotor_speeds_rpm, 1e4, p);
      garble(rng, in.q_WB.coeffs(), 1.0, p);
      if (hit(rng)) in.q_WB.coeffs().setZero();
      if (hit(rng)) in.t_s = hit(rng) ? garbage(rng, 1.0) : t - kDt;
    }
    if (!estimateSane(obs.update(in))) ++bad;
  }
  EXPECT_EQ(geaware_test::allocationCount() - before, 0);
  EXPECT_EQ(bad, 0) << "valid estimates with non-finite values";
  EXPECT_GT(obs.rejectedSamples(), 1000u);
  // A clean hover again: within 1 s the estimate is valid and zero.
  DisturbanceEstimate d;
  for (int k = 0; k < 200; ++k) {
    t += kDt;
    DisturbanceObserverInput in;
    in.t_s = t;
    in.accel_B = Vector3d(0.0, 0.0, kG);
    in.rotor_speeds_rpm.setConstant(n_hover);
    d = obs.update(in);
  }
  ASSERT_TRUE(d.valid) << "the observer no longer gives estimates";
  EXPECT_LT(d.a_ext_W.norm(), 1e-3);
  EXPECT_LT(d.tau_ext_B.norm(), 1e-6);
  EXPECT_NEAR(d.thrust_f_N, vp.mass_kg * kG, 1e-3);
}

}  // namespace
