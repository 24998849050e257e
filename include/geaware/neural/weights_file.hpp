// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The residual network's weight file: a versioned YAML document holding the architecture, the
// input standardisation, γ, every layer, and free-form provenance (the training command, the
// data set, the seed), so that a result can be reproduced from the file alone. The format is
// described in docs/neural-lander.md and lives in io/weights_file.hpp; this is the conversion
// between it and NetworkWeights, with the network's own checks (this build's feature order,
// hidden_widths describing the layers, NetworkWeights::validate). Loading is strict: a missing
// or unknown key, a wrong dimension or a non-finite number is an io::ConfigError naming the
// file, line and key.

#include <filesystem>
#include <map>
#include <string>
#include <string_view>

#include "geaware/io/weights_file.hpp"
#include "geaware/neural/residual_network.hpp"

namespace geaware::neural {

/// Format name and version written in every file; loading rejects any other.
inline constexpr std::string_view kWeightsFormat = io::kWeightsFormat;
inline constexpr int kWeightsFormatVersion = io::kWeightsFormatVersion;

struct WeightsDocument {
  NetworkWeights weights;
  /// Free-form text, e.g. {"command": "geaware train-neural …", "seed": "1"}.
  std::map<std::string, std::string> provenance;
};

/// The document as YAML text. Numbers are written in their shortest round-trip form, so
/// save → load gives bit-identical weights. Throws InvalidNetwork for invalid weights.
[[nodiscard]] std::string weightsToYaml(const WeightsDocument& doc);

/// Writes the document; throws InvalidNetwork, or std::runtime_error naming the file when it
/// cannot be written.
void saveWeights(const std::filesystem::path& file, const WeightsDocument& doc);

/// Parses and validates a document; `source` names it in errors. Throws io::ConfigError listing
/// every problem.
[[nodiscard]] WeightsDocument parseWeightsYaml(std::string_view yaml_text,
                                               const std::string& source);

/// Reads, parses and validates a file: std::runtime_error naming the file when it is missing or
/// unreadable, io::ConfigError for its content.
[[nodiscard]] WeightsDocument loadWeights(const std::filesystem::path& file);

}  // namespace geaware::neural
