// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/neural/residual_network.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "geaware/model/field_check.hpp"

namespace geaware::neural {
namespace {

/// Activations of one layer: dynamic size up to kMaxWidth, storage on the stack, so inference
/// never touches the heap.
using Activation = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxWidth, 1>;

std::string shape(Eigen::Index rows, Eigen::Index cols) {
  return std::to_string(rows) + "x" + std::to_string(cols);
}

NetworkWeights validated(NetworkWeights w) {
  auto errors = w.validate();
  if (!errors.empty()) throw InvalidNetwork(std::move(errors));
  return w;
}

}  // namespace

const std::array<std::string_view, kFeatureCount>& featureNames() noexcept {
  static constexpr std::array<std::string_view, kFeatureCount> kNames = {
      "height_m",        "v_W.x",          "v_W.y",   "v_W.z",           "R_WB.00",
      "R_WB.01",         "R_WB.02",        "R_WB.10", "R_WB.11",         "R_WB.12",
      "R_WB.20",         "R_WB.21",        "R_WB.22", "rotor_1_rpm/1e4", "rotor_2_rpm/1e4",
      "rotor_3_rpm/1e4", "rotor_4_rpm/1e4"};
  return kNames;
}

FeatureVector makeFeatures(const control::ResidualFeatures& f) noexcept {
  FeatureVector x;
  x(0) = f.height_m;
  x.segment<3>(1) = f.v_W;
  // A (near-)zero quaternion is no attitude: NaN features, which predict_W turns into "no
  // compensation" (Eigen's normalized() would silently keep the zero).
  if (f.q_WB.squaredNorm() > 1e-12) {
    const Eigen::Matrix3d r = f.q_WB.normalized().toRotationMatrix();
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) x(4 + 3 * i + j) = r(i, j);
    }
  } else {
    x.segment<9>(4).setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  x.segment<4>(13) = f.rotor_speeds_rpm / kRotorSpeedScaleRpm;
  return x;
}

double lipschitzBound(const std::vector<DenseLayer>& layers) {
  double bound = 1.0;
  for (const auto& l : layers) bound *= spectralNorm(l.weights);
  return bound;
}

std::vector<model::FieldError> NetworkWeights::validate() const {
  std::vector<model::FieldError> errors;
  model::FieldChecker c(errors);
  if (layers.empty() || layers.size() > static_cast<std::size_t>(kMaxLayers)) {
    errors.push_back({"layers", std::to_string(layers.size()) + " layers",
                      "1 to " + std::to_string(kMaxLayers) + " dense layers"});
  }
  bool dims_ok = !layers.empty();
  Eigen::Index inputs = kFeatureCount;
  for (std::size_t l = 0; l < layers.size(); ++l) {
    const std::string name = "layers[" + std::to_string(l) + "]";
    const DenseLayer& layer = layers[l];
    const bool last = l + 1 == layers.size();
    const Eigen::Index rows = layer.weights.rows();
    const bool rows_ok = last ? rows == kOutputCount : rows >= 1 && rows <= kMaxWidth;
    if (!rows_ok || layer.weights.cols() != inputs) {
      errors.push_back(
          {name + ".weights", shape(rows, layer.weights.cols()),
           (last ? std::to_string(kOutputCount) : "1.." + std::to_string(kMaxWidth)) + "x" +
               std::to_string(inputs) + " (outputs x inputs; " +
               (l == 0 ? "the first layer takes the " + std::to_string(kFeatureCount) + " features"
                       : "inputs = outputs of layers[" + std::to_string(l - 1) + "]") +
               (last ? "; the last layer gives the 3 force components" : "") + ")"});
      dims_ok = false;
    }
    if (layer.bias.size() != rows) {
      errors.push_back({name + ".bias", std::to_string(layer.bias.size()) + " entries",
                        std::to_string(rows) + " entries (one per output)"});
      dims_ok = false;
    }
    if (!layer.weights.allFinite()) {
      errors.push_back({name + ".weights", "non-finite entries", "finite numbers"});
      dims_ok = false;
    }
    if (!layer.bias.allFinite()) {
      errors.push_back({name + ".bias", "non-finite entries", "finite numbers"});
      dims_ok = false;
    }
    inputs = rows;
  }
  for (int i = 0; i < kFeatureCount; ++i) {
    const std::string feature = std::string(featureNames()[static_cast<std::size_t>(i)]);
    c.finite("input_mean[" + std::to_string(i) + "] (" + feature + ")", input_mean(i));
    c.positive("input_std[" + std::to_string(i) + "] (" + feature + ")", input_std(i));
  }
  if (lipschitz_gamma) {
    const double gamma = *lipschitz_gamma;
    if (!std::isfinite(gamma) || !(gamma > 0.0)) {
      c.fail("lipschitz_gamma", model::formatValue(gamma), "a finite number > 0 (or none)");
    } else if (dims_ok) {
      // The claim must hold: a file that says "γ-Lipschitz" but is not would void the
      // contraction argument of the controller's fixed-point iteration.
      const double bound = lipschitzBound(layers);
      if (!(bound <= gamma * (1.0 + kLipschitzTolerance))) {
        c.fail("lipschitz_gamma", model::formatValue(gamma),
               "at least the product of the layers' spectral norms, " + model::formatValue(bound));
      }
    }
  }
  return errors;
}

InvalidNetwork::InvalidNetwork(std::vector<model::FieldError> errors)
    : std::invalid_argument(model::describeErrors("invalid residual network:", errors)),
      errors_(std::move(errors)) {}

ResidualNetwork::ResidualNetwork(NetworkWeights weights)
    : weights_(validated(std::move(weights))),
      inv_std_(weights_.input_std.cwiseInverse()),
      lipschitz_bound_(neural::lipschitzBound(weights_.layers)) {}

Eigen::Vector3d ResidualNetwork::predict_W(const control::ResidualFeatures& f) const noexcept {
  return predictFeatures(makeFeatures(f));
}

Eigen::Vector3d ResidualNetwork::predictFeatures(const FeatureVector& x) const noexcept {
  if (!x.allFinite()) return Eigen::Vector3d::Zero();
  Activation a = (x - weights_.input_mean).cwiseProduct(inv_std_);
  Activation z;
  const std::size_t n = weights_.layers.size();
  for (std::size_t l = 0; l < n; ++l) {
    const DenseLayer& layer = weights_.layers[l];
    z.resize(layer.weights.rows());
    z.noalias() = layer.weights * a;
    z += layer.bias;
    if (l + 1 < n) a = z.cwiseMax(0.0);  // ReLU on hidden layers only
  }
  const Eigen::Vector3d out = z;
  return out.allFinite() ? out : Eigen::Vector3d::Zero();
}

}  // namespace geaware::neural
