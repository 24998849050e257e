// SPDX-License-Identifier: BSD-3-Clause
// The in-flight ground-effect learner against closed forms: noise-free samples of a curve that
// is linear between the knots give it back exactly; noisy samples of the paper's F_G converge to
// it; knots without samples keep what they had (no drift without excitation); gates, bounds,
// forgetting and the parameter checks.

#include "geaware/control/ground_effect_learner.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "geaware/control/controller.hpp"
#include "geaware/model/vehicle_model.hpp"
#include "geaware_test/paper_vehicle.hpp"
#include "configurations.hpp"

namespace geaware::control {
namespace {

// The paper's closed form F_G(h) = g2/(h² + g1), with the built-in vehicle's order of magnitude.
double paperCurve(double h) { return 0.0073 / (h * h + 0.018); }

GroundEffectLearnerParams params() {
  GroundEffectLearnerParams p;
  return p;
}

std::vector<double> zeros(const GroundEffectLearnerParams& p) { return std::vector<double>(p.knots_m.size(), 0.0); }

TEST(GroundEffectLearner, NoiseFreeSamplesOfAPiecewiseLinearCurveGiveItBackExactly) {
  GroundEffectLearnerParams p = params();
  p.prior_sigma = 1e3;  // a prior with (almost) no weight
  p.forgetting = 1.0;
  GroundEffectLearner l(p, zeros(p));
  std::vector<double> truth;
  for (double h : p.knots_m) truth.push_back(paperCurve(h));
  // Two heights per interval determine its two knot values.
  for (int rep = 0; rep < 400; ++rep) {  // ≥ 200 samples' worth at the end knots
    for (std::size_t j = 0; j + 1 < p.knots_m.size(); ++j) {
      for (double t : {0.2, 0.7}) {
        const double h = p.knots_m[j] + t * (p.knots_m[j + 1] - p.knots_m[j]);
        const double y = (1.0 - t) * truth[j] + t * truth[j + 1];
        ASSERT_EQ(l.update(h, y, 0.0, 0.0, 0.0), LearnerSample::kUsed);
      }
    }
  }
  for (std::size_t k = 0; k < p.knots_m.size(); ++k) {
    EXPECT_NEAR(l.value(k), truth[k], 1e-6) << "knot " << k;
    EXPECT_TRUE(l.learned(k)) << k;
  }
  EXPECT_NEAR(l.ratio(0.11), 0.5 * (truth[1] + truth[2]), 1e-6);
}

TEST(GroundEffectLearner, NoisySamplesOfThePapersCurveConverge) {
  GroundEffectLearnerParams p = params();
  GroundEffectLearner l(p, zeros(p));  // no model at all to start from
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> height(p.knots_m.front(), p.knots_m.back());
  std::normal_distribution<double> noise(0.0, p.sample_sigma);
  for (int i = 0; i < 200000; ++i) {
    const double h = height(rng);
    (void)l.update(h, paperCurve(h) + noise(rng), 0.05, 0.3, 0.0);
  }
  // The curve is convex between knots, so the best line through an interval sits a little
  // above its knots: within 10 % (and 0.005) of the curve there, and the interpolated curve
  // within 15 % over 0.1–0.3 m.
  for (std::size_t k = 0; k < p.knots_m.size(); ++k) {
    const double f = paperCurve(p.knots_m[k]);
    EXPECT_NEAR(l.value(k), f, std::max(0.1 * f, 0.005)) << "knot " << p.knots_m[k] << " m";
  }
  for (double h = 0.1; h <= 0.3; h += 0.01) {
    EXPECT_NEAR(l.ratio(h), paperCurve(h), 0.15 * paperCurve(h)) << h;
  }
}

// In forward flight the cushion fades, v_i²/(v_i² + V²) (Cheeseman & Bennett). With the fade
// modelled, samples at 0–4 m/s (v_i = 4 m/s) of the faded curve give the static curve back; the
// gate is then the fade (≥ 0.5) instead of 1.5 m/s. Treated as static, the same samples would
// learn a curve 30 % low, which is why the speed gate stands without a fade model.
TEST(GroundEffectLearner, WithTheFadeModelledSamplesAtSpeedGiveTheStaticCurve) {
  GroundEffectLearnerParams p = params();
  GroundEffectLearner faded(p, zeros(p));
  GroundEffectLearner naive(p, zeros(p));
  p.max_speed_mps = 100.0;  // the naive learner takes every speed, as if there were no fade
  GroundEffectLearner ungated(p, zeros(p));
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> height(p.knots_m.front(), p.knots_m.back());
  std::uniform_real_distribution<double> speed(0.0, 4.0);
  std::normal_distribution<double> noise(0.0, p.sample_sigma);
  const double v_i = 4.0;
  std::size_t fast_used = 0;
  for (int i = 0; i < 200000; ++i) {
    const double h = height(rng);
    const double V = speed(rng);
    const double fade = v_i * v_i / (v_i * v_i + V * V);
    const double y = fade * paperCurve(h) + noise(rng);
    if (faded.update(h, y, 0.05, V, 0.0, fade) == LearnerSample::kUsed && V > 1.5) ++fast_used;
    const LearnerSample n = naive.update(h, y, 0.05, V, 0.0);
    if (V > 1.5) {
      ASSERT_EQ(n, LearnerSample::kFast);
    }
    (void)ungated.update(h, y, 0.05, V, 0.0);
  }
  EXPECT_GT(fast_used, 100000u);
  for (double h = 0.1; h <= 0.3; h += 0.01) {
    EXPECT_NEAR(faded.ratio(h), paperCurve(h), 0.15 * paperCurve(h)) << h;
    EXPECT_LT(ungated.ratio(h), 0.8 * paperCurve(h)) << h;
  }
  // Below the fade's floor a sample is gated whatever the speed says.
  EXPECT_EQ(faded.update(0.2, 0.1, 0.05, 0.5, 0.0, 0.45), LearnerSample::kFast);
  EXPECT_EQ(faded.update(0.2, 0.1, 0.05, 0.5, 0.0, std::nan("")), LearnerSample::kNonFinite);
}

TEST(GroundEffectLearner, KnotsWithoutNewSamplesDoNotDrift) {
  GroundEffectLearnerParams p = params();
  GroundEffectLearner l(p, zeros(p));
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> height(p.knots_m.front(), p.knots_m.back());
  std::normal_distribution<double> noise(0.0, p.sample_sigma);
  for (int i = 0; i < 50000; ++i) {
    const double h = height(rng);
    (void)l.update(h, paperCurve(h) + noise(rng), 0.0, 0.0, 0.0);
  }
  std::vector<double> before(l.values(), l.values() + l.knots());
  // A long hover at 0.30 m (interval 0.28–0.33 m, knots 7 and 8): 100 s at 1 kHz. The interval
  // forgets only its own past, so every other interval keeps its information and the knots
  // away from the hover stay where they were.
  for (int i = 0; i < 100000; ++i) (void)l.update(0.30, paperCurve(0.30) + noise(rng), 0.0, 0.0, 0.0);
  for (std::size_t k = 0; k < l.knots(); ++k) {
    if (k >= 6 && k <= 9) continue;
    EXPECT_NEAR(l.value(k), before[k], 1e-3) << "knot " << p.knots_m[k] << " m drifted";
  }
  // The same hover with an unmodelled +0.05 there, in the raw fit (a bump the monotone curve
  // would flatten): learned where it hovered, and passed on to the other knots only through the
  // intervals that join them, less at every step away.
  GroundEffectLearnerParams raw_params = p;
  raw_params.monotone = false;
  GroundEffectLearner biased(raw_params, zeros(p));
  for (int i = 0; i < 50000; ++i) {
    const double h = height(rng);
    (void)biased.update(h, paperCurve(h) + noise(rng), 0.0, 0.0, 0.0);
  }
  const GroundEffectLearner unbiased = biased;
  for (int i = 0; i < 100000; ++i) (void)biased.update(0.30, paperCurve(0.30) + 0.05 + noise(rng), 0.0, 0.0, 0.0);
  EXPECT_GT(biased.ratio(0.30), paperCurve(0.30) + 0.03);
  double previous = std::abs(biased.value(7) - unbiased.value(7));
  for (std::size_t k = 7; k-- > 3;) {
    const double change = std::abs(biased.value(k) - unbiased.value(k));
    EXPECT_LT(change, 0.6 * previous) << "knot " << p.knots_m[k] << " m";
    previous = change;
  }
  // Samples that are all gated out change nothing at all.
  const std::vector<double> now(l.values(), l.values() + l.knots());
  for (int i = 0; i < 1000; ++i) (void)l.update(0.15, 0.4, 0.6, 0.0, 0.0);  // tilted
  for (std::size_t k = 0; k < l.knots(); ++k) EXPECT_EQ(l.value(k), now[k]);
}

TEST(GroundEffectLearner, WithoutSamplesTheEstimateIsThePriorAndNothingIsLearned) {
  GroundEffectLearnerParams p = params();
  std::vector<double> prior;
  for (double h : p.knots_m) prior.push_back(paperCurve(h));
  GroundEffectLearner l(p, prior);
  for (std::size_t k = 0; k < l.knots(); ++k) {
    EXPECT_EQ(l.value(k), prior[k]);
    EXPECT_FALSE(l.learned(k));
    EXPECT_EQ(l.dataSamples(k), 0.0);
  }
  EXPECT_EQ(l.used(), 0u);
  // Samples only in the lowest interval leave the prior of knots two intervals away untouched
  // up to the coupling through knot 1.
  for (int i = 0; i < 5000; ++i) (void)l.update(0.09, paperCurve(0.09), 0.0, 0.0, 0.0);
  EXPECT_TRUE(l.learned(0));
  EXPECT_TRUE(l.learned(1));
  EXPECT_FALSE(l.learned(2));
  EXPECT_NEAR(l.value(5), prior[5], 1e-12);
}

TEST(GroundEffectLearner, GatesOutliersAndBounds) {
  GroundEffectLearnerParams p = params();
  p.monotone = false;  // the bounds alone
  GroundEffectLearner l(p, zeros(p));
  EXPECT_EQ(l.update(std::nan(""), 0.1, 0, 0, 0), LearnerSample::kNonFinite);
  EXPECT_EQ(l.update(0.2, INFINITY, 0, 0, 0), LearnerSample::kNonFinite);
  EXPECT_EQ(l.update(0.05, 0.1, 0, 0, 0), LearnerSample::kOutsideKnots);
  EXPECT_EQ(l.update(0.6, 0.1, 0, 0, 0), LearnerSample::kOutsideKnots);
  EXPECT_EQ(l.update(0.2, 5.0, 0, 0, 0), LearnerSample::kOutlier);
  EXPECT_EQ(l.update(0.2, 0.1, 0.5, 0, 0), LearnerSample::kTilted);
  EXPECT_EQ(l.update(0.2, 0.1, 0, 3.0, 0), LearnerSample::kFast);
  EXPECT_EQ(l.update(0.2, 0.1, 0, 0, -1.0), LearnerSample::kClimbing);
  EXPECT_EQ(l.used(), 0u);
  // Samples above the upper bound: the estimate stops at it; below zero: at zero.
  for (int i = 0; i < 5000; ++i) ASSERT_EQ(l.update(0.2, 1.9, 0, 0, 0), LearnerSample::kUsed);
  EXPECT_EQ(l.value(5), p.max_ratio);
  for (int i = 0; i < 20000; ++i) (void)l.update(0.45, -1.0, 0, 0, 0);
  EXPECT_EQ(l.value(10), 0.0);
  EXPECT_EQ(l.update(0.5, 0.0, 0, 0, 0), LearnerSample::kUsed) << "the last knot is inside";
}

TEST(GroundEffectLearner, AnOffsetSeenFarFromTheGroundIsNotLearnedAsGroundEffect) {
  // A vehicle 6 % heavier than its file: the flight estimate is −0.06 everywhere, plus F_G near
  // the ground. Far samples (≥ 0.8 m) find the offset; the curve is learned without it.
  GroundEffectLearnerParams p = params();
  p.prior_sigma = p.no_model_prior_sigma;  // no model to start from, as the controller's "+learn0"
  GroundEffectLearner l(p, zeros(p));
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, p.sample_sigma);
  // Far away the sample is the curve's tail plus the offset.
  for (int i = 0; i < 2000; ++i) {
    ASSERT_EQ(l.update(1.2, paperCurve(1.2) - 0.06 + noise(rng), 0, 0, 0), LearnerSample::kOffset);
  }
  // One far height alone cannot tell the tail θ_N·(h_N/h)² from the offset: the curve stays at
  // its bound (0) until samples among the knots come.
  EXPECT_EQ(l.ratio(0.3), 0.0);
  EXPECT_EQ(l.offsetSamples(), 2000u);
  EXPECT_EQ(l.used(), 0u);
  std::uniform_real_distribution<double> height(p.knots_m.front(), p.knots_m.back());
  for (int i = 0; i < 100000; ++i) {
    const double h = height(rng);
    (void)l.update(h, paperCurve(h) - 0.06 + noise(rng), 0, 0, 0);
  }
  for (double h = 0.1; h <= 0.3; h += 0.02) EXPECT_NEAR(l.ratio(h), paperCurve(h), 0.15 * paperCurve(h)) << h;
  EXPECT_NEAR(l.offset(), -0.06, 0.01);
}

// The ground effect never weakens as the ground comes closer. Learning from nothing with samples
// only at 0.20–0.30 m, the knots below (never reached, prior 0) take the value learned at the
// lowest height reached, not 0: an unexplored height near the ground is not taken for free air
// (a vehicle that believed so would hover above it and never learn it). Noisy data give a
// non-increasing curve.
TEST(GroundEffectLearner, TheCurveNeverDecreasesTowardsTheGround) {
  GroundEffectLearnerParams p = params();
  p.prior_sigma = p.no_model_prior_sigma;
  GroundEffectLearner l(p, zeros(p));
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> height(0.20, 0.30);
  std::normal_distribution<double> noise(0.0, p.sample_sigma);
  for (int i = 0; i < 20000; ++i) {
    const double h = height(rng);
    (void)l.update(h, paperCurve(h) + noise(rng), 0, 0, 0);
  }
  for (std::size_t k = 0; k + 1 < l.knots(); ++k) EXPECT_GE(l.value(k), l.value(k + 1)) << k;
  EXPECT_NEAR(l.ratio(0.2), paperCurve(0.2), 0.1 * paperCurve(0.2));
  for (std::size_t k = 0; k < 5; ++k) {  // 0.08–0.17 m: never reached
    EXPECT_FALSE(l.learned(k));
    EXPECT_NEAR(l.value(k), l.ratio(0.2), 0.01) << "knot " << p.knots_m[k] << " m";
  }
  // The raw fit leaves them at the prior.
  p.monotone = false;
  GroundEffectLearner raw(p, zeros(p));
  std::mt19937_64 again(11);
  for (int i = 0; i < 20000; ++i) {
    const double h = height(again);
    (void)raw.update(h, paperCurve(h) + noise(again), 0, 0, 0);
  }
  EXPECT_NEAR(raw.value(0), 0.0, 1e-3);
}

TEST(GroundEffectLearner, ForgettingFollowsAChange) {
  GroundEffectLearnerParams p = params();
  p.forgetting = 0.995;  // a memory of ~200 samples per interval
  p.prior_sigma = 1.0;   // no model to start from: the prior only regularises
  GroundEffectLearner l(p, zeros(p));
  for (int i = 0; i < 5000; ++i) (void)l.update(0.22, 0.10, 0, 0, 0);
  EXPECT_NEAR(l.ratio(0.22), 0.10, 2e-3);
  for (int i = 0; i < 3000; ++i) (void)l.update(0.22, 0.20, 0, 0, 0);
  EXPECT_NEAR(l.ratio(0.22), 0.20, 2e-3);
  // Without forgetting the same data leave it between the two.
  p.forgetting = 1.0;
  GroundEffectLearner m(p, zeros(p));
  for (int i = 0; i < 5000; ++i) (void)m.update(0.22, 0.10, 0, 0, 0);
  for (int i = 0; i < 3000; ++i) (void)m.update(0.22, 0.20, 0, 0, 0);
  EXPECT_NEAR(m.ratio(0.22), (5000 * 0.10 + 3000 * 0.20) / 8000.0, 2e-3);
}

TEST(GroundEffectLearner, InvalidParametersAreListed) {
  GroundEffectLearnerParams p = params();
  p.knots_m = {0.1, 0.1, 0.3};
  p.far_height_m = 0.2;
  p.forgetting = 1.5;
  p.sample_sigma = -1.0;
  p.min_ratio = 1.0;
  p.max_ratio = 0.5;
  try {
    GroundEffectLearner l(p, {0.0, 0.0});
    FAIL() << "no error";
  } catch (const model::InvalidParameters& e) {
    const std::string what = e.what();
    for (const char* key : {"knots_m[1]", "forgetting", "sample_sigma", "max_ratio", "prior", "far_height_m"}) {
      EXPECT_NE(what.find(key), std::string::npos) << key << " missing from: " << what;
    }
  }
  GroundEffectLearnerParams q = params();
  q.knots_m.assign(17, 0.0);
  for (std::size_t k = 0; k < q.knots_m.size(); ++k) q.knots_m[k] = 0.1 + 0.01 * static_cast<double>(k);
  EXPECT_THROW(GroundEffectLearner(q, zeros(q)), model::InvalidParameters);
  GroundEffectLearnerParams r = params();
  std::vector<double> nan_prior = zeros(r);
  nan_prior[3] = std::nan("");
  EXPECT_THROW(GroundEffectLearner(r, nan_prior), model::InvalidParameters);
}

// The learners' heights and torques are given for the paper's vehicle; a controller for another
// vehicle learns at the same heights over propeller radius, with torques in proportion to its
// weight × arm, and the paper's vehicle keeps them exactly.
TEST(GroundEffectLearner, AControllerCarriesTheLearnersOverToItsVehicle) {
  const ControllerParams p = geaware_test::named("recommended+learn");
  // The reference the learners' defaults are given for is the built-in vehicle.
  EXPECT_EQ(p.learner.reference_propeller_radius_m, geaware_test::paperParams().propeller_radius_m);
  EXPECT_EQ(p.leveling_learner.reference_mass_kg, geaware_test::paperParams().mass_kg);
  EXPECT_EQ(p.leveling_learner.reference_diagonal_m, geaware_test::paperParams().diagonal_rotor_distance_m);
  const Controller paper(geaware_test::paperVehicle(), p);
  ASSERT_NE(paper.learner(), nullptr);
  ASSERT_EQ(paper.learner()->knots(), p.learner.knots_m.size());
  for (std::size_t k = 0; k < p.learner.knots_m.size(); ++k) EXPECT_EQ(paper.learner()->knot_m(k), p.learner.knots_m[k]);
  EXPECT_EQ(paper.params().leveling_learner.min_regressor_Nm, p.leveling_learner.min_regressor_Nm);

  model::VehicleParams small = geaware_test::paperParams();  // a 3-inch vehicle of 250 g
  small.propeller_radius_m = 0.0381;
  small.diagonal_rotor_distance_m = 0.13;
  small.mass_kg = 0.25;
  small.inertia_kgm2 = {1.6e-4, 1.75e-4, 2.9e-4};
  small.rotor.k_T_N_per_rpm2 = 1.262e-9;
  small.throttle = {1.681e9, 2.46e8, 9.0e6};
  const Controller c(model::VehicleModel(small), p);
  const double s = 0.0381 / 0.089;
  for (std::size_t k = 0; k < p.learner.knots_m.size(); ++k) {
    EXPECT_NEAR(c.learner()->knot_m(k), p.learner.knots_m[k] * s, 1e-15);
  }
  EXPECT_NEAR(c.params().learner.far_height_m, 0.8 * s, 1e-15);
  const double q = (0.25 * 0.13) / (1.696 * 0.35);
  EXPECT_NEAR(c.params().leveling_learner.min_regressor_Nm, 0.004 * q, 1e-15);
  EXPECT_NEAR(c.params().leveling_learner.sample_sigma_Nm, 0.02 * q, 1e-15);
  // A reference radius of 0 keeps the heights as given.
  ControllerParams as_given = p;
  as_given.learner.reference_propeller_radius_m = 0.0;
  EXPECT_EQ(Controller(model::VehicleModel(small), as_given).learner()->knot_m(0), p.learner.knots_m[0]);
}

}  // namespace
}  // namespace geaware::control
