// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/input_file.hpp"
#include "geaware/io/truth_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <yaml-cpp/yaml.h>

#include "geaware/io/format_version.hpp"
#include "geaware/io/param_reader.hpp"
#include "geaware/io/yaml_reader.hpp"
#include "geaware/model/field_check.hpp"
#include "geaware/model/vehicle_schema.hpp"
#include "builtin_truths.hpp"

namespace geaware::io {
namespace {

constexpr const char* kSection = "truth";

std::vector<std::string> splitKey(std::string_view key) { return detail::splitKey(key); }

/// The maps of the `truth:` section, opened as the keys need them: a section absent from the
/// file is not opened (its keys keep their defaults). Unknown keys are checked separately
/// (rejectUnknownKeys below), against the table rather than against the keys read.
class SectionMaps {
 public:
  explicit SectionMaps(MapReader& truth) : truth_(truth) {}
  SectionMaps(const SectionMaps&) = delete;
  SectionMaps& operator=(const SectionMaps&) = delete;
  ~SectionMaps() = default;

  /// The reader of the map holding `key`'s leaf, or null when a section on the way is absent.
  MapReader* holderOf(const std::vector<std::string>& parts) {
    MapReader* m = &truth_;
    std::string path;
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      path += (path.empty() ? "" : ".") + parts[i];
      auto it = open_.find(path);
      if (it == open_.end()) {
        if (!m->has(parts[i])) return nullptr;
        it = open_.emplace(path, std::make_unique<MapReader>(m->map(parts[i]))).first;
      }
      m = it->second.get();
    }
    return m;
  }

 private:
  MapReader& truth_;
  std::map<std::string, std::unique_ptr<MapReader>> open_;
};

/// Every section path of the table ("" the section itself, "sensors.imu", …) → its keys and
/// subsections.
std::map<std::string, std::set<std::string>> expectedKeys() {
  std::map<std::string, std::set<std::string>> out;
  for (const TruthKey& k : truthFileKeys()) {
    const auto parts = splitKey(k.key);
    std::string path;
    for (const auto& part : parts) {
      out[path].insert(part);
      path += (path.empty() ? "" : ".") + part;
    }
  }
  return out;
}

/// Reports every key of the section's maps that the table does not have, at its line, with the
/// keys expected there.
void rejectUnknownKeys(const YAML::Node& node, const std::string& path,
                       const std::map<std::string, std::set<std::string>>& expected,
                       YamlContext& ctx) {
  if (!node.IsMap()) return;  // reported where it was read
  const auto& keys = expected.at(path);
  for (const auto& kv : node) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : std::string("?");
    const std::string child = path.empty() ? key : path + "." + key;
    if (!keys.contains(key)) {
      std::string list;
      for (const auto& k : keys) list += (list.empty() ? "" : ", ") + k;
      ctx.problem(kv.first.Mark().line + 1, std::string(kSection) + "." + child,
                  "unknown key (expected one of: " + list + ")");
    } else if (expected.contains(child)) {
      rejectUnknownKeys(kv.second, child, expected, ctx);
    }
  }
}

bool inRange(const TruthKey& k, double v) {
  return std::isfinite(v) && (k.lo_exclusive ? v > k.lo : v >= k.lo) && v <= k.hi;
}

std::string unitText(const TruthKey& k) { return k.unit.empty() ? std::string() : " " + std::string(k.unit); }

/// Reads one key into the world (file unit → the world's), checking its range.
void readKey(MapReader& m, const TruthKey& k, const std::string& leaf, sim::World& w,
             YamlContext& ctx) {
  const std::string path = std::string(kSection) + "." + std::string(k.key);
  switch (k.kind) {
    case TruthValueKind::kBoolean: k.flag(w) = m.boolean(leaf); return;
    case TruthValueKind::kInteger: {
      k.set_integer(w, m.integer(leaf, static_cast<long>(k.lo), static_cast<long>(k.hi)));
      return;
    }
    default: break;
  }
  std::vector<double> values;
  if (k.kind == TruthValueKind::kNumber) {
    values.push_back(m.finiteNumber(leaf));
  } else if (k.kind == TruthValueKind::kVector) {
    values = m.finiteNumbers(leaf, k.cols);
  } else {
    const auto rows = m.finiteRows(leaf, k.cols);
    if (rows.size() != k.rows && ctx.lines.contains(path)) {
      ctx.problem(ctx.lineOf(path), path,
                  fmt::format("has {} rows, expected {} (one per motor, mixer order)", rows.size(), k.rows));
    }
    for (const auto& r : rows) values.insert(values.end(), r.begin(), r.end());
  }
  if (values.size() != k.count()) return;  // already reported
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double v = values[i];
    if (std::isnan(v)) return;  // already reported
    if (!inRange(k, v)) {
      const std::string item = k.kind == TruthValueKind::kNumber ? path
                               : k.kind == TruthValueKind::kVector
                                   ? fmt::format("{}[{}]", path, i)
                                   : fmt::format("{}[{}][{}]", path, i / k.cols, i % k.cols);
      ctx.problem(ctx.lineOf(item), item,
                  "got " + model::formatValue(v) + ", expected " + k.validText() + unitText(k));
      continue;
    }
    k.number(w, i) = v * k.to_si;
  }
}

void readTruthSection(const YAML::Node& doc, MapReader& root, sim::World& w, YamlContext& ctx) {
  if (!root.has(kSection)) return;
  MapReader truth = root.map(kSection);
  SectionMaps maps(truth);
  for (const TruthKey& k : truthFileKeys()) {
    const auto parts = splitKey(k.key);
    MapReader* m = maps.holderOf(parts);
    if (m == nullptr || !m->has(parts.back())) continue;
    readKey(*m, k, parts.back(), w, ctx);
  }
  static const auto expected = expectedKeys();
  rejectUnknownKeys(doc[kSection], "", expected, ctx);
}

/// A sim field path ("thrust_multiplier[2]", "imu.rate_Hz") as the truth file's key path.
std::string keyOfField(const std::string& prefix, std::string field) {
  static const std::vector<std::pair<std::string, std::string>> kAliases = {
      {"thrust_multiplier", "motor_k_T_scale"}, {"torque_multiplier", "motor_k_I_scale"},
      {"thrust_axis_tilt_rad", "thrust_axis_tilt_deg"}, {"cog_offset_B", "cog_offset_m"}};
  for (const auto& [from, to] : kAliases) {
    if (field.rfind(from, 0) == 0) field = to + field.substr(from.size());
  }
  return std::string(kSection) + "." + prefix + field;
}

/// The simulator's own checks across keys (speeds, voltages, ranges against each other), each
/// reported at its key's line (or the nearest section's).
void validateWorld(const sim::World& w, YamlContext& ctx) {
  const auto report = [&ctx](const std::string& prefix, const std::vector<model::FieldError>& errors) {
    for (const auto& e : errors) {
      const std::string key = keyOfField(prefix, e.field);
      ctx.problem(ctx.lineOf(key), key, "got " + e.value + ", expected " + e.expected);
    }
  };
  report("", w.truth.validate());  // the aerodynamics' too (keys aero.…)
  report("sensors.", w.sensors.validate());
  if (w.ground_turbulence) report("disturbances.ground_turbulence.", w.ground_turbulence_params.validate());
  report("disturbances.altitude_unsteadiness.", w.altitude_unsteadiness_params.validate());
  if (w.room_air) report("disturbances.room_air.", w.room_air_params.validate());
}

std::string yamlNumber(double v) { return fmt::format("{}", v); }

}  // namespace

sim::World parseTruthYaml(std::string_view yaml_text, const std::string& source) {
  YAML::Node doc;
  try {
    doc = YAML::Load(std::string(yaml_text));
  } catch (const YAML::ParserException& e) {
    throw ConfigError(source, {{e.mark.line + 1, "", "not valid YAML: " + e.msg}});
  }
  if (!doc.IsMap()) {
    throw ConfigError(source, {{1, "", "expected a map (a vehicle file with an optional 'truth' "
                                      "section) at the top level"}});
  }
  YamlContext ctx;
  MapReader root(doc, "", ctx);
  (void)readFormatVersion(root, ctx, source);
  // The vehicle part: the vehicle file's schema, read as the vehicle reader reads it.
  model::VehicleParams vehicle;
  readParameters(root, model::vehicleSchema(), vehicle);
  const bool vehicle_read = ctx.problems.empty();
  if (vehicle_read) {
    for (const auto& e : vehicle.validate()) {
      ctx.problem(ctx.lineOf(e.field), e.field, "got " + e.value + ", expected " + e.expected);
    }
  }
  // The world starts as the vehicle's ideal world; the truth section changes it.
  sim::World w = sim::idealWorld(vehicle, source);
  readTruthSection(doc, root, w, ctx);
  root.rejectUnknownKeys();
  if (ctx.problems.empty()) validateWorld(w, ctx);
  if (!ctx.problems.empty()) throw ConfigError(source, std::move(ctx.problems));
  return w;
}

sim::World loadTruthFile(const std::filesystem::path& file) {
  return parseTruthYaml(readInputFile(file, "truth file", "truth YAML file"), file.string());
}

std::string truthSectionYaml(const sim::World& world) {
  sim::World w = world;  // the accessors take a mutable world
  std::string out = std::string(kSection) + ":\n";
  std::vector<std::string> open;  // the sections of the previous key
  for (const TruthKey& k : truthFileKeys()) {
    auto parts = splitKey(k.key);
    const std::string leaf = parts.back();
    parts.pop_back();
    std::size_t common = 0;
    while (common < open.size() && common < parts.size() && open[common] == parts[common]) ++common;
    for (std::size_t i = common; i < parts.size(); ++i) {
      out += std::string(2 * (i + 1), ' ') + parts[i] + ":\n";
    }
    open = parts;
    out += std::string(2 * (parts.size() + 1), ' ') + leaf + ": ";
    switch (k.kind) {
      case TruthValueKind::kBoolean: out += k.flag(w) ? "true" : "false"; break;
      case TruthValueKind::kInteger: out += std::to_string(k.get_integer(w)); break;
      case TruthValueKind::kNumber: out += yamlNumber(k.number(w, 0) / k.to_si); break;
      case TruthValueKind::kVector:
      case TruthValueKind::kRows: {
        std::string list;
        for (std::size_t i = 0; i < k.count(); ++i) {
          const bool row_start = k.kind == TruthValueKind::kRows && i % k.cols == 0;
          if (i > 0) list += row_start ? "], " : ", ";
          if (row_start) list += "[";
          list += yamlNumber(k.number(w, i) / k.to_si);
        }
        if (k.kind == TruthValueKind::kRows) list += "]";
        out += "[" + list + "]";
        break;
      }
    }
    out += "\n";
  }
  return out;
}

std::vector<std::string> builtinTruthNames() {
  std::vector<std::string> names;
  for (const auto& b : detail::kBuiltinTruths) names.emplace_back(b.name);
  return names;
}

namespace {
const detail::BuiltinTruth& builtin(std::string_view name) {
  for (const auto& b : detail::kBuiltinTruths) {
    if (b.name == name) return b;
  }
  std::string names;
  for (const auto& b : detail::kBuiltinTruths) names += (names.empty() ? "" : ", ") + std::string(b.name);
  throw std::invalid_argument("no built-in truth '" + std::string(name) + "' (built in: " + names + ")");
}
}  // namespace

sim::World builtinTruth(std::string_view name) {
  const auto& b = builtin(name);
  return parseTruthYaml(b.yaml, std::string(b.path));
}

std::string builtinTruthPath(std::string_view name) { return std::string(builtin(name).path); }

sim::World resolveTruth(const std::string& reference, const std::filesystem::path& base_dir) {
  for (const auto& b : detail::kBuiltinTruths) {
    if (b.name == reference) return builtinTruth(reference);
  }
  const std::filesystem::path p(reference);
  return loadTruthFile(p.is_absolute() || base_dir.empty() ? p : base_dir / p);
}

}  // namespace geaware::io
