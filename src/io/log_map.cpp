// SPDX-License-Identifier: BSD-3-Clause
// Log map files (io/log_map.hpp): strict YAML, every problem with its line.

#include "geaware/io/log_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "builtin_log_maps.hpp"
#include "geaware/io/input_file.hpp"
#include "geaware/io/yaml_reader.hpp"

namespace geaware::io {
namespace {

struct ChannelSpec {
  const char* name;
  std::size_t min_fields, max_fields;
  std::vector<std::string> frames;                  // the first is the default
  std::vector<std::pair<std::string, double>> units;  // unit → factor into SI; empty: no unit
};

const std::vector<ChannelSpec>& channelSpecs() {
  static const std::vector<ChannelSpec> specs = {
      {"height", 1, 1, {"scalar", "world_z"}, {{"m", 1.0}, {"cm", 1e-2}, {"mm", 1e-3}}},
      {"specific_force", 3, 3, {"body"}, {{"m/s^2", 1.0}, {"g", 9.80665}, {"mm/s^2", 1e-3}}},
      {"gyro", 3, 3, {"body"}, {{"rad/s", 1.0}, {"deg/s", 0.017453292519943295}}},
      {"attitude", 3, 4, {"quaternion", "euler"}, {}},
      {"velocity", 3, 3, {"world"}, {{"m/s", 1.0}, {"mm/s", 1e-3}, {"cm/s", 1e-2}}},
      {"rotor_speed", 1, 8, {"scalar"}, {{"rpm", 1.0}, {"rad/s", 9.549296585513721}}},
      {"throttle", 1, 8, {"scalar"}, {}},  // scaled by its range, not by a unit
      {"armed", 1, 1, {"scalar"}, {}},     // 1 armed, 0 disarmed (every motor stopped)
      {"battery_voltage", 1, 1, {"scalar"}, {{"V", 1.0}, {"mV", 1e-3}}},
  };
  return specs;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// Motor order of a rotor_speed or throttle channel (io/log_map.hpp, MappedChannel).
void readMotors(MapReader& r, MappedChannel& c) {
  const std::size_t n = c.fields.size();
  if (r.has("motor_of_field")) {
    c.motor_of_field = r.texts("motor_of_field");
    if (c.motor_of_field.size() != n) {
      r.problem("motor_of_field", std::to_string(c.motor_of_field.size()) + " entries, expected one per field (" +
                                      std::to_string(n) + ")");
    }
  }
  if (r.has("motor_base")) c.motor_base = static_cast<double>(r.integer("motor_base", 0, 1000));
  if (r.has("rotor_of_motor")) {
    std::vector<bool> seen(n, false);
    for (const double v : r.finiteNumbers("rotor_of_motor", n)) {
      if (v < 1.0 || v > static_cast<double>(n) || std::floor(v) != v || seen[static_cast<std::size_t>(v) - 1]) {
        r.problem("rotor_of_motor", "expected each of the rotor numbers 1 to " + std::to_string(n) + " once");
        break;
      }
      seen[static_cast<std::size_t>(v) - 1] = true;
      c.rotor_of_motor.push_back(static_cast<unsigned>(v));
    }
  }
}

// The raw range of a throttle channel and how a NaN reads (io/log_map.hpp, MappedChannel).
void readThrottle(MapReader& r, MappedChannel& c) {
  if (r.has("range")) {
    const std::vector<double> v = r.finiteNumbers("range", 2);
    if (v.size() == 2 && !(v[1] > v[0])) {
      r.problem("range", "expected [raw value at throttle 0, raw value at throttle 1] with the second larger");
    } else if (v.size() == 2) {
      c.range = {v[0], v[1]};
    }
  }
  if (r.has("range_params")) {
    c.range_params = r.texts("range_params");
    if (c.range_params.size() != 2) r.problem("range_params", "expected two parameter names (throttle 0 and 1)");
  }
  if (r.has("nan_is_stopped")) c.nan_is_stopped = r.boolean("nan_is_stopped");
}

MappedChannel readChannel(MapReader& r, const ChannelSpec& spec, const YamlContext& ctx) {
  MappedChannel c;
  c.line = ctx.lineOf(r.path());
  // No topic: each field is looked up in the one topic that has it (a Crazyflie log's variables
  // are the same in a CSV export and in either uSD format).
  if (r.has("topic")) c.topic = r.text("topic");
  if (r.has("instance")) c.instance = static_cast<unsigned>(r.integer("instance", 0, 255));
  c.fields = r.texts("fields");
  c.field_instances.assign(c.fields.size(), c.instance);
  if (r.has("instances")) {
    std::vector<unsigned> instances;
    for (const double v : r.finiteNumbers("instances")) {
      if (v < 0.0 || v > 255.0 || std::floor(v) != v) {
        r.problem("instances", "expected whole numbers in [0, 255]");
        break;
      }
      instances.push_back(static_cast<unsigned>(v));
    }
    if (c.fields.size() != 1) {
      r.problem("instances", "with instances, give one field (taken from each instance)");
    } else {
      c.fields.assign(instances.size(), c.fields.front());
      c.field_instances = instances;
    }
  }
  if (c.fields.size() < spec.min_fields || c.fields.size() > spec.max_fields) {
    r.problem("fields", std::to_string(c.fields.size()) + " fields, expected " +
                            (spec.min_fields == spec.max_fields ? std::to_string(spec.min_fields)
                                                                : std::to_string(spec.min_fields) + " to " +
                                                                      std::to_string(spec.max_fields)));
  }
  c.frame = r.has("frame") ? r.choice("frame", spec.frames) : spec.frames.front();
  const std::size_t expected = c.frame == "euler" ? 3 : c.frame == "quaternion" ? 4 : 0;
  if (expected > 0 && c.fields.size() != expected) {
    r.problem("fields", std::to_string(c.fields.size()) + " fields, a " + c.frame + " attitude has " +
                            std::to_string(expected));
  }
  // Each field is an expression (a plain name is one); one that writes units converts itself.
  bool with_units = false, without_units = false;
  for (std::size_t k = 0; k < c.fields.size(); ++k) {
    try {
      c.expressions.push_back(ColumnExpression::parse(
          c.fields[k], std::string(spec.name) + " fields[" + std::to_string(k) + "] '" + c.fields[k] + "'"));
      const ColumnExpression& e = c.expressions.back();
      if (e.hasUnits()) with_units = true;
      if (!e.hasUnits() && !e.fields().empty()) without_units = true;  // a bare number needs no unit
    } catch (const ExpressionError& e) {
      r.problem("fields", e.what());
      c.expressions.emplace_back();
    }
  }
  c.from_option.assign(c.fields.size(), false);
  std::vector<std::pair<std::string, double>> units = spec.units;
  if (c.frame == "euler") units = {{"deg", 0.017453292519943295}, {"rad", 1.0}};
  if (!units.empty() && (without_units || r.has("unit"))) {
    std::vector<std::string> names;
    for (const auto& [u, f] : units) names.push_back(u);
    c.unit = r.choice("unit", names);
    for (const auto& [u, f] : units) {
      if (u == c.unit) c.scale = f;
    }
    if (with_units) r.problem("unit", "a field writes its own unit: give every field its unit, or none and unit");
  }
  if (r.has("optional")) c.optional = r.boolean("optional");
  const std::string channel = spec.name;
  if (channel == "rotor_speed" || channel == "throttle") readMotors(r, c);
  if (channel == "rotor_speed" && r.has("pole_pairs")) c.pole_pairs = static_cast<double>(r.integer("pole_pairs", 1, 100));
  if (channel == "throttle") readThrottle(r, c);
  r.rejectUnknownKeys();
  return c;
}

}  // namespace

std::vector<std::string> builtinLogMapNames() {
  std::vector<std::string> names;
  for (const auto& m : detail::kBuiltinLogMaps) names.emplace_back(m.name);
  return names;
}

LogMap parseLogMap(const std::string& text, const std::string& source, const std::string& name) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(source, {{e.mark.line + 1, "", "not valid YAML: " + e.msg}});
  }
  if (!root.IsMap()) throw ConfigError(source, {{1, "", "expected a map with the keys family, frames, channels"}});
  YamlContext ctx;
  MapReader reader(root, "", ctx, root.Mark().line >= 0 ? root.Mark().line + 1 : 1);
  LogMap map;
  map.name = name;
  map.source = source;
  map.family = reader.text("family");
  map.frames = reader.choice("frames", {"ned_frd", "enu_flu"});
  if (reader.has("time")) {
    MapReader time = reader.map("time");
    map.time_field = time.text("field");
    const std::string unit = time.choice("unit", {"s", "ms", "us"});
    map.time_scale = unit == "s" ? 1.0 : unit == "ms" ? 1e-3 : 1e-6;
    time.rejectUnknownKeys();
  }
  MapReader channels = reader.map("channels");
  for (const auto& spec : channelSpecs()) {
    if (!channels.has(spec.name)) continue;
    MapReader r = channels.map(spec.name);
    map.channels[spec.name] = readChannel(r, spec, ctx);
  }
  if (channels.valid()) {
    std::vector<std::string> known;
    for (const auto& spec : channelSpecs()) known.emplace_back(spec.name);
    if (map.channels.empty() && ctx.problems.empty()) {
      channels.problem("", "no channel mapped (expected some of: " + joined(known) + ")");
    }
    channels.rejectUnknownKeys();
  }
  reader.rejectUnknownKeys();
  if (!ctx.problems.empty()) throw ConfigError(source, std::move(ctx.problems));
  return map;
}

LogMap loadLogMap(const std::string& name_or_file) {
  for (const auto& m : detail::kBuiltinLogMaps) {
    if (m.name == name_or_file) {
      return parseLogMap(std::string(m.yaml), "built-in map " + std::string(m.name) + " (" + std::string(m.path) + ")",
                         std::string(m.name));
    }
  }
  std::error_code ec;
  if (!std::filesystem::exists(name_or_file, ec)) {
    throw std::runtime_error("--map '" + name_or_file + "': no such map file and no built-in map of that name (built in: " +
                             joined(builtinLogMapNames()) + ")");
  }
  const std::string text = readInputFile(name_or_file, "log map file", "log map YAML file");
  return parseLogMap(text, name_or_file, std::filesystem::path(name_or_file).stem().string());
}

}  // namespace geaware::io
