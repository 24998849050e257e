// SPDX-License-Identifier: BSD-3-Clause
// The weight-file format on its own (io/weights_file.hpp): it round-trips any network shape bit
// for bit, and its reader checks the format's own consistency (format and version first,
// dimensions chained from the feature count through the layers) without knowing the network.
// The network's checks (this build's features, validate()) are tested in tests/neural.

#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "geaware/io/config_error.hpp"
#include "geaware/io/weights_file.hpp"

namespace geaware::io {
namespace {

/// Two features → 3 hidden → 1 output, with numbers that need every digit.
WeightsFile tinyFile() {
  WeightsFile f;
  f.features = {"a", "b"};
  f.hidden_widths = {3};
  f.lipschitz_gamma = 0.1 + 0.2;
  f.input_mean = {1.0 / 3.0, -2e-300};
  f.input_std = {1.0, 7.5e12};
  f.layers = {{{{0.1, 0.2}, {-0.3, 1e-17}, {5.0, 6.0}}, {0.0, 1.0, 2.0}},
              {{{1.0 / 7.0, 2.0, 3.0}}, {-4.0}}};
  f.provenance = {{"command", "train --out \"w.yaml\""}};
  return f;
}

std::vector<ConfigProblem> problemsOf(const std::string& text) {
  try {
    static_cast<void>(parseWeightsFile(text, "w.yaml"));
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), "w.yaml");
    return e.problems();
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return {};
}

std::string edit(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "'" << from << "' not in\n" << text;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

int lineOf(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

TEST(WeightsFileFormat, RoundTripsAnyShapeBitForBitAndRecordsLines) {
  const WeightsFile f = tinyFile();
  const std::string text = weightsFileToYaml(f);
  const WeightsFile back = parseWeightsFile(text, "w.yaml");
  EXPECT_EQ(back.features, f.features);
  EXPECT_EQ(back.hidden_widths, f.hidden_widths);
  EXPECT_EQ(back.lipschitz_gamma, f.lipschitz_gamma);
  EXPECT_EQ(back.input_mean, f.input_mean);
  EXPECT_EQ(back.input_std, f.input_std);
  ASSERT_EQ(back.layers.size(), 2u);
  for (std::size_t l = 0; l < 2; ++l) {
    EXPECT_EQ(back.layers[l].weights, f.layers[l].weights) << l;
    EXPECT_EQ(back.layers[l].bias, f.layers[l].bias) << l;
  }
  EXPECT_EQ(back.provenance, f.provenance);
  EXPECT_EQ(weightsFileToYaml(back), text);
  EXPECT_EQ(back.lineOf("layers[1].bias[0]"), lineOf(text, "bias: [-4]"));
  EXPECT_EQ(back.lineOf("lipschitz_gamma"), lineOf(text, "lipschitz_gamma:"));
  EXPECT_EQ(back.lineOf("layers[0].weights[1][0]"), lineOf(text, "[-0.3"));

  WeightsFile none = f;
  none.lipschitz_gamma.reset();
  none.provenance.clear();
  const std::string none_text = weightsFileToYaml(none);
  EXPECT_NE(none_text.find("lipschitz_gamma: none\n"), std::string::npos);
  EXPECT_EQ(none_text.find("provenance"), std::string::npos);
  EXPECT_FALSE(parseWeightsFile(none_text, "w.yaml").lipschitz_gamma.has_value());
}

TEST(WeightsFileFormat, FormatAndVersionAreCheckedBeforeAnythingElse) {
  const std::string good = weightsFileToYaml(tinyFile());
  // Another version with an unknown key: only the version is reported.
  auto p = problemsOf(edit(edit(good, "version: 1", "version: 2"), "activation", "act"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].key, "version");
  EXPECT_EQ(p[0].line, lineOf(good, "version:"));
  EXPECT_EQ(p[0].message, "'2' is not supported; this build reads version 1");
  p = problemsOf(edit(good, "format: geaware-residual-network", "format: onnx"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].message, "'onnx', expected 'geaware-residual-network'");
}

TEST(WeightsFileFormat, DimensionsChainFromTheFeaturesThroughTheLayers) {
  const std::string good = weightsFileToYaml(tinyFile());
  // A third feature: the mean, the deviation and the first layer's rows are now one short.
  auto p = problemsOf(edit(good, "features: [a, b]", "features: [a, b, c]"));
  ASSERT_EQ(p.size(), 5u);
  EXPECT_EQ(p[0].key, "input_mean");
  EXPECT_EQ(p[0].message, "has 2 entries, expected 3");
  EXPECT_EQ(p[2].key, "layers[0].weights[0]");
  EXPECT_EQ(p[2].line, lineOf(good, "[0.1, 0.2]"));
  // The second layer takes the first layer's 3 outputs; its bias has one entry per row.
  p = problemsOf(edit(edit(good, "[0.14285714285714285, 2, 3]", "[0.14285714285714285, 2]"),
                      "bias: [-4]", "bias: [-4, 1]"));
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].key, "layers[1].weights[0]");
  EXPECT_EQ(p[0].message, "has 2 entries, expected 3");
  EXPECT_EQ(p[1].key, "layers[1].bias");
  EXPECT_EQ(p[1].message, "has 2 entries, expected 1");
  // An empty layer.
  p = problemsOf(edit(good, "  - weights:\n      - [0.142", "  - weights: []\n    x:\n      - [0.142"));
  ASSERT_FALSE(p.empty());
  EXPECT_EQ(p[0].key, "layers[1].weights");
  EXPECT_EQ(p[0].message, "expected a non-empty list of rows");
}

TEST(WeightsFileFormat, ReportsEveryOtherProblemInOneRun) {
  const std::string good = weightsFileToYaml(tinyFile());
  std::string text = edit(good, "activation: relu", "activation: tanh\ndropout: 0.5");
  text = edit(text, "bias: [-4]", "bias: [.inf]\n    scale: 2");
  const auto p = problemsOf(text);
  std::vector<std::string> keys;
  for (const auto& q : p) keys.push_back(q.key);
  EXPECT_EQ(keys, (std::vector<std::string>{"activation", "layers[1].bias[0]", "layers[1].scale",
                                            "dropout"}));
  EXPECT_EQ(p[1].message, "'.inf' is not a finite number");
  EXPECT_EQ(problemsOf("- 1\n").at(0).message,
            "expected a map with the keys of a residual-network weight file");
}

}  // namespace
}  // namespace geaware::io
