// SPDX-License-Identifier: BSD-3-Clause
// The virtual rigs: determinism with a seed, noise statistics, sweep layout, the single-rotor
// stand's closed forms, the mixing experiment of docs/paper-facts.md, and the whole calibration.

#include "geaware/sim/rigs.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <vector>

#include "geaware/model/mixer.hpp"
#include "geaware/model/motor.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace geaware::sim {
namespace {

using geaware_test::paperParams;

std::vector<PlatformRow> runPlatform(const PlatformSweep& sw, std::uint64_t seed,
                                     PlatformParams p = {}) {
  const ForceTorquePlatform platform(rigGeometry(paperParams()), RotorAeroParams{}, p);
  std::vector<PlatformRow> rows;
  platform.sweep(sw, seed, [&rows](const PlatformRow& r) { rows.push_back(r); });
  return rows;
}

bool bitIdentical(const PlatformRow& a, const PlatformRow& b) {
  const auto same = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  bool ok = same(a.t_s, b.t_s) && same(a.h_m, b.h_m) && same(a.tilt_deg, b.tilt_deg);
  for (int i = 0; i < 4; ++i)
    ok = ok && same(a.n_rpm[static_cast<std::size_t>(i)], b.n_rpm[static_cast<std::size_t>(i)]);
  for (int k = 0; k < 3; ++k)
    ok = ok && same(a.force_B[k], b.force_B[k]) && same(a.torque_B[k], b.torque_B[k]);
  return ok;
}

PlatformSweep smallSweep() {
  PlatformSweep sw;
  sw.heights_m = {0.1, 0.2};
  sw.tilts_deg = {0.0, 15.0};
  sw.rpm = {10000.0, 15000.0};
  return sw;
}

TEST(RigNoise, BoxMullerOnTheEngineSeedIsTheRigsFormerStream) {
  // The rigs' stream before it moved into NoiseSource: Box–Muller on std::mt19937_64(seed).
  std::mt19937_64 rng(11);
  auto noise = NoiseSource::fromEngineSeed(11);
  for (int k = 0; k < 1000; ++k) {
    const double u1 = (static_cast<double>(rng() >> 11) + 1.0) * 0x1.0p-53;
    const double u2 = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    const double r = std::sqrt(-2.0 * std::log(u1));
    const double a = 2.0 * std::numbers::pi * u2;
    ASSERT_EQ(noise.boxMuller(0.5), 0.5 * r * std::cos(a)) << k;
    ASSERT_EQ(noise.boxMuller(2.0), 2.0 * r * std::sin(a)) << k;
  }
  std::mt19937_64 rng2(5);
  auto u = NoiseSource::fromEngineSeed(5);
  for (int k = 0; k < 1000; ++k) {
    ASSERT_EQ(u.uniformHalfOpen(), static_cast<double>(rng2() >> 11) * 0x1.0p-53) << k;
  }
}

TEST(RigNoise, SameSeedSameSequenceAndUnitVariance) {
  auto a = NoiseSource::fromEngineSeed(7);
  auto b = NoiseSource::fromEngineSeed(7);
  auto c = NoiseSource::fromEngineSeed(8);
  double sum = 0.0;
  double sum_sq = 0.0;
  bool differs = false;
  const int N = 200000;
  for (int k = 0; k < N; ++k) {
    const double x = a.boxMuller(1.0);
    EXPECT_EQ(x, b.boxMuller(1.0));
    differs = differs || x != c.boxMuller(1.0);
    sum += x;
    sum_sq += x * x;
  }
  EXPECT_TRUE(differs);
  // Mean within 5σ/√N, variance within 2 % (N = 2e5: its standard error is 0.3 %).
  EXPECT_NEAR(sum / N, 0.0, 5.0 / std::sqrt(N));
  EXPECT_NEAR(sum_sq / N, 1.0, 0.02);
}

TEST(Platform, SameSeedGivesBitIdenticalRowsAnotherSeedDiffers) {
  const auto a = runPlatform(smallSweep(), 42);
  const auto b = runPlatform(smallSweep(), 42);
  const auto c = runPlatform(smallSweep(), 43);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), c.size());
  bool any_diff = false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_TRUE(bitIdentical(a[k], b[k])) << "row " << k;
    any_diff = any_diff || !bitIdentical(a[k], c[k]);
  }
  EXPECT_TRUE(any_diff);
}

TEST(Platform, SweepLayoutTimeAndSetpoints) {
  PlatformParams p;
  p.samples_per_setpoint = 3;
  const auto rows = runPlatform(smallSweep(), 1, p);
  ASSERT_EQ(rows.size(), 2u * 2u * 2u * 3u);
  EXPECT_EQ(smallSweep().setpointCount(), 8u);
  // Heights outermost, then tilts, then speeds; time strictly increasing.
  EXPECT_EQ(rows.front().h_m, 0.1);
  EXPECT_EQ(rows.back().h_m, 0.2);
  EXPECT_EQ(rows[3].n_rpm[0], 15000.0);
  EXPECT_EQ(rows[6].tilt_deg, 15.0);
  for (std::size_t k = 1; k < rows.size(); ++k) EXPECT_GT(rows[k].t_s, rows[k - 1].t_s);
}

TEST(Platform, NoiseHasTheConfiguredSpreadAroundTheSteadyWrench) {
  PlatformParams p;
  p.samples_per_setpoint = 20000;
  p.force_noise_N = 0.05;
  p.torque_noise_Nm = 0.004;
  PlatformSweep sw;
  sw.heights_m = {0.18};
  sw.tilts_deg = {15.0};
  sw.rpm = {15000.0};
  const auto rows = runPlatform(sw, 3, p);
  const ForceTorquePlatform quiet(rigGeometry(paperParams()), RotorAeroParams{}, PlatformParams{});
  const Wrench truth = quiet.wrench(0.18, 15.0, {15000.0, 15000.0, 15000.0, 15000.0}).wrench;
  double mean_fz = 0.0;
  double var_fz = 0.0;
  double mean_ty = 0.0;
  double var_ty = 0.0;
  for (const auto& r : rows) {
    mean_fz += r.force_B.z() / static_cast<double>(rows.size());
    mean_ty += r.torque_B.y() / static_cast<double>(rows.size());
  }
  for (const auto& r : rows) {
    var_fz += std::pow(r.force_B.z() - mean_fz, 2) / static_cast<double>(rows.size());
    var_ty += std::pow(r.torque_B.y() - mean_ty, 2) / static_cast<double>(rows.size());
  }
  EXPECT_NEAR(mean_fz, truth.force_B.z(), 5.0 * 0.05 / std::sqrt(20000.0));
  EXPECT_NEAR(mean_ty, truth.torque_B.y(), 5.0 * 0.004 / std::sqrt(20000.0));
  EXPECT_NEAR(std::sqrt(var_fz), 0.05, 0.05 * 0.03);
  EXPECT_NEAR(std::sqrt(var_ty), 0.004, 0.004 * 0.03);
}

TEST(Platform, RpmDifferencesFollowTheMixerRows) {
  PlatformSweep sw;
  sw.heights_m = {0.2};
  sw.tilts_deg = {0.0};
  sw.rpm = {12000.0};
  sw.rpm_diffs = {0.0, 500.0};
  PlatformParams p;
  p.samples_per_setpoint = 1;
  const auto rows = runPlatform(sw, 5, p);
  ASSERT_EQ(rows.size(), 1u + 3u);  // Δ = 0 once, Δ = 500 on roll, pitch, yaw
  const Eigen::Matrix4d& A = model::Mixer::allocationPattern();
  for (int axis = 1; axis <= 3; ++axis) {
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(rows[static_cast<std::size_t>(axis)].n_rpm[static_cast<std::size_t>(i)],
                12000.0 + 500.0 * A(axis, i));
    }
  }
}

TEST(Platform, InvalidSweepsAreRejected) {
  const ForceTorquePlatform platform(rigGeometry(paperParams()), RotorAeroParams{},
                                     PlatformParams{});
  const auto sink = [](const PlatformRow&) {};
  PlatformSweep sw = smallSweep();
  sw.heights_m = {};
  EXPECT_THROW((void)platform.sweep(sw, 1, sink), std::invalid_argument);
  sw = smallSweep();
  sw.tilts_deg = {50.0};
  EXPECT_THROW((void)platform.sweep(sw, 1, sink), std::invalid_argument);
  sw = smallSweep();
  sw.heights_m = {-0.1};
  EXPECT_THROW((void)platform.sweep(sw, 1, sink), std::invalid_argument);
  sw = smallSweep();
  sw.rpm_diffs = {20000.0};
  EXPECT_THROW((void)platform.sweep(sw, 1, sink), std::invalid_argument);
  PlatformParams bad;
  bad.samples_per_setpoint = 0;
  EXPECT_THROW(ForceTorquePlatform(rigGeometry(paperParams()), RotorAeroParams{}, bad),
               std::invalid_argument);
}

TEST(Platform, MixingCoefficientsBarelyChangeNearTheGroundWhileThrustDoes) {
  // docs/paper-facts.md "The mixer near the ground": k_TX and k_I change < 10 % from high altitude
  // down to the board, k_T about 30 %. Rpm-difference experiments on the level board, fitted
  // by least squares from the noisy rig rows (as the paper identified them).
  const double arm = geaware::model::mixerArm_m(paperParams().diagonal_rotor_distance_m);
  const Eigen::Matrix4d& A = model::Mixer::allocationPattern();
  struct Coeffs {
    double kT, kTX, kI;
  };
  const auto identify = [&](double h) {
    PlatformSweep sw;
    sw.heights_m = {h};
    sw.tilts_deg = {0.0};
    sw.rpm = {9000.0, 12000.0, 15000.0};
    sw.rpm_diffs = {-1500.0, -750.0, 0.0, 750.0, 1500.0};
    sw.diff_axes = {DiffAxis::kRoll, DiffAxis::kYaw};
    PlatformParams p;
    p.samples_per_setpoint = 10;
    const auto rows = runPlatform(sw, 11, p);
    // Least squares through the origin: y = k·x.
    double sxx_t = 0, sxy_t = 0, sxx_x = 0, sxy_x = 0, sxx_i = 0, sxy_i = 0;
    for (const auto& r : rows) {
      double n2 = 0, roll = 0, yaw = 0;
      for (int i = 0; i < 4; ++i) {
        const double s =
            r.n_rpm[static_cast<std::size_t>(i)] * r.n_rpm[static_cast<std::size_t>(i)];
        n2 += s;
        roll += A(1, i) * s;
        yaw += A(3, i) * s;
      }
      sxx_t += n2 * n2;
      sxy_t += n2 * r.force_B.z();
      sxx_x += arm * roll * arm * roll;
      sxy_x += arm * roll * r.torque_B.x();
      sxx_i += yaw * yaw;
      sxy_i += yaw * r.torque_B.z();
    }
    return Coeffs{sxy_t / sxx_t, sxy_x / sxx_x, sxy_i / sxx_i};
  };
  const Coeffs inf = identify(50.0);
  EXPECT_NEAR(inf.kT, paperParams().rotor.k_T_N_per_rpm2, 0.002 * inf.kT);
  for (double h : {0.072, 0.1, 0.15, 0.2, 0.3, 0.5, 1.0}) {
    const Coeffs c = identify(h);
    EXPECT_LT(std::abs(c.kTX / inf.kTX - 1.0), 0.10) << "h = " << h;
    EXPECT_LT(std::abs(c.kI / inf.kI - 1.0), 0.10) << "h = " << h;
  }
  const double kT_change = identify(0.072).kT / inf.kT - 1.0;
  EXPECT_NEAR(kT_change, 0.30, 0.10);
}

TEST(RotorStand, SteadyStateFollowsTheThrottleCurveAndTheRotorLaws) {
  RotorStandParams p;
  p.thrust_noise_N = 0.0;
  p.torque_noise_Nm = 0.0;
  p.rpm_noise = 0.0;
  const RotorStand stand(paperParams(), p);
  std::vector<RotorStandRow> rows;
  const std::size_t count =
      stand.sweep({0.2, 0.5, 1.0}, 1, [&rows](const RotorStandRow& r) { rows.push_back(r); });
  ASSERT_EQ(count, rows.size());
  ASSERT_EQ(rows.size(), 3u * 200u);
  const model::ThrottleCurve curve(paperParams().throttle);
  const auto& rp = paperParams().rotor;
  for (std::size_t k : {199u, 399u, 599u}) {  // last sample of each hold: settled (1 s ≫ 30 ms)
    const RotorStandRow& r = rows[k];
    EXPECT_NEAR(r.rpm, curve.speedRpm(r.throttle), 1e-6 * r.rpm);
    EXPECT_NEAR(r.thrust_N, rp.k_T_N_per_rpm2 * r.rpm * r.rpm, 1e-9);
    EXPECT_NEAR(r.torque_Nm, rp.k_I_Nm_per_rpm2 * r.rpm * r.rpm, 1e-9);
  }
  // docs/paper-facts.md's throttle figure: ~10,300 rpm at 0.2, ~15,000 at 0.5, ~19,700 at 1 (±3 %).
  EXPECT_NEAR(rows[199].rpm, 10300.0, 0.03 * 10300.0);
  EXPECT_NEAR(rows[399].rpm, 15000.0, 0.03 * 15000.0);
  EXPECT_NEAR(rows[599].rpm, 19700.0, 0.03 * 19700.0);
  // Right after a step up, J_R·ṅ adds to the torque.
  const RotorStandRow& step = rows[200];
  EXPECT_GT(step.torque_Nm, rp.k_I_Nm_per_rpm2 * step.rpm * step.rpm + 1e-3);
}

TEST(RotorStand, DeterministicAndRejectsBadThrottles) {
  const RotorStand stand(paperParams(), RotorStandParams{});
  std::vector<double> a;
  std::vector<double> b;
  (void)stand.sweep({0.3, 0.6}, 9, [&a](const RotorStandRow& r) { a.push_back(r.thrust_N); });
  (void)stand.sweep({0.3, 0.6}, 9, [&b](const RotorStandRow& r) { b.push_back(r.thrust_N); });
  EXPECT_EQ(a, b);
  EXPECT_THROW((void)stand.sweep({1.2}, 9, [](const RotorStandRow&) {}), std::invalid_argument);
  EXPECT_THROW((void)stand.sweep({}, 9, [](const RotorStandRow&) {}), std::invalid_argument);
}

TEST(Calibration, EveryTargetOfThePaperPasses) {
  const CalibrationResult res = calibrate(paperParams(), RotorAeroParams{});
  ASSERT_GT(res.checks.size(), 30u);
  for (const auto& c : res.checks) {
    EXPECT_TRUE(c.pass) << c.name << ": paper " << c.paper << ", ours " << c.ours << " ("
                        << c.tolerance << ")";
  }
  EXPECT_TRUE(res.allPass());
  EXPECT_EQ(res.curves.h_m.size(), res.curves.torque_15deg_Nm.size());
}

}  // namespace
}  // namespace geaware::sim
