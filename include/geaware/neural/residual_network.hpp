// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The Neural-Lander residual-force network (Shi et al. 2019, "Neural Lander: Stable Drone
// Landing Control using Learned Dynamics", ICRA 2019): a ReLU multilayer perceptron
//   f̂(x) = W_L·φ(… φ(W_1·x̄ + b_1) …) + b_L,   φ = ReLU,   x̄ = (x − μ) ⊘ σ,
// whose weight matrices are spectrally normalised during training so that ‖W_l‖₂ ≤ γ^(1/L)
// and the whole map is γ-Lipschitz in the standardised features x̄ (Shi et al. §IV-B).
//
// Inference only: pure Eigen, no I/O. Training is in trainer.hpp, the weight file in
// weights_file.hpp. Design notes, the feature layout and the file format: docs/neural-lander.md.

#include <Eigen/Core>
#include <array>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "geaware/control/residual_force.hpp"
#include "geaware/model/field_error.hpp"
#include "geaware/neural/spectral_norm.hpp"

namespace geaware::neural {

/// Number of features: h (1), v_W (3), R_WB row-major (9), rotor speeds / 1e4 (4).
inline constexpr int kFeatureCount = 17;
/// Number of outputs: the residual force f_W [N].
inline constexpr int kOutputCount = 3;
/// Widest layer inference supports; activations live on the stack up to this width.
inline constexpr int kMaxWidth = 256;
/// Most dense layers (hidden + output) a network may have.
inline constexpr int kMaxLayers = 8;
/// Rotor speeds enter the features as rpm / kRotorSpeedScaleRpm, so that all raw features are
/// O(1) before standardisation.
inline constexpr double kRotorSpeedScaleRpm = 1e4;

using FeatureVector = Eigen::Matrix<double, kFeatureCount, 1>;

/// Feature names in vector order, as written in the weight file.
[[nodiscard]] const std::array<std::string_view, kFeatureCount>& featureNames() noexcept;

/// Raw (not standardised) feature vector of one sample:
/// [h, v_x, v_y, v_z, R00, R01, R02, R10, …, R22, n1/1e4, …, n4/1e4] with R = R_WB of the
/// normalised quaternion (NaN entries for a zero quaternion). Shi et al. feed the attitude as a
/// quaternion; we use the rotation matrix because q and −q are the same attitude, so a quaternion
/// input makes the learned map discontinuous (or doubles the data it needs) and its Lipschitz bound
/// meaningless across the sign flip. R is unique and continuous in the attitude.
[[nodiscard]] FeatureVector makeFeatures(const control::ResidualFeatures& f) noexcept;

/// One affine layer y = W·x + b.
struct DenseLayer {
  Eigen::MatrixXd weights;  ///< W, outputs × inputs [N per standardised unit on the last layer]
  Eigen::VectorXd bias;     ///< b, outputs
};

/// Everything that defines a trained network. Plain data; ResidualNetwork validates it.
struct NetworkWeights {
  /// Input → output. ReLU after every layer except the last, whose output is f_W [N].
  std::vector<DenseLayer> layers;
  FeatureVector input_mean = FeatureVector::Zero();  ///< μ, subtracted from the raw features
  FeatureVector input_std = FeatureVector::Ones();   ///< σ (> 0), divides the centred features
  /// γ that spectral normalisation enforced: ∏‖W_l‖₂ ≤ γ [N per standardised unit]. Empty for
  /// a network trained without it (no bound is claimed).
  std::optional<double> lipschitz_gamma;

  /// Every problem, each naming its field ("layers[1].weights") and value; empty when valid.
  /// Checks the chain of dimensions (17 → … → 3, each width ≤ kMaxWidth), finiteness, σ > 0,
  /// γ > 0 and, when γ is set, that the exact bound ∏σ_max(W_l) ≤ γ·(1 + kLipschitzTolerance).
  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

/// Product of the exact spectral norms of the layers: an upper bound on the network's Lipschitz
/// constant in the standardised features (ReLU is 1-Lipschitz; biases do not count).
[[nodiscard]] double lipschitzBound(const std::vector<DenseLayer>& layers);

/// Thrown when a network is built from weights that fail NetworkWeights::validate().
class InvalidNetwork : public std::invalid_argument {
 public:
  explicit InvalidNetwork(std::vector<model::FieldError> errors);
  [[nodiscard]] const std::vector<model::FieldError>& errors() const noexcept { return errors_; }

 private:
  std::vector<model::FieldError> errors_;
};

/// The residual-force model the controller's `neural` acceleration compensation calls.
class ResidualNetwork final : public control::ResidualForceModel {
 public:
  /// Validates; throws InvalidNetwork listing every problem.
  explicit ResidualNetwork(NetworkWeights weights);

  /// f̂_W [N]. No allocation (activations on the stack). A non-finite feature or output gives
  /// zero, i.e. no compensation, rather than a NaN for the controller.
  [[nodiscard]] Eigen::Vector3d predict_W(
      const control::ResidualFeatures& f) const noexcept override;

  /// Same from a raw feature vector (makeFeatures()).
  [[nodiscard]] Eigen::Vector3d predictFeatures(const FeatureVector& x) const noexcept;

  /// ∏σ_max(W_l), computed exactly by SVD at construction.
  [[nodiscard]] double lipschitzBound() const noexcept { return lipschitz_bound_; }

  [[nodiscard]] const NetworkWeights& weights() const noexcept { return weights_; }

 private:
  NetworkWeights weights_;
  FeatureVector inv_std_;  ///< 1/σ, so inference multiplies
  double lipschitz_bound_;
};

}  // namespace geaware::neural
