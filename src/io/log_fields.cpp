// SPDX-License-Identifier: BSD-3-Clause
// Expressions on a log's channels (io/log_map.hpp): field references resolved in topics,
// evaluated on one topic's time axis; `--column`/`--const` put into a log map.

#include <algorithm>
#include <cctype>
#include <set>

#include "geaware/io/log_map.hpp"
#include "text.hpp"

namespace geaware::io {
namespace {

std::string topicText(const Topic& t) { return t.name + "[" + std::to_string(t.instance) + "]"; }

std::string fieldList(const Topic& t) {
  std::string s;
  constexpr std::size_t kShown = 40;
  for (std::size_t i = 0; i < std::min(t.channels.size(), kShown); ++i) {
    s += (i ? ", " : "") + detail::excerpt(t.channels[i].name);
  }
  if (t.channels.size() > kShown)
    s += ", … (" + std::to_string(t.channels.size() - kShown) + " more)";
  return s.empty() ? "none" : s;
}

std::string topicList(const LogData& log) {
  std::set<std::string> names;
  for (const auto& t : log.topics) names.insert(t.name);
  std::string s;
  std::size_t n = 0;
  for (const auto& name : names) {
    if (n++ == 40) {
      s += ", … (" + std::to_string(names.size() - 40) + " more)";
      break;
    }
    s += (s.empty() ? "" : ", ") + detail::excerpt(name);
  }
  return s.empty() ? "none" : s;
}

struct Resolved {
  const Topic* topic = nullptr;
  const Channel* channel = nullptr;
};

// `ref` as TOPIC.rest or TOPIC[k].rest for a topic of the log (the longest name that fits).
Resolved byTopicPrefix(const LogData& log, std::string_view ref, const std::string& topic,
                       unsigned instance) {
  Resolved best;
  std::size_t best_len = 0;
  for (const auto& t : log.topics) {
    const std::string& n = t.name;
    if (n.size() <= best_len || ref.size() <= n.size() || ref.substr(0, n.size()) != n) continue;
    std::string_view rest = ref.substr(n.size());
    unsigned want = n == topic ? instance : 0;
    if (rest.front() == '[') {
      const auto close = rest.find(']');
      if (close == std::string_view::npos || close < 2 || close + 1 >= rest.size() ||
          rest[close + 1] != '.')
        continue;
      const std::string_view digits = rest.substr(1, close - 1);
      if (!std::all_of(digits.begin(), digits.end(),
                       [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }) ||
          digits.size() > 3) {
        continue;
      }
      want = static_cast<unsigned>(std::stoul(std::string(digits)));
      rest = rest.substr(close + 1);
    }
    if (rest.size() < 2 || rest.front() != '.' || t.instance != want) continue;
    if (const Channel* c = t.channel(rest.substr(1))) best = {&t, c}, best_len = n.size();
  }
  return best;
}

}  // namespace

EvaluatedField evaluateOnLog(const ColumnExpression& e, const LogData& log,
                             const std::string& topic, unsigned instance, const Unit* target,
                             const std::string& target_name, bool log_units) {
  EvaluatedField out;
  std::vector<const Channel*> channels;
  const Topic* home = topic.empty() ? nullptr : log.topic(topic, instance);
  for (std::size_t k = 0; k < e.fields().size(); ++k) {
    const std::string& ref = e.fields()[k];
    const std::string at = e.where() + ": character " + std::to_string(e.fieldOffset(k) + 1) + ": ";
    Resolved r;
    if (home != nullptr) {
      if (const Channel* c = home->channel(ref)) r = {home, c};
    }
    if (r.channel == nullptr) r = byTopicPrefix(log, ref, topic, instance);
    if (r.channel == nullptr && topic.empty()) {
      for (const auto& t : log.topics) {
        const Channel* c = t.channel(ref);
        if (c == nullptr) continue;
        if (r.channel != nullptr) {
          throw LogError(log.source, at + "field '" + detail::excerpt(ref) + "' is in " +
                                         topicText(*r.topic) + " and in " + topicText(t) +
                                         ": name the topic, e.g. " + t.name + "[" +
                                         std::to_string(t.instance) + "]." + ref);
        }
        r = {&t, c};
      }
    }
    if (r.channel == nullptr) {
      if (!topic.empty() && home == nullptr) {
        throw MissingFieldError(log.source, at + "the log has no topic '" + topic + "' instance " +
                                                std::to_string(instance) +
                                                " (its topics: " + topicList(log) + ")");
      }
      if (home != nullptr) {
        throw MissingFieldError(log.source, at + "topic " + topicText(*home) + " has no field '" +
                                                detail::excerpt(ref) +
                                                "' (its fields: " + fieldList(*home) + ")");
      }
      throw MissingFieldError(log.source, at + "no topic of the log has a field '" +
                                              detail::excerpt(ref) +
                                              "' (its topics: " + topicList(log) + ")");
    }
    if (out.topic != nullptr && out.topic != r.topic) {
      throw LogError(log.source,
                     at + "field '" + detail::excerpt(ref) + "' is in " + topicText(*r.topic) +
                         ", an earlier one in " + topicText(*out.topic) +
                         ": the fields of one expression come from one topic (one time axis)");
    }
    out.topic = r.topic;
    channels.push_back(r.channel);
  }
  std::vector<ColumnExpression::FieldData> data;
  for (const Channel* c : channels) data.push_back({c->values, c->unit});
  const std::size_t rows = out.topic != nullptr ? out.topic->size() : 1;
  out.values = e.evaluate(data, rows, target, target_name, log_units);
  return out;
}

std::vector<std::string> mappedColumnNames() {
  return {"h_m",          "a_x_mps2", "a_y_mps2", "a_z_mps2", "gyro_x_radps", "gyro_y_radps",
          "gyro_z_radps", "qw",       "qx",       "qy",       "qz",           "vx_mps",
          "vy_mps",       "vz_mps",   "n1_rpm",   "n2_rpm",   "n3_rpm",       "n4_rpm",
          "n5_rpm",       "n6_rpm",   "n7_rpm",   "n8_rpm",   "throttle1",    "throttle2",
          "throttle3",    "throttle4", "throttle5", "throttle6", "throttle7",   "throttle8",
          "armed",        "vbat_V"};
}

namespace {

// The channel and component a column defines.
struct Slot {
  std::string channel;
  std::size_t component = 0;
};

Slot slotOf(const std::string& name) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> channels = {
      {"height", {"h_m"}},
      {"specific_force", {"a_x_mps2", "a_y_mps2", "a_z_mps2"}},
      {"gyro", {"gyro_x_radps", "gyro_y_radps", "gyro_z_radps"}},
      {"attitude", {"qw", "qx", "qy", "qz"}},
      {"velocity", {"vx_mps", "vy_mps", "vz_mps"}},
      {"rotor_speed",
       {"n1_rpm", "n2_rpm", "n3_rpm", "n4_rpm", "n5_rpm", "n6_rpm", "n7_rpm", "n8_rpm"}},
      {"throttle",
       {"throttle1", "throttle2", "throttle3", "throttle4", "throttle5", "throttle6", "throttle7", "throttle8"}},
      {"armed", {"armed"}},
      {"battery_voltage", {"vbat_V"}}};
  for (const auto& [channel, names] : channels) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it != names.end()) {
      return {channel, static_cast<std::size_t>(it - names.begin())};
    }
  }
  return {};
}

}  // namespace

void applyColumnDefinitions(LogMap& map, const std::vector<ColumnDefinition>& definitions) {
  std::set<std::string> created;
  for (const auto& d : definitions) {
    const Slot slot = slotOf(d.name);
    if (slot.channel.empty()) {
      std::string names;
      for (const auto& n : mappedColumnNames()) names += (names.empty() ? "" : ", ") + n;
      throw ExpressionError(d.option + ": character 1: '" + d.name +
                            "' is not a column a log map has (" + names + ")");
    }
    auto it = map.channels.find(slot.channel);
    if (it == map.channels.end()) {
      MappedChannel c;
      c.frame = slot.channel == "attitude"                                   ? "quaternion"
                : slot.channel == "specific_force" || slot.channel == "gyro" ? "body"
                : slot.channel == "velocity"                                 ? "world"
                                                                             : "scalar";
      it = map.channels.emplace(slot.channel, std::move(c)).first;
      created.insert(slot.channel);
    }
    MappedChannel& c = it->second;
    if (slot.channel == "attitude" && c.frame != "quaternion") {
      throw ExpressionError(d.option + ": character 1: the map's attitude is " + c.frame +
                            " angles; qw … qz replace a quaternion only");
    }
    const std::size_t n = std::max(c.fields.size(), slot.component + 1);
    c.fields.resize(n);
    c.field_instances.resize(n, c.instance);
    c.expressions.resize(n);
    c.from_option.resize(n, false);
    c.fields[slot.component] = d.expression.text();
    c.expressions[slot.component] = d.expression;
    c.from_option[slot.component] = true;
  }
  for (const auto& name : created) {
    const MappedChannel& c = map.channels.at(name);
    for (std::size_t k = 0; k < c.fields.size(); ++k) {
      if (!c.from_option[k]) {
        throw ExpressionError("--column: the map " + map.source + " has no " + name +
                              ": define all " + std::to_string(c.fields.size()) +
                              " of its columns (component " + std::to_string(k + 1) +
                              " is missing)");
      }
    }
    if ((name == "specific_force" || name == "gyro" || name == "velocity") &&
        c.fields.size() != 3) {
      throw ExpressionError("--column: the map " + map.source + " has no " + name +
                            ": define all 3 of its columns");
    }
    if (name == "attitude" && c.fields.size() != 4) {
      throw ExpressionError("--column: the map " + map.source +
                            " has no attitude: define qw, qx, qy and qz");
    }
  }
}

}  // namespace geaware::io
