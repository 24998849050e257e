// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Training of the Neural-Lander residual network (Shi et al. 2019 §IV): mini-batch Adam on the
// mean squared error of the residual force, with spectral normalisation of every layer after
// every step so that the trained network is γ-Lipschitz. Deterministic: the same set, options
// and seed give bit-identical weights on the same build.
//
// The optimiser and back-propagation are dlib's (dlib::adam, dlib's dense and ReLU layers);
// initialisation, shuffling, the spectral projection and the export to NetworkWeights are ours
// (see trainer.cpp for why). Pure computation: no I/O; save the result with weights_file.hpp.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "geaware/control/residual_force.hpp"
#include "geaware/model/field_error.hpp"
#include "geaware/neural/residual_network.hpp"

namespace geaware::neural {

/// Training rows: raw features (makeFeatures()) and the measured residual force f_W [N].
class TrainingSet {
 public:
  /// Adds one row; returns false and adds nothing when a feature or the label is not finite.
  [[nodiscard]] bool add(const control::ResidualFeatures& f, const Eigen::Vector3d& force_W);
  [[nodiscard]] bool add(const FeatureVector& x, const Eigen::Vector3d& force_W);

  [[nodiscard]] std::size_t size() const noexcept { return features_.size(); }
  [[nodiscard]] const std::vector<FeatureVector>& features() const noexcept { return features_; }
  [[nodiscard]] const std::vector<Eigen::Vector3d>& labels() const noexcept { return labels_; }

 private:
  std::vector<FeatureVector> features_;
  std::vector<Eigen::Vector3d> labels_;
};

/// Most hidden layers train() supports (dlib networks have their depth fixed at compile time;
/// each supported depth is one instantiation).
inline constexpr int kMaxHiddenLayers = 4;

struct TrainOptions {
  /// Neurons per hidden layer: 1..kMaxHiddenLayers layers, each 1..kMaxWidth wide [-].
  std::vector<int> hidden_widths = {32, 32};
  int epochs = 300;             ///< passes over the training rows [-]
  int batch_size = 64;          ///< rows per Adam step [-]
  double learning_rate = 1e-3;  ///< Adam step size (β₁ = 0.9, β₂ = 0.999) [-]
  double weight_decay = 0.0;    ///< L2 penalty on the weights (dlib's Adam) [-]
  /// Project every layer after every step (Shi et al.); off only for comparisons.
  bool spectral_normalisation = true;
  /// γ: the network is γ-Lipschitz in the standardised features, each layer getting
  /// ‖W_l‖₂ ≤ γ^(1/L) [N per standard deviation of a feature].
  double lipschitz_gamma = 4.0;
  int power_iterations = 1;          ///< power-iteration steps per training step, warm-started [-]
  double validation_fraction = 0.2;  ///< share of rows held out, in [0, 0.9] [-]
  /// Floor on each feature's σ in raw feature units [m, m/s, -, rpm/1e4]: a feature nearly
  /// constant in the data (e.g. the attitude in hover-only logs) must not be blown up at run
  /// time by a tiny σ.
  double min_input_std = 0.05;
  std::uint64_t seed = 1;  ///< initialisation, split and shuffling

  /// Every offending field with its value; empty when valid.
  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

struct TrainResult {
  NetworkWeights weights;               ///< the trained network (γ set iff spectral normalisation)
  std::vector<double> train_loss;       ///< after each epoch: mean squared error per force
                                        ///< component on the training rows [N²]
  std::vector<double> validation_loss;  ///< same on the held-out rows (empty without them) [N²]
  std::size_t train_rows = 0;
  std::size_t validation_rows = 0;
};

/// Called after each epoch with (epoch from 1, training loss, validation loss or NaN) [N²].
using EpochCallback = std::function<void(int, double, double)>;

/// Trains a network on `set`. Throws std::invalid_argument naming every invalid option, or when
/// the set is too small to hold at least one training row (and one validation row if asked).
[[nodiscard]] TrainResult train(const TrainingSet& set, const TrainOptions& options,
                                const EpochCallback& on_epoch = {});

/// Mean squared error per force component of `weights` on `set` [N²]; NaN for an empty set.
/// Checks dimensions and finiteness (throws InvalidNetwork) but not γ.
[[nodiscard]] double meanSquaredError(const NetworkWeights& weights, const TrainingSet& set);

}  // namespace geaware::neural
