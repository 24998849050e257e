// SPDX-License-Identifier: BSD-3-Clause
// Training: the network learns a known residual, spectral normalisation holds the Lipschitz
// bound (and training without it breaks the bound, so the check can fail), determinism, and
// validation of options and data.

#include "geaware/neural/trainer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "synthetic_residual.hpp"

namespace geaware::neural {
namespace {

using geaware_test::SyntheticResidual;

/// Options small enough for a unit test (~1 s for 3,000 rows) and large enough to learn the
/// target: with these the validation MSE is ≈ 0.2 % of the label variance and the RMS error on
/// fresh rows ≈ 0.04 N, so the thresholds below leave a margin of about 3–5×.
TrainOptions quickOptions() {
  TrainOptions o;
  o.hidden_widths = {32, 32};
  o.epochs = 100;
  o.batch_size = 32;
  o.learning_rate = 3e-3;
  o.lipschitz_gamma = 30.0;  // the target's steepest slope is ≈ 12 N per σ_h near h = 0.1 m
  o.validation_fraction = 0.2;
  o.seed = 42;
  return o;
}

double labelVariance(const TrainingSet& set) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& y : set.labels()) mean += y;
  mean /= static_cast<double>(set.size());
  double var = 0.0;
  for (const auto& y : set.labels()) var += (y - mean).squaredNorm();
  return var / (3.0 * static_cast<double>(set.size()));
}

bool bitIdentical(const NetworkWeights& a, const NetworkWeights& b) {
  if (a.layers.size() != b.layers.size()) return false;
  for (std::size_t l = 0; l < a.layers.size(); ++l) {
    if (a.layers[l].weights != b.layers[l].weights || a.layers[l].bias != b.layers[l].bias) {
      return false;
    }
  }
  return a.input_mean == b.input_mean && a.input_std == b.input_std;
}

TEST(Trainer, LearnsGroundEffectAndDragResidual) {
  const SyntheticResidual target;
  const TrainingSet set = target.makeSet(3000, 1);
  const TrainResult r = train(set, quickOptions());
  ASSERT_EQ(r.train_loss.size(), 100u);
  ASSERT_EQ(r.validation_loss.size(), 100u);
  EXPECT_EQ(r.train_rows + r.validation_rows, 3000u);
  EXPECT_EQ(r.validation_rows, 600u);

  // Validation error against the spread of the labels: the network explains > 99 % of the
  // variance (a constant predictor explains 0 %).
  const double var = labelVariance(set);
  EXPECT_LT(r.validation_loss.back(), 0.01 * var)
      << "validation MSE " << r.validation_loss.back() << " N², label variance " << var << " N²";
  EXPECT_LT(r.train_loss.back(), 0.2 * r.train_loss.front());

  // On fresh rows from the same distribution, with the controller-facing interface: RMS error
  // below 0.1 N, where the ground-effect force reaches ≈ 4 N at h = 0.1 m.
  const ResidualNetwork net(r.weights);
  std::mt19937_64 rng(99);
  double se = 0.0;
  const int n = 500;
  for (int i = 0; i < n; ++i) {
    const auto f = target.sample(rng);
    se += (net.predict_W(f) - target.force_W(f)).squaredNorm();
  }
  EXPECT_LT(std::sqrt(se / (3.0 * n)), 0.1);

  // The ground effect itself: near the ground at hover speed, the vertical force is learned.
  control::ResidualFeatures hover;
  hover.height_m = 0.15;
  hover.rotor_speeds_rpm.setConstant(10200.0);
  EXPECT_NEAR(net.predict_W(hover).z(), target.force_W(hover).z(), 0.25);
}

TEST(Trainer, SpectralNormalisationHoldsTheLipschitzBound) {
  // γ = 1 is far below what the target needs (≈ 12): without the projection the trained
  // network's bound exceeds it, with the projection it cannot.
  const SyntheticResidual target;
  const TrainingSet set = target.makeSet(1000, 2);
  TrainOptions o = quickOptions();
  o.epochs = 20;
  o.lipschitz_gamma = 1.0;

  o.spectral_normalisation = true;
  const TrainResult bounded = train(set, o);
  ASSERT_TRUE(bounded.weights.lipschitz_gamma.has_value());
  EXPECT_EQ(*bounded.weights.lipschitz_gamma, 1.0);
  const double bound = lipschitzBound(bounded.weights.layers);  // exact, by SVD
  EXPECT_LE(bound, 1.0 * (1.0 + kLipschitzTolerance));
  EXPECT_NO_THROW(ResidualNetwork{bounded.weights});  // the certificate is checked there too

  o.spectral_normalisation = false;
  const TrainResult free = train(set, o);
  EXPECT_FALSE(free.weights.lipschitz_gamma.has_value());
  EXPECT_GT(lipschitzBound(free.weights.layers), 2.0);
}

TEST(Trainer, BoundHoldsForEveryDepth) {
  const SyntheticResidual target;
  const TrainingSet set = target.makeSet(300, 3);
  for (int depth = 1; depth <= kMaxHiddenLayers; ++depth) {
    TrainOptions o = quickOptions();
    o.hidden_widths.assign(static_cast<std::size_t>(depth), 16);
    o.epochs = 3;
    o.lipschitz_gamma = 2.0;
    const TrainResult r = train(set, o);
    ASSERT_EQ(r.weights.layers.size(), static_cast<std::size_t>(depth + 1));
    EXPECT_EQ(r.weights.layers.front().weights.cols(), kFeatureCount);
    EXPECT_EQ(r.weights.layers.back().weights.rows(), kOutputCount);
    for (int l = 0; l < depth; ++l) {
      EXPECT_EQ(r.weights.layers[static_cast<std::size_t>(l)].weights.rows(), 16);
    }
    EXPECT_LE(lipschitzBound(r.weights.layers), 2.0 * (1.0 + kLipschitzTolerance))
        << depth << " hidden layers";
  }
}

TEST(Trainer, SameSeedGivesBitIdenticalWeights) {
  const SyntheticResidual target;
  const TrainingSet set = target.makeSet(400, 4);
  TrainOptions o = quickOptions();
  o.epochs = 5;
  const TrainResult a = train(set, o);
  const TrainResult b = train(set, o);
  EXPECT_TRUE(bitIdentical(a.weights, b.weights));
  EXPECT_EQ(a.train_loss, b.train_loss);
  EXPECT_EQ(a.validation_loss, b.validation_loss);
  o.seed = 43;
  const TrainResult c = train(set, o);
  EXPECT_FALSE(bitIdentical(a.weights, c.weights));
}

TEST(Trainer, StandardisationComesFromTrainingRowsWithAFloor) {
  // All rows level and hovering: the attitude and rotor features are constant, so their σ is
  // the floor, not 0 (which would blow up any run-time deviation).
  TrainingSet set;
  for (int i = 0; i < 50; ++i) {
    control::ResidualFeatures f;
    f.height_m = 0.1 + 0.02 * i;
    f.rotor_speeds_rpm.setConstant(10000.0);
    ASSERT_TRUE(set.add(f, Eigen::Vector3d(0.0, 0.0, 1.0 / f.height_m)));
  }
  TrainOptions o = quickOptions();
  o.epochs = 1;
  o.validation_fraction = 0.0;
  o.min_input_std = 0.05;
  const TrainResult r = train(set, o);
  EXPECT_TRUE(r.validation_loss.empty());
  EXPECT_NEAR(r.weights.input_mean(0), 0.1 + 0.02 * 24.5, 1e-12);
  EXPECT_NEAR(r.weights.input_std(0), 0.02 * std::sqrt((50.0 * 50.0 - 1.0) / 12.0), 1e-12);
  EXPECT_EQ(r.weights.input_std(4), 0.05);   // R00 = 1 throughout
  EXPECT_EQ(r.weights.input_std(13), 0.05);  // rotor 1 at 1.0 throughout
}

TEST(Trainer, RejectsInvalidOptionsNamingThem) {
  const TrainingSet set = SyntheticResidual{}.makeSet(100, 5);
  TrainOptions o = quickOptions();
  o.hidden_widths = {32, 0};
  o.learning_rate = -1.0;
  o.lipschitz_gamma = std::numeric_limits<double>::infinity();
  try {
    static_cast<void>(train(set, o));
    FAIL() << "accepted invalid options";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("hidden_widths[1]"), std::string::npos) << what;
    EXPECT_NE(what.find("learning_rate"), std::string::npos) << what;
    EXPECT_NE(what.find("lipschitz_gamma"), std::string::npos) << what;
  }
  o = quickOptions();
  o.hidden_widths = {8, 8, 8, 8, 8};
  EXPECT_FALSE(o.validate().empty());
}

TEST(Trainer, RejectsTooSmallSetsAndNonFiniteRows) {
  TrainingSet set;
  control::ResidualFeatures f;
  EXPECT_FALSE(set.add(f, Eigen::Vector3d(std::nan(""), 0.0, 0.0)));
  f.v_W.x() = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(set.add(f, Eigen::Vector3d::Zero()));
  EXPECT_EQ(set.size(), 0u);
  f.v_W.x() = 0.0;
  EXPECT_TRUE(set.add(f, Eigen::Vector3d::Zero()));
  TrainOptions o = quickOptions();  // 20 % of 1 row is no validation row
  EXPECT_THROW(static_cast<void>(train(set, o)), std::invalid_argument);
  o.validation_fraction = 0.0;
  EXPECT_NO_THROW(static_cast<void>(train(set, o)));
}

TEST(Trainer, MeanSquaredErrorOfAConstantNetwork) {
  // A network whose output is its last bias: MSE is the mean of (b − y)² per component.
  NetworkWeights w;
  w.layers = {DenseLayer{Eigen::MatrixXd::Zero(1, kFeatureCount), Eigen::VectorXd::Zero(1)},
              DenseLayer{Eigen::MatrixXd::Zero(3, 1), Eigen::Vector3d(1.0, 0.0, 0.0)}};
  TrainingSet set;
  ASSERT_TRUE(set.add(FeatureVector::Zero(), Eigen::Vector3d(0.0, 0.0, 0.0)));
  ASSERT_TRUE(set.add(FeatureVector::Zero(), Eigen::Vector3d(1.0, 3.0, 0.0)));
  // Errors: (1,0,0) and (0,−3,0): (1 + 9) / 6.
  EXPECT_NEAR(meanSquaredError(w, set), 10.0 / 6.0, 1e-15);
}

}  // namespace
}  // namespace geaware::neural
