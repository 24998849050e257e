// SPDX-License-Identifier: BSD-3-Clause
// The weight file: save → load is bit-exact, and every kind of corrupt file is rejected with
// the file, the line and the key named.

#include "geaware/neural/weights_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include "geaware/io/config_error.hpp"
#include "synthetic_residual.hpp"

namespace geaware::neural {
namespace {

/// 17 → 2 → 3 with round numbers, so that the YAML can be edited by text. Its exact Lipschitz
/// bound is 0.1·√34 · √6/3 ≈ 0.476.
NetworkWeights smallNetwork() {
  NetworkWeights w;
  w.layers = {
      DenseLayer{Eigen::MatrixXd::Constant(2, kFeatureCount, 0.1), Eigen::Vector2d(0.5, -0.5)},
      DenseLayer{Eigen::MatrixXd::Constant(3, 2, 1.0 / 3.0), Eigen::Vector3d(1.0, 0.0, 0.0)}};
  w.lipschitz_gamma = 2.0;
  return w;
}

/// `text` with the one occurrence of `from` replaced by `to` (fails the test if absent).
std::string edit(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "'" << from << "' not in\n" << text;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// 1-based line of the first occurrence of `needle`.
int lineOf(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

/// The message of the ConfigError `yaml` raises ("" and a test failure when it is accepted).
std::string rejection(const std::string& yaml) {
  try {
    static_cast<void>(parseWeightsYaml(yaml, "corrupt.yaml"));
  } catch (const io::ConfigError& e) {
    EXPECT_EQ(e.file(), "corrupt.yaml");
    return e.what();
  }
  ADD_FAILURE() << "accepted:\n" << yaml;
  return "";
}

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << (haystack)

std::filesystem::path tempFile(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("geaware_neural_test_" + std::to_string(::getpid()) + "_" + name);
}

TEST(WeightsFile, SaveLoadGivesBitIdenticalWeightsAndPredictions) {
  // A trained network: its numbers have full float→double mantissas, not round values.
  const geaware_test::SyntheticResidual target;
  TrainOptions o;
  o.hidden_widths = {24, 16};
  o.epochs = 3;
  o.lipschitz_gamma = 10.0;
  const TrainResult trained = train(target.makeSet(300, 8), o);
  const WeightsDocument saved{trained.weights,
                              {{"command", "geaware train-neural --seed 1 --out \"w.yaml\""},
                               {"dataset", "hover-descent 0.1–1.5 m"}}};
  const auto file = tempFile("roundtrip.yaml");
  saveWeights(file, saved);
  const WeightsDocument loaded = loadWeights(file);
  std::filesystem::remove(file);

  ASSERT_EQ(loaded.weights.layers.size(), saved.weights.layers.size());
  for (std::size_t l = 0; l < saved.weights.layers.size(); ++l) {
    EXPECT_TRUE(loaded.weights.layers[l].weights == saved.weights.layers[l].weights) << l;
    EXPECT_TRUE(loaded.weights.layers[l].bias == saved.weights.layers[l].bias) << l;
  }
  EXPECT_TRUE(loaded.weights.input_mean == saved.weights.input_mean);
  EXPECT_TRUE(loaded.weights.input_std == saved.weights.input_std);
  EXPECT_EQ(loaded.weights.lipschitz_gamma, saved.weights.lipschitz_gamma);
  EXPECT_EQ(loaded.provenance, saved.provenance);

  const ResidualNetwork a(saved.weights);
  const ResidualNetwork b(loaded.weights);
  std::mt19937_64 rng(3);
  for (int i = 0; i < 100; ++i) {
    const auto f = target.sample(rng);
    EXPECT_EQ(a.predict_W(f), b.predict_W(f)) << "sample " << i;
  }
}

TEST(WeightsFile, NetworkWithoutBoundRoundTripsAsNone) {
  WeightsDocument doc{smallNetwork(), {}};
  doc.weights.lipschitz_gamma.reset();
  const std::string yaml = weightsToYaml(doc);
  EXPECT_CONTAINS(yaml, "lipschitz_gamma: none");
  EXPECT_FALSE(parseWeightsYaml(yaml, "none.yaml").weights.lipschitz_gamma.has_value());
}

TEST(WeightsFile, RejectsWrongDimensions) {
  const std::string good = weightsToYaml({smallNetwork(), {}});
  // One entry short in a row.
  std::string short_row = "[0.1";
  for (int i = 1; i < kFeatureCount - 1; ++i) short_row += ", 0.1";
  short_row += "]\n";
  std::string full_row = "[0.1";
  for (int i = 1; i < kFeatureCount; ++i) full_row += ", 0.1";
  full_row += "]\n";
  const std::string bad_row = edit(good, full_row, short_row);
  const std::string what = rejection(bad_row);
  EXPECT_CONTAINS(what, "layers[0].weights[0]");
  EXPECT_CONTAINS(what, "has 16 entries, expected 17");
  EXPECT_CONTAINS(what, "corrupt.yaml:" + std::to_string(lineOf(good, full_row)));

  // Three biases for a layer of two outputs.
  EXPECT_CONTAINS(rejection(edit(good, "bias: [0.5, -0.5]", "bias: [0.5, -0.5, 1]")),
                  "layers[0].bias");
  // 16 means for 17 features.
  EXPECT_CONTAINS(rejection(edit(good, "input_mean: [0, ", "input_mean: [")),
                  "key 'input_mean': has 16 entries, expected 17");
  // hidden_widths that do not describe the layers.
  EXPECT_CONTAINS(rejection(edit(good, "hidden_widths: [2]", "hidden_widths: [3]")),
                  "hidden_widths");
}

TEST(WeightsFile, RejectsNonFiniteNumbers) {
  const std::string good = weightsToYaml({smallNetwork(), {}});
  const std::string bad = edit(good, "bias: [1, 0, 0]", "bias: [.nan, 0, 0]");
  const std::string what = rejection(bad);
  EXPECT_CONTAINS(what, "corrupt.yaml:" + std::to_string(lineOf(good, "bias: [1, 0, 0]")) +
                            ": key 'layers[1].bias[0]': '.nan' is not a finite number");
  EXPECT_CONTAINS(rejection(edit(good, "input_std: [1, ", "input_std: [inf, ")), "input_std[0]");
  EXPECT_CONTAINS(rejection(edit(good, "lipschitz_gamma: 2", "lipschitz_gamma: 2x")),
                  "expected a number, got '2x'");
  // Finite but invalid: a zero standard deviation.
  EXPECT_CONTAINS(rejection(edit(good, "input_std: [1, ", "input_std: [0, ")), "input_std[0]");
}

TEST(WeightsFile, RejectsMissingAndUnknownKeys) {
  const std::string good = weightsToYaml({smallNetwork(), {}});
  const auto from = good.find("input_std:");
  std::string no_std = good;
  no_std.erase(from, good.find('\n', from) + 1 - from);
  EXPECT_CONTAINS(rejection(no_std), "key 'input_std': is missing (required)");
  EXPECT_CONTAINS(rejection(edit(good, "activation: relu\n", "activation: relu\ndropout: 0.1\n")),
                  "key 'dropout': unknown key");
  EXPECT_CONTAINS(rejection(edit(good, "    bias: [1, 0, 0]", "    bias: [1, 0, 0]\n    scale: 2")),
                  "key 'layers[1].scale': unknown key");
}

TEST(WeightsFile, RejectsOtherFormatsVersionsAndFeatureOrders) {
  const std::string good = weightsToYaml({smallNetwork(), {}});
  EXPECT_CONTAINS(rejection(edit(good, "version: 1", "version: 2")),
                  "'2' is not supported; this build reads version 1");
  EXPECT_CONTAINS(rejection(edit(good, "format: geaware-residual-network", "format: onnx")),
                  "expected 'geaware-residual-network'");
  EXPECT_CONTAINS(rejection(edit(good, "v_W.x, v_W.y", "v_W.y, v_W.x")),
                  "does not match this build's feature order");
  EXPECT_CONTAINS(rejection("layers: [\n"), "not valid YAML");
  EXPECT_CONTAINS(rejection("- 1\n- 2\n"), "expected a map");
}

TEST(WeightsFile, RejectsAFalseLipschitzClaim) {
  // The network's exact bound is ≈ 0.476: a file claiming γ = 0.4 is lying.
  const std::string good = weightsToYaml({smallNetwork(), {}});
  const std::string what = rejection(edit(good, "lipschitz_gamma: 2", "lipschitz_gamma: 0.4"));
  EXPECT_CONTAINS(what, "key 'lipschitz_gamma'");
  EXPECT_CONTAINS(what, "product of the layers' spectral norms");
}

TEST(WeightsFile, LoadNamesTheFile) {
  const auto missing = tempFile("does_not_exist.yaml");
  try {
    static_cast<void>(loadWeights(missing));
    FAIL() << "loaded a missing file";
  } catch (const std::runtime_error& e) {
    EXPECT_CONTAINS(e.what(), missing.string() + ": no such weight file");
  }
  const auto corrupt = tempFile("corrupt.yaml");
  {
    std::ofstream out(corrupt);
    out << edit(weightsToYaml({smallNetwork(), {}}), "version: 1", "version: 7");
  }
  const int version_line = lineOf(weightsToYaml({smallNetwork(), {}}), "version:");
  try {
    static_cast<void>(loadWeights(corrupt));
    FAIL() << "loaded a corrupt file";
  } catch (const io::ConfigError& e) {
    EXPECT_EQ(e.file(), corrupt.string());
    EXPECT_CONTAINS(e.what(),
                    corrupt.string() + ":" + std::to_string(version_line) + ": key 'version'");
  }
  std::filesystem::remove(corrupt);
}

TEST(WeightsFile, RefusesToSaveInvalidWeights) {
  NetworkWeights w = smallNetwork();
  w.layers[0].weights(1, 3) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(saveWeights(tempFile("never.yaml"), {w, {}}), InvalidNetwork);
  EXPECT_FALSE(std::filesystem::exists(tempFile("never.yaml")));
}

}  // namespace
}  // namespace geaware::neural
