// SPDX-License-Identifier: BSD-3-Clause
// Single-rotor stand: k_T, k_I, J_R and the throttle curve from a synthetic sweep.

#include "geaware/ident/rotor_fit.hpp"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "synthetic.hpp"

namespace {

using geaware::ident::fitRotorStand;
using geaware::ident::RotorFitOptions;
using ident_test::withinSigmas;

RotorFitOptions sweepOptions() {
  RotorFitOptions o;
  // The sweep never holds a speed: the throttle curve uses every sample (the synthetic
  // throttle is the exact static inverse of the curve, so transients do not bias it).
  o.throttle_max_rate_rpm_per_s = std::numeric_limits<double>::infinity();
  return o;
}

TEST(RotorFit, RecoversTheStandParametersWithinTheirStandardErrors) {
  const auto& p = geaware_test::paperParams();
  for (std::uint64_t seed : {1u, 2u, 3u, 4u}) {
    const auto fit = fitRotorStand(ident_test::syntheticStand({}, seed), sweepOptions());
    SCOPED_TRACE(seed);
    EXPECT_TRUE(withinSigmas(fit.k_T_N_per_rpm2, p.rotor.k_T_N_per_rpm2));
    EXPECT_TRUE(withinSigmas(fit.k_I_Nm_per_rpm2, p.rotor.k_I_Nm_per_rpm2));
    ASSERT_TRUE(fit.J_R_kgm2.has_value());
    EXPECT_TRUE(withinSigmas(*fit.J_R_kgm2, p.rotor.J_R_kgm2));
    EXPECT_TRUE(withinSigmas(fit.c2_rpm2, p.throttle.c2_rpm2));
    EXPECT_TRUE(withinSigmas(fit.c1_rpm2, p.throttle.c1_rpm2));
    EXPECT_TRUE(withinSigmas(fit.c0_rpm2, p.throttle.c0_rpm2));
    EXPECT_NEAR(fit.thrust.residual_rms, 0.02, 0.002);
    EXPECT_TRUE(fit.warnings.empty()) << fit.warnings.front();
  }
}

TEST(RotorFit, StandardErrorsShrinkAsOneOverRootN) {
  ident_test::StandSpec shorter;
  shorter.duration_s = 5.0;
  const auto a = fitRotorStand(ident_test::syntheticStand(shorter, 5), sweepOptions());
  const auto b = fitRotorStand(ident_test::syntheticStand({}, 6), sweepOptions());  // 4× longer
  EXPECT_NEAR(a.k_T_N_per_rpm2.std_error / b.k_T_N_per_rpm2.std_error, 2.0, 0.25);
  EXPECT_NEAR(a.k_I_Nm_per_rpm2.std_error / b.k_I_Nm_per_rpm2.std_error, 2.0, 0.25);
}

TEST(RotorFit, SteadyStepsLeaveJROutWithAWarning) {
  // Ten held speeds across the throttle range, torque without any J_R·ṅ term.
  const auto& p = geaware_test::paperParams();
  const geaware::model::ThrottleCurve curve(p.throttle);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  geaware::ident::RotorStandLog log;
  log.source = "steps";
  for (int i = 0; i < 20000; ++i) {
    const double rpm = 4000.0 + 1500.0 * (i / 2000);
    log.t_s.push_back(0.001 * i);
    log.throttle.push_back(curve.throttle(rpm));
    log.rpm.push_back(rpm + 2.0 * noise(rng));
    log.thrust_N.push_back(p.rotor.k_T_N_per_rpm2 * rpm * rpm + 0.02 * noise(rng));
    log.torque_Nm.push_back(p.rotor.k_I_Nm_per_rpm2 * rpm * rpm + 0.003 * noise(rng));
  }
  const auto fit = fitRotorStand(log);
  EXPECT_FALSE(fit.J_R_kgm2.has_value());
  ASSERT_EQ(fit.warnings.size(), 1u);
  EXPECT_NE(fit.warnings.front().find("J_R not fitted"), std::string::npos) << fit.warnings.front();
  EXPECT_TRUE(withinSigmas(fit.k_I_Nm_per_rpm2, p.rotor.k_I_Nm_per_rpm2));
  // The default rate limit keeps the throttle curve on the steady samples.
  EXPECT_TRUE(withinSigmas(fit.c1_rpm2, p.throttle.c1_rpm2));
  EXPECT_TRUE(withinSigmas(fit.c0_rpm2, p.throttle.c0_rpm2));
}

TEST(RotorFit, AccelerationFromTheTimeSeries) {
  std::vector<double> t, n;
  for (int i = 0; i < 1000; ++i) {
    t.push_back(0.001 * i);
    n.push_back(5000.0 + 3000.0 * t.back() + 200.0 * t.back() * t.back());
  }
  const auto rate = geaware::ident::rotorAcceleration(t, n, 0.02);
  // Exact for a quadratic in the interior (a centred window's slope is the derivative).
  EXPECT_NEAR(rate[500], 3000.0 + 400.0 * t[500], 1e-6);
}

}  // namespace
