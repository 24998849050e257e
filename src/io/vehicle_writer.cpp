// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/vehicle_writer.hpp"

#include "geaware/io/output_file.hpp"

#include <algorithm>
#include <exception>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <yaml-cpp/yaml.h>

#include "geaware/io/config_error.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/vehicle_schema.hpp"
#include "vehicle_text.hpp"

namespace geaware::io {
namespace {

using namespace detail;

/// Value read back from a parsed vehicle for a fitted key, by the schema's accessor.
std::vector<double> readBack(const model::VehicleParams& p, const std::string& key) {
  const auto* s = model::vehicleSchema().find(key);
  if (s == nullptr) throw std::logic_error("readBack: unknown key " + key);
  if (s->kind == model::ParamKind::kList) return s->listOf(p);
  return {s->numberOf(p)};
}

YAML::Node flowList(const std::vector<double>& values) {
  YAML::Node seq(YAML::NodeType::Sequence);
  for (const double v : values) seq.push_back(formatNumber(v));
  seq.SetStyle(YAML::EmitterStyle::Flow);
  return seq;
}

/// Re-emits the whole document with the values set (comments are lost).
std::string reemit(const std::string& base_text, const VehicleUpdate& update,
                   const std::vector<SectionRewrite>& rewrites) {
  YAML::Node root = YAML::Load(base_text);
  for (const auto& r : rewrites) {
    YAML::Node section(YAML::NodeType::Map);
    if (r.table != nullptr) {
      YAML::Node table(YAML::NodeType::Map);
      table["heights_m"] = flowList(r.table->heights_m);
      table[r.section->values_key] = flowList(r.table->values);
      section["table"] = table;
    } else {
      for (std::size_t i = 0; i < r.formula.size(); ++i) {
        section[r.section->formula_keys[i]] = formatNumber(r.formula[i]->values.front());
      }
    }
    root["ground_effect"][r.section->name] = section;
  }
  for (const auto& e : update.entries()) {
    if (rewritten(rewrites, e)) continue;
    const auto parts = splitPath(e.key);
    YAML::Node node = root;
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      YAML::Node child = node[parts[i]];
      node.reset(child);
    }
    if (e.list) {
      node[parts.back()] = flowList(e.values);
    } else {
      node[parts.back()] = formatNumber(e.values.front());
    }
  }
  YAML::Emitter emitter;
  emitter << root;
  return std::string(emitter.c_str()) + "\n";
}

bool readsBackAs(const std::vector<double>& got, const std::vector<double>& written) {
  if (got.size() != written.size()) return false;
  for (std::size_t i = 0; i < got.size(); ++i) {
    if (got[i] != written[i]) return false;  // bit for bit: formatNumber round-trips
  }
  return true;
}

/// Parses the merged text and checks every merged value reads back as written.
bool readsBack(const std::string& text, const std::string& name, const VehicleUpdate& update) {
  const model::VehicleParams p = io::parseVehicleYaml(text, name);
  for (const auto& e : update.entries()) {
    if (e.table) {
      const model::HeightTableParams& t = tableOf(p, *sectionByPath(e.key));
      if (!readsBackAs(t.heights_m, e.heights_m) || !readsBackAs(t.values, e.values)) return false;
      continue;
    }
    // A formula key is only in use when its curve is not a table.
    if (const CurveSection* s = sectionOfKey(e.key); s != nullptr && !tableOf(p, *s).empty()) {
      return false;
    }
    if (!readsBackAs(readBack(p, e.key), e.values)) return false;
  }
  return true;
}

}  // namespace

// ------------------------------------------------------------------------------- the merge

MergeResult mergeVehicleYaml(std::string_view base_text, const std::string& base_name,
                             const VehicleUpdate& update) {
  const std::string text(base_text);
  // The base must itself be a valid vehicle file: merging into a broken one would hide its
  // problems behind ours.
  (void)io::parseVehicleYaml(text, base_name);
  MergeResult result;
  const YAML::Node root = YAML::Load(text);

  std::vector<std::string> lines;
  {
    std::size_t pos = 0;
    for (;;) {
      const std::size_t nl = text.find('\n', pos);
      lines.push_back(text.substr(pos, nl == std::string::npos ? nl : nl - pos));
      if (nl == std::string::npos) break;
      pos = nl + 1;
    }
  }
  const std::vector<SectionRewrite> rewrites = sectionRewrites(root, update);
  bool in_place = true;
  std::exception_ptr in_place_error;
  // Locate the rewritten sections first, while the line numbers are yaml-cpp's.
  std::vector<std::pair<SectionSpan, const SectionRewrite*>> spans;
  for (const auto& r : rewrites) {
    const auto span = locateSection(lines, root, *r.section);
    if (!span) {
      result.notes.push_back("section '" + r.section->path +
                             "' is not a block map under its own key line in the base file");
      in_place = false;
      break;
    }
    spans.emplace_back(*span, &r);
  }
  for (const auto& e : update.entries()) {
    if (!in_place) break;
    if (rewritten(rewrites, e)) continue;
    const YAML::Node node = find(root, e.key);
    if (!node.IsDefined()) {
      result.notes.push_back("key '" + e.key + "' is not in the base file");
      in_place = false;
      break;
    }
    if (!replaceInLine(lines, node, update, e)) {
      result.notes.push_back("key '" + e.key + "' is not written as a plain value" +
                             std::string(e.list ? " or a one-line flow list" : "") +
                             " in the base file");
      in_place = false;
      break;
    }
  }
  if (in_place) {
    // Bottom up, so the spans above stay where they are.
    std::sort(spans.begin(), spans.end(),
              [](const auto& a, const auto& b) { return a.first.key_line > b.first.key_line; });
    for (const auto& [span, r] : spans) rewriteSection(lines, span, *r, update);
    std::string merged;
    for (std::size_t i = 0; i < lines.size(); ++i) merged += lines[i] + (i + 1 < lines.size() ? "\n" : "");
    try {
      if (readsBack(merged, base_name + " (merged)", update)) {
        result.yaml = std::move(merged);
        return result;
      }
      result.notes.push_back("the line-level edit did not read back as written");
    } catch (const io::ConfigError& e) {
      // The values or the edit are at fault: re-emitting tells which.
      in_place_error = std::current_exception();
      result.notes.push_back("the line-level edit did not load: " + std::string(e.what()));
    }
  }
  result.comments_preserved = false;
  result.notes.push_back("the file was re-emitted: every key is kept, the comments are lost");
  result.yaml = reemit(text, update, rewrites);
  bool ok = false;
  try {
    ok = readsBack(result.yaml, base_name + " (merged)", update);
  } catch (const io::ConfigError&) {
    // The values are invalid: the in-place edit's error has the base file's line numbers.
    if (in_place_error) std::rethrow_exception(in_place_error);
    throw;
  }
  if (!ok)
    throw std::runtime_error("mergeVehicleYaml: the re-emitted vehicle file does not read back");
  return result;
}

MergeResult writeVehicleFile(const std::filesystem::path& base, const std::filesystem::path& out,
                             const VehicleUpdate& update) {
  std::ifstream in(base, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read the base vehicle file " + base.string());
  std::ostringstream buf;
  buf << in.rdbuf();
  return writeVehicleFile(buf.str(), base.string(), out, update);
}

MergeResult writeVehicleFile(std::string_view base_text, const std::string& base_name,
                             const std::filesystem::path& out, const VehicleUpdate& update) {
  MergeResult result = mergeVehicleYaml(base_text, base_name, update);
  writeFileAtomically(out.string(), result.yaml, "the vehicle file");
  return result;
}

}  // namespace geaware::io

