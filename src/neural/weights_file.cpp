#include "geaware/neural/weights_file.hpp"

#include <yaml-cpp/yaml.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>
#include <vector>

#include "geaware/io/config_error.hpp"

namespace geaware::neural {
namespace {

// ---------------------------------------------------------------------------------------------
// Writing.

/// Shortest text that reads back as the same double (std::to_chars round-trip guarantee).
std::string exact(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

template <typename Vec>
void emitRow(YAML::Emitter& out, const Vec& v) {
  out << YAML::Flow << YAML::BeginSeq;
  for (Eigen::Index i = 0; i < v.size(); ++i) out << exact(v(i));
  out << YAML::EndSeq;
}

// ---------------------------------------------------------------------------------------------
// Strict reading: every problem is collected with its line and key path; keys never read are
// reported as unknown.

int lineOf(const YAML::Node& n) { return n.Mark().line >= 0 ? n.Mark().line + 1 : 0; }

struct Reader {
  std::vector<io::ConfigProblem> problems;
  std::map<std::string, int> lines;  // key path → line, for problems found after reading

  void problem(int line, std::string key, std::string message) {
    problems.push_back({line, std::move(key), std::move(message)});
  }

  /// Child `key` of map `node` (path `path`); a problem when missing or empty.
  YAML::Node child(const YAML::Node& node, const std::string& path, const std::string& key,
                   int parent_line) {
    const std::string full = path.empty() ? key : path + "." + key;
    for (const auto& kv : node) {
      if (kv.first.IsScalar() && kv.first.Scalar() == key) {
        lines[full] = lineOf(kv.first);
        if (!kv.second.IsDefined() || kv.second.IsNull()) {
          problem(lineOf(kv.first), full, "has no value");
          return YAML::Node(YAML::NodeType::Undefined);
        }
        return kv.second;
      }
    }
    problem(parent_line, full, "is missing (required)");
    return YAML::Node(YAML::NodeType::Undefined);
  }

  void rejectUnknown(const YAML::Node& node, const std::string& path,
                     const std::set<std::string>& known) {
    for (const auto& kv : node) {
      const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : "?";
      if (known.count(key) == 0) {
        std::string full = path;
        if (!full.empty()) full += '.';
        full += key;
        problem(lineOf(kv.first), std::move(full), "unknown key");
      }
    }
  }

  /// A finite number; NaN (with a problem) otherwise. Parsed with std::from_chars, strictly:
  /// "1.5x" is not a number, and .nan/.inf are named as such.
  double number(const YAML::Node& n, const std::string& path) {
    if (!n.IsScalar()) {
      problem(lineOf(n), path, "expected a number");
      return std::nan("");
    }
    const std::string& s = n.Scalar();
    double v = 0.0;
    const char* first = s.data();
    if (!s.empty() && s[0] == '+') ++first;
    const auto res = std::from_chars(first, s.data() + s.size(), v);
    if (res.ec != std::errc() || res.ptr != s.data() + s.size()) {
      std::string lower;
      for (char c : s) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      const bool special =
          lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos;
      problem(
          lineOf(n), path,
          special ? "'" + s + "' is not a finite number" : "expected a number, got '" + s + "'");
      return std::nan("");
    }
    if (!std::isfinite(v)) {
      problem(lineOf(n), path, "'" + s + "' is not a finite number");
      return std::nan("");
    }
    return v;
  }

  /// A flow or block list of numbers; `expected_size` < 0 accepts any length.
  std::vector<double> numbers(const YAML::Node& n, const std::string& path,
                              long expected_size = -1) {
    std::vector<double> out;
    if (!n.IsDefined()) return out;
    if (!n.IsSequence()) {
      problem(lineOf(n), path, "expected a list of numbers");
      return out;
    }
    if (expected_size >= 0 && static_cast<long>(n.size()) != expected_size) {
      problem(lineOf(n), path,
              "has " + std::to_string(n.size()) + " entries, expected " +
                  std::to_string(expected_size));
    }
    for (std::size_t i = 0; i < n.size(); ++i) {
      out.push_back(number(n[i], path + "[" + std::to_string(i) + "]"));
    }
    return out;
  }

  std::string text(const YAML::Node& n, const std::string& path) {
    if (!n.IsDefined()) return {};
    if (!n.IsScalar()) {
      problem(lineOf(n), path, "expected text");
      return {};
    }
    return n.Scalar();
  }

  /// Line of `key` or of its nearest recorded parent ("layers[1].weights" → "layers[1]" → …).
  [[nodiscard]] int lineFor(std::string key) const {
    while (true) {
      if (auto it = lines.find(key); it != lines.end()) return it->second;
      const auto cut = key.find_last_of(".[");
      if (cut == std::string::npos) return 0;
      key.resize(cut);
    }
  }
};

const std::set<std::string> kTopKeys = {
    "format",          "version",    "features",  "hidden_widths", "activation",
    "lipschitz_gamma", "input_mean", "input_std", "layers",        "provenance"};

WeightsDocument read(const YAML::Node& root, Reader& r) {
  WeightsDocument doc;
  if (!root.IsMap()) {
    r.problem(1, "", "expected a map with the keys of a residual-network weight file");
    return doc;
  }
  const int top = lineOf(root);  // missing top-level keys are reported at the document's start
  // 1. Format and version first: a file of another format or version is not read further.
  const std::string format = r.text(r.child(root, "", "format", top), "format");
  const YAML::Node version_node = r.child(root, "", "version", top);
  if (!r.problems.empty()) return doc;
  if (format != kWeightsFormat) {
    r.problem(r.lineFor("format"), "format",
              "'" + format + "', expected '" + std::string(kWeightsFormat) + "'");
    return doc;
  }
  if (!version_node.IsScalar() || version_node.Scalar() != std::to_string(kWeightsFormatVersion)) {
    r.problem(r.lineFor("version"), "version",
              "'" + (version_node.IsScalar() ? version_node.Scalar() : std::string("?")) +
                  "' is not supported; this build reads version " +
                  std::to_string(kWeightsFormatVersion));
    return doc;
  }
  r.rejectUnknown(root, "", kTopKeys);

  // 2. Architecture: the feature order must be this build's, the widths must match the layers.
  const YAML::Node features = r.child(root, "", "features", top);
  if (features.IsDefined()) {
    bool same = features.IsSequence() && features.size() == featureNames().size();
    for (std::size_t i = 0; same && i < features.size(); ++i) {
      same = features[i].IsScalar() && features[i].Scalar() == featureNames()[i];
    }
    if (!same) {
      std::string expected;
      for (auto n : featureNames()) expected += (expected.empty() ? "" : ", ") + std::string(n);
      r.problem(r.lineFor("features"), "features",
                "does not match this build's feature order [" + expected + "]");
    }
  }
  const YAML::Node activation = r.child(root, "", "activation", top);
  if (activation.IsDefined() && r.text(activation, "activation") != "relu") {
    r.problem(r.lineFor("activation"), "activation", "expected 'relu'");
  }
  std::vector<double> widths = r.numbers(r.child(root, "", "hidden_widths", top), "hidden_widths");

  // 3. γ: a number, or `none` for a network trained without spectral normalisation.
  const YAML::Node gamma = r.child(root, "", "lipschitz_gamma", top);
  if (gamma.IsDefined()) {
    if (gamma.IsScalar() && gamma.Scalar() == "none") {
      doc.weights.lipschitz_gamma.reset();
    } else {
      doc.weights.lipschitz_gamma = r.number(gamma, "lipschitz_gamma");
    }
  }

  // 4. Standardisation.
  const auto mean = r.numbers(r.child(root, "", "input_mean", top), "input_mean", kFeatureCount);
  const auto stdev = r.numbers(r.child(root, "", "input_std", top), "input_std", kFeatureCount);
  if (mean.size() == kFeatureCount)
    doc.weights.input_mean = Eigen::Map<const FeatureVector>(mean.data());
  if (stdev.size() == kFeatureCount)
    doc.weights.input_std = Eigen::Map<const FeatureVector>(stdev.data());

  // 5. Layers: weights as a list of rows (one per output), bias as a list.
  const YAML::Node layers = r.child(root, "", "layers", top);
  if (layers.IsDefined() && !layers.IsSequence()) {
    r.problem(r.lineFor("layers"), "layers", "expected a list of layers");
  } else if (layers.IsDefined()) {
    for (std::size_t l = 0; l < layers.size(); ++l) {
      const std::string path = "layers[" + std::to_string(l) + "]";
      const YAML::Node layer = layers[l];
      r.lines[path] = lineOf(layer);
      if (!layer.IsMap()) {
        r.problem(lineOf(layer), path, "expected a map with 'weights' and 'bias'");
        doc.weights.layers.emplace_back();  // keeps the indices of the layers after it
        continue;
      }
      r.rejectUnknown(layer, path, {"weights", "bias"});
      DenseLayer dense;
      const YAML::Node rows = r.child(layer, path, "weights", lineOf(layer));
      if (rows.IsDefined()) {
        if (!rows.IsSequence() || rows.size() == 0) {
          r.problem(lineOf(rows), path + ".weights", "expected a non-empty list of rows");
        } else {
          // Columns: the features for the first layer, the previous layer's outputs after.
          // (When the previous layer was unreadable, its first row decides.)
          long cols =
              l == 0 ? kFeatureCount : static_cast<long>(doc.weights.layers[l - 1].weights.rows());
          if (cols == 0) cols = rows[0].IsSequence() ? static_cast<long>(rows[0].size()) : 0L;
          dense.weights.resize(static_cast<Eigen::Index>(rows.size()), cols);
          for (std::size_t i = 0; i < rows.size(); ++i) {
            const auto row = r.numbers(rows[i], path + ".weights[" + std::to_string(i) + "]", cols);
            if (static_cast<long>(row.size()) == cols) {
              for (long j = 0; j < cols; ++j) {
                dense.weights(static_cast<Eigen::Index>(i), j) = row[static_cast<std::size_t>(j)];
              }
            }
          }
        }
      }
      const auto bias = r.numbers(r.child(layer, path, "bias", lineOf(layer)), path + ".bias");
      dense.bias =
          Eigen::Map<const Eigen::VectorXd>(bias.data(), static_cast<Eigen::Index>(bias.size()));
      doc.weights.layers.push_back(std::move(dense));
    }
  }
  if (!r.problems.empty()) return doc;  // the numbers below would be placeholders

  // 6. hidden_widths must describe the layers (a hand-edited file is caught here).
  bool widths_match = widths.size() + 1 == doc.weights.layers.size();
  for (std::size_t i = 0; widths_match && i < widths.size(); ++i) {
    widths_match = widths[i] == static_cast<double>(doc.weights.layers[i].weights.rows());
  }
  if (!widths_match) {
    std::string actual;
    for (std::size_t i = 0; i + 1 < doc.weights.layers.size(); ++i) {
      actual += (actual.empty() ? "" : ", ") + std::to_string(doc.weights.layers[i].weights.rows());
    }
    r.problem(r.lineFor("hidden_widths"), "hidden_widths",
              "does not match the layers, whose hidden widths are [" + actual + "]");
  }

  // 7. Provenance: optional, text values only.
  for (const auto& kv : root) {
    if (!kv.first.IsScalar() || kv.first.Scalar() != "provenance") continue;
    if (!kv.second.IsMap()) {
      r.problem(lineOf(kv.first), "provenance", "expected a map of text values");
      break;
    }
    for (const auto& p : kv.second) {
      const std::string key = p.first.IsScalar() ? p.first.Scalar() : "?";
      if (!p.second.IsScalar()) {
        r.problem(lineOf(p.first), "provenance." + key, "expected text");
      } else {
        doc.provenance[key] = p.second.Scalar();
      }
    }
  }

  // 8. The network's own checks (dimension chain, σ > 0, the γ certificate), at their lines.
  for (const auto& e : doc.weights.validate()) {
    std::string key = e.field.substr(0, e.field.find(' '));
    r.problem(r.lineFor(key), key, e.value + ": expected " + e.expected);
  }
  return doc;
}

}  // namespace

std::string weightsToYaml(const WeightsDocument& doc) {
  if (auto errors = doc.weights.validate(); !errors.empty())
    throw InvalidNetwork(std::move(errors));
  const NetworkWeights& w = doc.weights;
  YAML::Emitter out;
  out << YAML::Comment("geaware Neural-Lander residual-force network (docs/neural-lander.md)");
  out << YAML::BeginMap;
  out << YAML::Key << "format" << YAML::Value << std::string(kWeightsFormat);
  out << YAML::Key << "version" << YAML::Value << kWeightsFormatVersion;
  out << YAML::Key << "features" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (auto n : featureNames()) out << std::string(n);
  out << YAML::EndSeq;
  out << YAML::Key << "hidden_widths" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (std::size_t l = 0; l + 1 < w.layers.size(); ++l) out << w.layers[l].weights.rows();
  out << YAML::EndSeq;
  out << YAML::Key << "activation" << YAML::Value << "relu";
  out << YAML::Key << "lipschitz_gamma" << YAML::Value
      << (w.lipschitz_gamma ? exact(*w.lipschitz_gamma) : std::string("none"));
  out << YAML::Key << "input_mean" << YAML::Value;
  emitRow(out, w.input_mean);
  out << YAML::Key << "input_std" << YAML::Value;
  emitRow(out, w.input_std);
  out << YAML::Key << "layers" << YAML::Value << YAML::BeginSeq;
  for (const auto& l : w.layers) {
    out << YAML::BeginMap << YAML::Key << "weights" << YAML::Value << YAML::BeginSeq;
    for (Eigen::Index i = 0; i < l.weights.rows(); ++i) emitRow(out, l.weights.row(i));
    out << YAML::EndSeq << YAML::Key << "bias" << YAML::Value;
    emitRow(out, l.bias);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  if (!doc.provenance.empty()) {
    out << YAML::Key << "provenance" << YAML::Value << YAML::BeginMap;
    for (const auto& [k, v] : doc.provenance) {
      out << YAML::Key << k << YAML::Value << YAML::DoubleQuoted << v;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

void saveWeights(const std::filesystem::path& file, const WeightsDocument& doc) {
  const std::string text = weightsToYaml(doc);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out || !(out << text) || !out.flush()) {
    throw std::runtime_error(file.string() + ": cannot write the weight file");
  }
}

WeightsDocument parseWeightsYaml(std::string_view yaml_text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml_text));
  } catch (const YAML::ParserException& e) {
    throw io::ConfigError(source, {{e.mark.line + 1, "", "not valid YAML: " + e.msg}});
  }
  Reader r;
  WeightsDocument doc = read(root, r);
  if (!r.problems.empty()) throw io::ConfigError(source, std::move(r.problems));
  return doc;
}

WeightsDocument loadWeights(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw std::runtime_error(file.string() + (std::filesystem::exists(file, ec)
                                                  ? ": not a regular file (expected a weight file)"
                                                  : ": no such weight file"));
  }
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  if (!in || !(text << in.rdbuf())) throw std::runtime_error(file.string() + ": cannot read");
  return parseWeightsYaml(text.str(), file.string());
}

}  // namespace geaware::neural
