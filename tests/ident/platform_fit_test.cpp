// SPDX-License-Identifier: BSD-3-Clause
// Quadrotor platform, level board: k_T with F_G's g1, g2, and the mixing coefficients per
// height band, from synthetic logs of the controller-side model.

#include "geaware/ident/platform_fit.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "synthetic.hpp"

namespace {

using geaware::ident::fitAdditionalThrust;
using geaware::ident::fitMixing;
using ident_test::withinSigmas;

TEST(PlatformFit, AdditionalThrustWithinStandardErrorsForSeveralSeeds) {
  const auto& p = geaware_test::paperParams();
  ident_test::PlatformSpec spec;
  spec.tilted_samples = 0;
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
    SCOPED_TRACE(seed);
    const auto fit = fitAdditionalThrust(ident_test::syntheticPlatform(spec, seed));
    EXPECT_TRUE(withinSigmas(fit.k_T_N_per_rpm2, p.rotor.k_T_N_per_rpm2));
    EXPECT_TRUE(withinSigmas(fit.g1_m2, p.additional_thrust.g1_m2));
    EXPECT_TRUE(withinSigmas(fit.g2_m2, p.additional_thrust.g2_m2));
    EXPECT_NEAR(fit.stats.residual_rms, spec.sigma_force_N, 0.1 * spec.sigma_force_N);
    EXPECT_TRUE(fit.warnings.empty()) << fit.warnings.front();
  }
}

TEST(PlatformFit, AdditionalThrustErrorsShrinkAsOneOverRootN) {
  ident_test::PlatformSpec small;
  small.tilted_samples = 0;
  small.level_samples = 5000;
  ident_test::PlatformSpec large = small;
  large.level_samples = 20000;
  const auto a = fitAdditionalThrust(ident_test::syntheticPlatform(small, 8));
  const auto b = fitAdditionalThrust(ident_test::syntheticPlatform(large, 9));
  EXPECT_NEAR(a.g1_m2.std_error / b.g1_m2.std_error, 2.0, 0.3);
  EXPECT_NEAR(a.g2_m2.std_error / b.g2_m2.std_error, 2.0, 0.3);
}

TEST(PlatformFit, RobustLossIgnoresFivePercentGrossOutliers) {
  const auto& p = geaware_test::paperParams();
  ident_test::PlatformSpec spec;
  spec.tilted_samples = 0;
  spec.outlier_fraction = 0.05;
  const auto log = ident_test::syntheticPlatform(spec, 10);
  const auto fit = fitAdditionalThrust(log);
  EXPECT_TRUE(withinSigmas(fit.g1_m2, p.additional_thrust.g1_m2));
  EXPECT_TRUE(withinSigmas(fit.g2_m2, p.additional_thrust.g2_m2));
  EXPECT_TRUE(withinSigmas(fit.k_T_N_per_rpm2, p.rotor.k_T_N_per_rpm2));
  EXPECT_NEAR(static_cast<double>(fit.stats.outliers) / static_cast<double>(log.size()), 0.05, 0.01);
  // Without the robust scheme the same data give a visibly worse F_G.
  geaware::ident::PlatformFitOptions plain;
  plain.robust = {geaware::ident::RobustLoss::kNone, 1.0, 0.0};
  const auto bad = fitAdditionalThrust(log, plain);
  EXPECT_GT(std::abs(bad.g2_m2.value - p.additional_thrust.g2_m2),
            10.0 * std::abs(fit.g2_m2.value - p.additional_thrust.g2_m2));
}

TEST(PlatformFit, FittedCurveMatchesTheModelOverTheFlyableRange) {
  const auto& p = geaware_test::paperParams();
  const geaware::model::GroundEffectModel truth(p);
  ident_test::PlatformSpec spec;
  spec.tilted_samples = 0;
  const auto fit = fitAdditionalThrust(ident_test::syntheticPlatform(spec, 12));
  for (double h = 0.075; h <= 1.0; h += 0.025) {
    const double F = fit.g2_m2.value / (h * h + fit.g1_m2.value);
    EXPECT_NEAR(F, truth.thrustRatio(h), 4.0 * geaware::ident::additionalThrustStdError(fit, h))
        << "h = " << h;
  }
  // The paper's per-sample F̃_G with the true k_T scatters around the model.
  const auto log = ident_test::syntheticPlatform(spec, 13);
  const auto F = geaware::ident::measuredAdditionalThrust(log, p.rotor.k_T_N_per_rpm2);
  double mean_error = 0.0;
  for (std::size_t i = 0; i < log.size(); ++i) mean_error += F[i] - truth.thrustRatio(log.h_m[i]);
  EXPECT_NEAR(mean_error / static_cast<double>(log.size()), 0.0, 1e-4);
}

TEST(PlatformFit, MixingCoefficientsAndHeightBands) {
  const auto& p = geaware_test::paperParams();
  const geaware::model::GroundEffectModel truth(p);
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    const auto fit = fitMixing(ident_test::syntheticPlatform({}, seed), p.diagonal_rotor_distance_m);
    ASSERT_TRUE(fit.k_TX_N_per_rpm2 && fit.k_TY_N_per_rpm2 && fit.k_I_Nm_per_rpm2);
    EXPECT_TRUE(withinSigmas(*fit.k_TX_N_per_rpm2, p.rotor.k_TX_N_per_rpm2));
    EXPECT_TRUE(withinSigmas(*fit.k_TY_N_per_rpm2, p.rotor.k_TY_N_per_rpm2));
    EXPECT_TRUE(withinSigmas(*fit.k_I_Nm_per_rpm2, p.rotor.k_I_Nm_per_rpm2));
    ASSERT_GE(fit.bands.size(), 4u);
    // The effective k_T falls with height (about 30 % from the lowest band to the top), the
    // torque coefficients do not change (the model has no height dependence for them).
    for (std::size_t b = 0; b + 1 < fit.bands.size(); ++b) {
      EXPECT_GT(fit.bands[b].k_T_N_per_rpm2->value, fit.bands[b + 1].k_T_N_per_rpm2->value);
    }
    const double k_low = fit.bands.front().k_T_N_per_rpm2->value;
    EXPECT_GT(k_low / fit.k_T_top_N_per_rpm2.value - 1.0, 0.2);
    for (const auto& band : fit.bands) {
      EXPECT_TRUE(withinSigmas(*band.k_TX_N_per_rpm2, p.rotor.k_TX_N_per_rpm2));
      EXPECT_TRUE(withinSigmas(*band.k_I_Nm_per_rpm2, p.rotor.k_I_Nm_per_rpm2));
    }
    // The top band (1.5 and 2.0 m) sees k_T·(1 + F_G) with F_G < 0.4 %.
    EXPECT_NEAR(fit.k_T_top_N_per_rpm2.value / p.rotor.k_T_N_per_rpm2 - 1.0,
                truth.thrustRatio(fit.bands.back().h_mean_m), 1e-3);
  }
}

TEST(PlatformFit, NoMixingExperimentsMeansNoMixingCoefficients) {
  ident_test::PlatformSpec spec;
  spec.mixing_rpm = 0.0;
  spec.tilted_samples = 0;
  const auto fit = fitMixing(ident_test::syntheticPlatform(spec, 4), 0.35);
  EXPECT_FALSE(fit.k_TX_N_per_rpm2.has_value());
  EXPECT_FALSE(fit.k_I_Nm_per_rpm2.has_value());
  ASSERT_GE(fit.warnings.size(), 3u);
  EXPECT_NE(fit.warnings.front().find("k_TX not fitted"), std::string::npos) << fit.warnings.front();
}

TEST(PlatformFit, HeightsOutOfGroundEffectCannotConstrainFG) {
  ident_test::PlatformSpec spec;
  spec.tilted_samples = 0;
  spec.level_heights_m = {1.5, 2.0};
  const auto log = ident_test::syntheticPlatform(spec, 5);
  try {
    const auto fit = fitAdditionalThrust(log);
    ASSERT_FALSE(fit.warnings.empty());
    EXPECT_NE(fit.warnings.front().find("poorly constrained"), std::string::npos);
  } catch (const geaware::ident::IdentError& e) {
    EXPECT_NE(std::string(e.what()).find(log.source), std::string::npos) << e.what();
  }
  spec.level_samples = 5;
  EXPECT_THROW((void)fitAdditionalThrust(ident_test::syntheticPlatform(spec, 5)),
               geaware::ident::IdentError);
}

}  // namespace

namespace {

// The reported standard errors are honest: over 40 seeds the z-scores of g1 and g2 have unit
// variance (the mean of 40 z² lies in [0.47, 1.83] with probability 99.9 %).
TEST(PlatformFit, AdditionalThrustZScoresHaveUnitVariance) {
  const auto& p = geaware_test::paperParams();
  ident_test::PlatformSpec spec;
  spec.tilted_samples = 0;
  spec.level_samples = 2000;
  double z1 = 0.0;
  double z2 = 0.0;
  constexpr int kSeeds = 40;
  for (int s = 0; s < kSeeds; ++s) {
    const auto fit = fitAdditionalThrust(ident_test::syntheticPlatform(spec, 100 + static_cast<std::uint64_t>(s)));
    z1 += std::pow((fit.g1_m2.value - p.additional_thrust.g1_m2) / fit.g1_m2.std_error, 2);
    z2 += std::pow((fit.g2_m2.value - p.additional_thrust.g2_m2) / fit.g2_m2.std_error, 2);
  }
  EXPECT_GT(z1 / kSeeds, 0.47);
  EXPECT_LT(z1 / kSeeds, 1.83);
  EXPECT_GT(z2 / kSeeds, 0.47);
  EXPECT_LT(z2 / kSeeds, 1.83);
}

}  // namespace
