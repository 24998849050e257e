// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The weight file of a dense residual network (docs/neural-lander.md): a YAML document with the
// format name and version, the input feature names, the hidden widths, γ (or `none`), the input
// standardisation, every layer's weights (one list per output row) and bias, and free-form
// provenance. This is the format only: the reader checks it strictly (unknown and missing keys,
// finite numbers, consistent dimensions) and knows nothing of the network that uses it — the
// feature names and the network's own checks are neural::loadWeights'. Numbers are written in
// their shortest round-trip form, so write → read gives bit-identical values.

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace geaware::io {

/// Format name and version written in every file; reading rejects any other, before anything
/// else of the file is read. (`format` + `version` are this file's format version.)
inline constexpr std::string_view kWeightsFormat = "geaware-residual-network";
inline constexpr int kWeightsFormatVersion = 1;
/// The only activation the format describes.
inline constexpr std::string_view kWeightsActivation = "relu";

/// One dense layer: `weights` has one row per output, each with one entry per input.
struct WeightsFileLayer {
  std::vector<std::vector<double>> weights;
  std::vector<double> bias;
};

/// The content of a weight file, as written.
struct WeightsFile {
  std::vector<std::string> features;  ///< input feature names, in input order
  std::vector<double> hidden_widths;  ///< as written; the layers' row counts except the last
  std::optional<double> lipschitz_gamma;  ///< none: trained without spectral normalisation
  std::vector<double> input_mean;     ///< one per feature
  std::vector<double> input_std;      ///< one per feature
  std::vector<WeightsFileLayer> layers;
  std::map<std::string, std::string> provenance;  ///< free-form text, e.g. the command, the seed
  /// Key path → 1-based line of every key and item read ("layers[1].bias[0]"); empty for a
  /// WeightsFile not read from text.
  std::map<std::string, int> lines;

  /// Line of `key` or of its nearest recorded parent ("layers[1].weights" → "layers[1]" → …),
  /// 0 when none is recorded: for problems the caller finds after reading.
  [[nodiscard]] int lineOf(std::string key) const;
};

/// Parses `text` (named `source` in errors). Strict: `format` and `version` are checked first
/// and a mismatch stops reading; then unknown keys, missing keys, non-finite numbers and
/// dimensions (the first layer has one column per feature, every later layer one per row of
/// the layer before it, a bias one entry per row, the mean and standard deviation one entry per
/// feature). Throws io::ConfigError listing every problem with its line and key path.
[[nodiscard]] WeightsFile parseWeightsFile(std::string_view text, const std::string& source);

/// The file as YAML text (lines and hidden_widths as given; `activation` is always relu).
[[nodiscard]] std::string weightsFileToYaml(const WeightsFile& file);

/// Reads and parses `path`: std::runtime_error naming it when it is missing or unreadable,
/// io::ConfigError for its content.
[[nodiscard]] WeightsFile readWeightsFile(const std::filesystem::path& path);

/// Writes weightsFileToYaml(file) to `path`; std::runtime_error naming it when it cannot be
/// written.
void writeWeightsFile(const std::filesystem::path& path, const WeightsFile& file);

}  // namespace geaware::io
