// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/neural/weights_file.hpp"

#include <utility>
#include <vector>

#include "geaware/io/config_error.hpp"

namespace geaware::neural {
namespace {

template <typename Vec>
std::vector<double> toVector(const Vec& v) {
  std::vector<double> out(static_cast<std::size_t>(v.size()));
  for (Eigen::Index i = 0; i < v.size(); ++i) out[static_cast<std::size_t>(i)] = v(i);
  return out;
}

io::WeightsFile toFile(const WeightsDocument& doc) {
  const NetworkWeights& w = doc.weights;
  io::WeightsFile file;
  for (auto n : featureNames()) file.features.emplace_back(n);
  for (std::size_t l = 0; l + 1 < w.layers.size(); ++l) {
    file.hidden_widths.push_back(static_cast<double>(w.layers[l].weights.rows()));
  }
  file.lipschitz_gamma = w.lipschitz_gamma;
  file.input_mean = toVector(w.input_mean);
  file.input_std = toVector(w.input_std);
  for (const auto& l : w.layers) {
    io::WeightsFileLayer layer;
    for (Eigen::Index i = 0; i < l.weights.rows(); ++i) {
      layer.weights.push_back(toVector(l.weights.row(i)));
    }
    layer.bias = toVector(l.bias);
    file.layers.push_back(std::move(layer));
  }
  file.provenance = doc.provenance;
  return file;
}

bool hasThisBuildsFeatures(const std::vector<std::string>& features) {
  bool same = features.size() == featureNames().size();
  for (std::size_t i = 0; same && i < features.size(); ++i) same = features[i] == featureNames()[i];
  return same;
}

/// The network of a file read without problems: the io reader has checked that every row of a
/// layer has the same length and that the mean and the deviation have one entry per feature.
NetworkWeights toWeights(const io::WeightsFile& file) {
  NetworkWeights w;
  w.lipschitz_gamma = file.lipschitz_gamma;
  w.input_mean = Eigen::Map<const FeatureVector>(file.input_mean.data());
  w.input_std = Eigen::Map<const FeatureVector>(file.input_std.data());
  for (const auto& l : file.layers) {
    DenseLayer dense;
    const auto rows = static_cast<Eigen::Index>(l.weights.size());
    const auto cols = static_cast<Eigen::Index>(l.weights.empty() ? 0 : l.weights[0].size());
    dense.weights.resize(rows, cols);
    for (Eigen::Index i = 0; i < rows; ++i) {
      dense.weights.row(i) = Eigen::Map<const Eigen::RowVectorXd>(
          l.weights[static_cast<std::size_t>(i)].data(), cols);
    }
    dense.bias = Eigen::Map<const Eigen::VectorXd>(l.bias.data(),
                                                   static_cast<Eigen::Index>(l.bias.size()));
    w.layers.push_back(std::move(dense));
  }
  return w;
}

/// The network's checks of a file the io reader accepted, at the lines of their keys.
WeightsDocument fromFile(const io::WeightsFile& file, const std::string& source) {
  // 1. The feature order must be this build's (the columns depend on it).
  if (!hasThisBuildsFeatures(file.features)) {
    std::string expected;
    for (auto n : featureNames()) expected += (expected.empty() ? "" : ", ") + std::string(n);
    throw io::ConfigError(source, {{file.lineOf("features"), "features",
                                    "does not match this build's feature order [" + expected +
                                        "]"}});
  }
  WeightsDocument doc{toWeights(file), file.provenance};
  std::vector<io::ConfigProblem> problems;
  // 2. hidden_widths must describe the layers (a hand-edited file is caught here).
  const auto& layers = doc.weights.layers;
  bool widths_match = file.hidden_widths.size() + 1 == layers.size();
  for (std::size_t i = 0; widths_match && i < file.hidden_widths.size(); ++i) {
    widths_match = file.hidden_widths[i] == static_cast<double>(layers[i].weights.rows());
  }
  if (!widths_match) {
    std::string actual;
    for (std::size_t i = 0; i + 1 < layers.size(); ++i) {
      actual += (actual.empty() ? "" : ", ") + std::to_string(layers[i].weights.rows());
    }
    problems.push_back({file.lineOf("hidden_widths"), "hidden_widths",
                        "does not match the layers, whose hidden widths are [" + actual + "]"});
  }
  // 3. The network's own checks (dimension chain, σ > 0, the γ certificate).
  for (const auto& e : doc.weights.validate()) {
    std::string key = e.field.substr(0, e.field.find(' '));
    problems.push_back({file.lineOf(key), key, e.value + ": expected " + e.expected});
  }
  if (!problems.empty()) throw io::ConfigError(source, std::move(problems));
  return doc;
}

}  // namespace

std::string weightsToYaml(const WeightsDocument& doc) {
  if (auto errors = doc.weights.validate(); !errors.empty())
    throw InvalidNetwork(std::move(errors));
  return io::weightsFileToYaml(toFile(doc));
}

void saveWeights(const std::filesystem::path& file, const WeightsDocument& doc) {
  if (auto errors = doc.weights.validate(); !errors.empty())
    throw InvalidNetwork(std::move(errors));
  io::writeWeightsFile(file, toFile(doc));
}

WeightsDocument parseWeightsYaml(std::string_view yaml_text, const std::string& source) {
  return fromFile(io::parseWeightsFile(yaml_text, source), source);
}

WeightsDocument loadWeights(const std::filesystem::path& file) {
  return fromFile(io::readWeightsFile(file), file.string());
}

}  // namespace geaware::neural
