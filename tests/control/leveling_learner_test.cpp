// SPDX-License-Identifier: BSD-3-Clause
// The in-flight leveling-scale learner against closed forms: noise-free samples of
// y = s·x + b give s and b back; noisy ones converge; a level hover gives no sample and changes
// nothing; a constant tilt (a bias torque that looks like leveling from one direction) neither
// publishes a scale nor, after one was learned, moves it; a bias that shifts at one tilt moves it
// boundedly, and spread tilts bring it back; the gates,
// the bounds and the parameter checks.

#include "geaware/control/leveling_learner.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "geaware/model/vehicle_model.hpp"

namespace geaware::control {
namespace {

constexpr double kTilt = 0.05;   // [rad]
constexpr double kSpeed = 0.5;   // [m/s]
constexpr double kClimb = 0.1;   // [m/s]

/// A regressor that turns through every direction with magnitude 0.005–0.02 N·m, as a
/// lemniscate near the ground tilts the vehicle [N·m].
Eigen::Vector2d sweep(int i) {
  const double a = 0.013 * i;
  return (0.0125 + 0.0075 * std::sin(0.0071 * i)) * Eigen::Vector2d(std::cos(a), std::sin(a));
}

TEST(LevelingLearner, NoiseFreeSamplesGiveTheScaleAndTheBiasBack) {
  LevelingLearnerParams p;
  p.scale_walk_sigma = 0.0;
  p.bias_walk_sigma_Nm = 0.0;
  p.no_model_prior_sigma = 1e3;
  p.bias_sigma_Nm = 1e3;  // priors with (almost) no weight
  LevelingLearner l(p, 0.0);
  const double s = 0.62;
  const Eigen::Vector2d b(0.012, -0.031);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector2d x = sweep(i);
    ASSERT_EQ(l.update(x, s * x + b, kTilt, kSpeed, kClimb), LearnerSample::kUsed);
  }
  EXPECT_NEAR(l.estimate(), s, 1e-6);
  EXPECT_NEAR(l.bias_Nm().x(), b.x(), 1e-7);
  EXPECT_NEAR(l.bias_Nm().y(), b.y(), 1e-7);
  EXPECT_TRUE(l.learned());
  EXPECT_NEAR(l.scale(), s, 1e-6);
  EXPECT_EQ(l.used(), 2000u);
}

TEST(LevelingLearner, NoisySamplesConvergeAndOnlyThenIsTheScaleUsed) {
  LevelingLearnerParams p;
  LevelingLearner l(p, 0.0);  // no model to start from
  EXPECT_EQ(l.scale(), 0.0);
  EXPECT_FALSE(l.learned());
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, p.sample_sigma_Nm);
  const double s = 0.55;
  const Eigen::Vector2d b(-0.02, 0.015);
  int first_learned = -1;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector2d x = sweep(i);
    const Eigen::Vector2d y = s * x + b + Eigen::Vector2d(noise(rng), noise(rng));
    (void)l.update(x, y, kTilt, kSpeed, kClimb);
    if (first_learned < 0 && l.learned()) first_learned = i;
    if (first_learned < 0) {
      ASSERT_EQ(l.scale(), 0.0) << i;  // the prior until excited
    }
  }
  ASSERT_GT(first_learned, 10);  // not from the first samples
  EXPECT_LE(l.scaleSigma(), p.learned_sigma);
  EXPECT_NEAR(l.scale(), s, 0.05 * s);
  EXPECT_NEAR(l.bias_Nm().x(), b.x(), 0.003);
  EXPECT_NEAR(l.bias_Nm().y(), b.y(), 0.003);
}

/// A learner that has learned s = 0.6 with bias b from a well-excited phase.
LevelingLearner learned(const Eigen::Vector2d& b, const LevelingLearnerParams& p = {}) {
  LevelingLearner l(p, 1.0);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 0.02);
  for (int i = 0; i < 6000; ++i) {
    const Eigen::Vector2d x = sweep(i);
    (void)l.update(x, 0.6 * x + b + Eigen::Vector2d(noise(rng), noise(rng)), kTilt, kSpeed, kClimb);
  }
  EXPECT_TRUE(l.learned());
  EXPECT_NEAR(l.scale(), 0.6, 0.03);
  return l;
}

TEST(LevelingLearner, ALevelHoverGivesNoSampleAndChangesNothing) {
  LevelingLearner l = learned(Eigen::Vector2d(0.01, 0.0));
  const double scale = l.scale();
  const double estimate = l.estimate();
  const std::uint64_t used = l.used();
  // 100 s at 200 Hz, level (x ≈ 0 below the gate) with a torque the ground does not make.
  for (int i = 0; i < 20000; ++i) {
    ASSERT_EQ(l.update(Eigen::Vector2d(1e-4, -2e-4), Eigen::Vector2d(0.05, -0.03), kTilt, kSpeed, kClimb),
              LearnerSample::kUnexcited);
  }
  EXPECT_EQ(l.scale(), scale);
  EXPECT_EQ(l.estimate(), estimate);
  EXPECT_EQ(l.used(), used);
}

TEST(LevelingLearner, AConstantTiltNeverPublishesAScale) {
  // A bias torque of 0.03 N·m at a constant tilt: b + s·x = 0.03 cannot tell s from b. From the
  // file's M_G (prior 1) and from none (prior 0), 100 s of it leave the scale in use alone.
  for (const double prior : {1.0, 0.0}) {
    LevelingLearner l(LevelingLearnerParams{}, prior);
    std::mt19937_64 rng(5);
    std::normal_distribution<double> noise(0.0, 0.02);
    const Eigen::Vector2d x(0.012, 0.0);
    for (int i = 0; i < 20000; ++i) {
      ASSERT_EQ(l.update(x, Eigen::Vector2d(0.03 + noise(rng), noise(rng)), kTilt, kSpeed, kClimb),
                LearnerSample::kUsed);
    }
    EXPECT_FALSE(l.learned()) << prior;
    EXPECT_EQ(l.scale(), prior);
    EXPECT_GT(l.scaleSigma(), LevelingLearnerParams{}.learned_sigma) << prior;
    if (prior == 1.0) {
      // The file's prior keeps the estimate where it was: the biases take the torque. (From
      // no model, the weak prior lets the unused estimate take a share.)
      EXPECT_NEAR(l.estimate(), prior, 0.02);
      EXPECT_NEAR(l.bias_Nm().x(), 0.03 - 0.012 * prior, 0.002);
    }
  }
}

/// 200 s at 200 Hz at one tilt x = (0.012, 0.004) N·m, the truth s = 0.6 with bias b, noisy.
void holdOneTilt(LevelingLearner& l, const Eigen::Vector2d& b, std::mt19937_64& rng) {
  std::normal_distribution<double> noise(0.0, 0.02);
  const Eigen::Vector2d x(0.012, 0.004);
  for (int i = 0; i < 40000; ++i) {
    (void)l.update(x, 0.6 * x + b + Eigen::Vector2d(noise(rng), noise(rng)), kTilt, kSpeed, kClimb);
  }
}

TEST(LevelingLearner, AfterLearningALongConstantTiltDoesNotMoveTheScale) {
  // 200 s at one tilt with the same torques as before: the scale stays (the data there say
  // nothing new about it, and it hardly walks).
  LevelingLearner l = learned(Eigen::Vector2d(0.01, 0.0));
  const double before = l.scale();
  std::mt19937_64 rng(9);
  holdOneTilt(l, Eigen::Vector2d(0.01, 0.0), rng);
  EXPECT_NEAR(l.scale(), before, 0.02 * before);
}

TEST(LevelingLearner, ABiasThatShiftsAtOneTiltMovesTheScaleBoundedlyAndTheSpreadBringsItBack) {
  // The bias torque steps by 0.01 N·m (a CoG moved 0.6 mm by a shifting battery) while the
  // tilt holds: b + s·x alone cannot tell which moved. The biases walk faster than the scale,
  // so most of the step goes to the bias; the rest moves s by less than 15 %. A minute of
  // spread tilts afterwards puts s back within 3 %.
  LevelingLearner l = learned(Eigen::Vector2d(0.01, 0.0));
  const double before = l.scale();
  std::mt19937_64 rng(9);
  const Eigen::Vector2d b(0.02, 0.0);
  holdOneTilt(l, b, rng);
  std::normal_distribution<double> noise(0.0, 0.02);
  EXPECT_NEAR(l.scale(), before, 0.15 * before);
  EXPECT_NEAR(l.bias_Nm().x() + 0.012 * l.estimate(), b.x() + 0.012 * 0.6, 0.002);
  for (int i = 0; i < 12000; ++i) {
    const Eigen::Vector2d xi = sweep(i);
    (void)l.update(xi, 0.6 * xi + b + Eigen::Vector2d(noise(rng), noise(rng)), kTilt, kSpeed, kClimb);
  }
  EXPECT_NEAR(l.scale(), 0.6, 0.03 * 0.6);
  EXPECT_NEAR(l.bias_Nm().x(), b.x(), 0.002);
}

TEST(LevelingLearner, GatesAndBounds) {
  LevelingLearnerParams p;
  LevelingLearner l(p, 1.0);
  const Eigen::Vector2d x(0.01, 0.0), y(0.01, 0.0);
  const double nan = std::nan("");
  EXPECT_EQ(l.update(Eigen::Vector2d(nan, 0.0), y, kTilt, kSpeed, kClimb), LearnerSample::kNonFinite);
  EXPECT_EQ(l.update(x, Eigen::Vector2d(0.0, nan), kTilt, kSpeed, kClimb), LearnerSample::kNonFinite);
  EXPECT_EQ(l.update(x, y, nan, kSpeed, kClimb), LearnerSample::kNonFinite);
  EXPECT_EQ(l.update(x, Eigen::Vector2d(0.0, 0.6), kTilt, kSpeed, kClimb), LearnerSample::kOutlier);
  EXPECT_EQ(l.update(x, y, 0.4, kSpeed, kClimb), LearnerSample::kTilted);
  EXPECT_EQ(l.update(x, y, kTilt, 1.6, kClimb), LearnerSample::kFast);
  EXPECT_EQ(l.update(x, y, kTilt, kSpeed, -0.6), LearnerSample::kClimbing);
  EXPECT_EQ(l.update(Eigen::Vector2d(0.003, 0.0), y, kTilt, kSpeed, kClimb), LearnerSample::kUnexcited);
  EXPECT_EQ(l.used(), 0u);
  EXPECT_EQ(l.scale(), 1.0);
  // A scale beyond the bounds is used at the bound.
  LevelingLearner big(p, 1.0);
  for (int i = 0; i < 6000; ++i) {
    const Eigen::Vector2d xi = sweep(i);
    (void)big.update(xi, 8.0 * xi, kTilt, kSpeed, kClimb);
  }
  EXPECT_GT(big.estimate(), p.max_scale);
  EXPECT_EQ(big.scale(), p.max_scale);
  LevelingLearner negative(p, 1.0);
  for (int i = 0; i < 6000; ++i) {
    const Eigen::Vector2d xi = sweep(i);
    (void)negative.update(xi, -0.5 * xi, kTilt, kSpeed, kClimb);
  }
  EXPECT_EQ(negative.scale(), p.min_scale);
}

TEST(LevelingLearner, InvalidParametersAreRefusedByName) {
  LevelingLearnerParams p;
  p.scale_walk_sigma = -1.0;
  p.min_scale = 2.0;
  p.max_scale = 1.0;
  p.min_regressor_Nm = -1.0;
  try {
    LevelingLearner l(p, 1.0);
    FAIL() << "accepted";
  } catch (const model::InvalidParameters& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("scale_walk_sigma"), std::string::npos) << what;
    EXPECT_NE(what.find("max_scale"), std::string::npos) << what;
    EXPECT_NE(what.find("min_regressor_Nm"), std::string::npos) << what;
  }
  EXPECT_THROW(LevelingLearner(LevelingLearnerParams{}, std::nan("")), model::InvalidParameters);
}

}  // namespace
}  // namespace geaware::control
