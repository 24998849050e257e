// SPDX-License-Identifier: BSD-3-Clause
// Quadrotor platform, tilted board: the leveling-torque shape (g3, g4) and scale.

#include "geaware/ident/leveling_fit.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "synthetic.hpp"

namespace {

using geaware::ident::fitLeveling;
using geaware::ident::LevelingInputs;
using ident_test::withinSigmas;

LevelingInputs truthInputs() {
  const auto& p = geaware_test::paperParams();
  return {p.rotor.k_T_N_per_rpm2, p.rotor.k_TY_N_per_rpm2, p.diagonal_rotor_distance_m};
}

ident_test::PlatformSpec tiltedOnly() {
  ident_test::PlatformSpec spec;
  spec.level_samples = 0;
  return spec;
}

TEST(LevelingFit, RecoversShapeAndScaleWithinStandardErrorsForSeveralSeeds) {
  const auto& lt = geaware_test::paperParams().leveling_torque;
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
    SCOPED_TRACE(seed);
    const auto fit = fitLeveling(ident_test::syntheticPlatform(tiltedOnly(), seed), truthInputs());
    EXPECT_TRUE(withinSigmas(fit.g3_m, lt.g3_m));
    EXPECT_TRUE(withinSigmas(fit.g4_m2, lt.g4_m2));
    EXPECT_TRUE(withinSigmas(fit.scale_m4, lt.scale_m4));
    EXPECT_NEAR(fit.peak_height_m, geaware::model::GroundEffectModel(geaware_test::paperParams()).levelingPeakHeight(), 0.01);
    EXPECT_NEAR(fit.stats.residual_rms, 0.002, 0.0002);
    EXPECT_TRUE(fit.warnings.empty()) << fit.warnings.front();
  }
}

TEST(LevelingFit, CurveWithinTenPercentOverTheRoundTripRange) {
  const auto& p = geaware_test::paperParams();
  const geaware::model::GroundEffectModel truth(p);
  const auto fit = fitLeveling(ident_test::syntheticPlatform(tiltedOnly(), 6), truthInputs());
  for (double h = 0.1; h <= 0.35; h += 0.01) {
    const double M = geaware::ident::levelingCoefficient(fit.g3_m.value, fit.g4_m2.value,
                                                         fit.scale_m4.value, h);
    EXPECT_NEAR(M, truth.levelingCoefficient(h), 0.1 * truth.levelingCoefficient(h)) << h;
    EXPECT_NEAR(M, truth.levelingCoefficient(h),
                4.0 * geaware::ident::levelingCoefficientStdError(fit, h)) << h;
  }
}

TEST(LevelingFit, RobustLossIgnoresFivePercentGrossOutliers) {
  const auto& lt = geaware_test::paperParams().leveling_torque;
  auto spec = tiltedOnly();
  spec.outlier_fraction = 0.05;
  const auto fit = fitLeveling(ident_test::syntheticPlatform(spec, 7), truthInputs());
  EXPECT_TRUE(withinSigmas(fit.g3_m, lt.g3_m));
  EXPECT_TRUE(withinSigmas(fit.g4_m2, lt.g4_m2));
  EXPECT_TRUE(withinSigmas(fit.scale_m4, lt.scale_m4));
}

TEST(LevelingFit, TiltLimitIsAnOption) {
  auto spec = tiltedOnly();
  spec.tilts_deg = {5.0, 15.0};
  const auto log = ident_test::syntheticPlatform(spec, 8);
  const auto fit = fitLeveling(log, truthInputs());
  EXPECT_EQ(fit.tilt_max_deg, 5.0);
  EXPECT_LT(fit.stats.count + fit.stats.outliers, log.size());
  geaware::ident::LevelingFitOptions all;
  all.max_tilt_deg = 20.0;
  EXPECT_EQ(fitLeveling(log, truthInputs(), all).tilt_max_deg, 15.0);
}

TEST(LevelingFit, WrongSignConventionIsAnError) {
  const auto log = ident_test::syntheticPlatform(tiltedOnly(), 9);
  geaware::ident::LevelingFitOptions o;
  o.torque_sign = +1.0;
  try {
    (void)fitLeveling(log, truthInputs(), o);
    ADD_FAILURE();
  } catch (const geaware::ident::IdentError& e) {
    EXPECT_NE(std::string(e.what()).find("sign"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)fitLeveling(ident_test::syntheticPlatform({1000, 0}, 9), truthInputs()),
               geaware::ident::IdentError);  // no tilted samples
}

}  // namespace
