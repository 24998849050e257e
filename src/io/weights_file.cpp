// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/input_file.hpp"
#include "geaware/io/weights_file.hpp"

#include "geaware/io/output_file.hpp"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "geaware/io/config_error.hpp"
#include "geaware/io/yaml_reader.hpp"

namespace geaware::io {
namespace {

// ---------------------------------------------------------------------------------------------
// Writing.

/// Shortest text that reads back as the same double (std::to_chars round-trip guarantee).
std::string exact(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

void emitRow(YAML::Emitter& out, const std::vector<double>& v) {
  out << YAML::Flow << YAML::BeginSeq;
  for (double x : v) out << exact(x);
  out << YAML::EndSeq;
}

// ---------------------------------------------------------------------------------------------
// Reading.

/// `format` and `version`, read first: false (with a problem) for a file of another format or
/// version, whose other keys may mean something else.
bool readFormat(MapReader& root, const YamlContext& ctx) {
  const std::string format = root.text("format");
  const std::string version = root.text("version");
  if (!ctx.problems.empty()) return false;
  if (format != kWeightsFormat) {
    root.problem("format", "'" + format + "', expected '" + std::string(kWeightsFormat) + "'");
    return false;
  }
  if (version != std::to_string(kWeightsFormatVersion)) {
    root.problem("version", "'" + version + "' is not supported; this build reads version " +
                                std::to_string(kWeightsFormatVersion));
    return false;
  }
  return true;
}

/// The layers: the first has `features` columns (none: unknown, its first row decides), every
/// later one a column per row of the layer before it, and each bias an entry per row.
void readLayers(MapReader& root, std::optional<std::size_t> features, WeightsFile& file) {
  std::optional<std::size_t> columns = features;
  for (MapReader& layer : root.maps("layers")) {
    WeightsFileLayer dense;
    if (layer.valid()) {
      const std::size_t before = layer.problemCount();
      dense.weights = layer.finiteRows("weights", columns);
      if (dense.weights.empty() && layer.problemCount() == before) {
        layer.problem("weights", "expected a non-empty list of rows");
      }
      const std::optional<std::size_t> rows =
          dense.weights.empty() ? std::nullopt : std::optional<std::size_t>(dense.weights.size());
      dense.bias = layer.finiteNumbers("bias", rows);
      layer.rejectUnknownKeys();
    }
    // After an unreadable layer, the next one's first row decides its columns.
    columns = dense.weights.empty() ? std::nullopt
                                    : std::optional<std::size_t>(dense.weights.size());
    file.layers.push_back(std::move(dense));
  }
}

/// Every key after format and version.
void readContent(MapReader& root, YamlContext& ctx, WeightsFile& file) {
  std::size_t before = ctx.problems.size();
  file.features = root.texts("features");
  const std::optional<std::size_t> features =
      ctx.problems.size() == before ? std::optional<std::size_t>(file.features.size())
                                    : std::nullopt;
  before = ctx.problems.size();
  const std::string activation = root.text("activation");
  if (ctx.problems.size() == before && activation != kWeightsActivation) {
    root.problem("activation", "expected '" + std::string(kWeightsActivation) + "'");
  }
  file.hidden_widths = root.finiteNumbers("hidden_widths");
  // γ: a number, or `none` for a network trained without spectral normalisation.
  if (root.valueIs("lipschitz_gamma", "none")) {
    static_cast<void>(root.text("lipschitz_gamma"));
  } else {
    file.lipschitz_gamma = root.finiteNumber("lipschitz_gamma");
  }
  file.input_mean = root.finiteNumbers("input_mean", features);
  file.input_std = root.finiteNumbers("input_std", features);
  readLayers(root, features, file);
  file.provenance = root.optionalTextMap("provenance");
  root.rejectUnknownKeys();
}

}  // namespace

int WeightsFile::lineOf(std::string key) const { return lineOfKey(lines, std::move(key)); }

WeightsFile parseWeightsFile(std::string_view text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::ParserException& e) {
    throw ConfigError(source, {{e.mark.line + 1, "", "not valid YAML: " + e.msg}});
  }
  if (!root.IsMap()) {
    throw ConfigError(source,
                      {{1, "", "expected a map with the keys of a residual-network weight file"}});
  }
  YamlContext ctx;
  // Missing top-level keys are reported at the document's first line.
  MapReader reader(root, "", ctx, root.Mark().line >= 0 ? root.Mark().line + 1 : 1);
  WeightsFile file;
  if (readFormat(reader, ctx)) readContent(reader, ctx, file);
  if (!ctx.problems.empty()) throw ConfigError(source, std::move(ctx.problems));
  file.lines = std::move(ctx.lines);
  return file;
}

std::string weightsFileToYaml(const WeightsFile& file) {
  YAML::Emitter out;
  out << YAML::Comment("geaware Neural-Lander residual-force network (docs/neural-lander.md)");
  out << YAML::BeginMap;
  out << YAML::Key << "format" << YAML::Value << std::string(kWeightsFormat);
  out << YAML::Key << "version" << YAML::Value << kWeightsFormatVersion;
  out << YAML::Key << "features" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const auto& n : file.features) out << n;
  out << YAML::EndSeq;
  out << YAML::Key << "hidden_widths" << YAML::Value;
  emitRow(out, file.hidden_widths);
  out << YAML::Key << "activation" << YAML::Value << std::string(kWeightsActivation);
  out << YAML::Key << "lipschitz_gamma" << YAML::Value
      << (file.lipschitz_gamma ? exact(*file.lipschitz_gamma) : std::string("none"));
  out << YAML::Key << "input_mean" << YAML::Value;
  emitRow(out, file.input_mean);
  out << YAML::Key << "input_std" << YAML::Value;
  emitRow(out, file.input_std);
  out << YAML::Key << "layers" << YAML::Value << YAML::BeginSeq;
  for (const auto& l : file.layers) {
    out << YAML::BeginMap << YAML::Key << "weights" << YAML::Value << YAML::BeginSeq;
    for (const auto& row : l.weights) emitRow(out, row);
    out << YAML::EndSeq << YAML::Key << "bias" << YAML::Value;
    emitRow(out, l.bias);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  if (!file.provenance.empty()) {
    out << YAML::Key << "provenance" << YAML::Value << YAML::BeginMap;
    for (const auto& [k, v] : file.provenance) {
      out << YAML::Key << k << YAML::Value << YAML::DoubleQuoted << v;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

WeightsFile readWeightsFile(const std::filesystem::path& path) {
  return parseWeightsFile(readInputFile(path, "weight file", "weight file"), path.string());
}

void writeWeightsFile(const std::filesystem::path& path, const WeightsFile& file) {
  const std::string text = weightsFileToYaml(file);
  writeFileAtomically(path.string(), text, "the weight file");
}

}  // namespace geaware::io
