// SPDX-License-Identifier: BSD-3-Clause
// mapFlight (io/log_map.hpp): mapped channels onto one time axis, in SI units and ENU/FLU.

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include <Eigen/Geometry>

#include "geaware/io/log_map.hpp"

namespace geaware::io {
namespace {

// One mapped channel as read: each component's values (SI, rpm for rotor speeds) on its topic's
// time axis, or a constant (no topic, one value).
struct Component {
  const Topic* topic = nullptr;
  std::vector<double> values;
  std::string field;  // as the map or the option wrote it
};
struct Series {
  std::string name;
  std::vector<Component> parts;
  const MappedChannel* spec = nullptr;
};

// The unit a channel's values are in once mapped (an expression with units is converted to it).
const Unit* channelUnit(const std::string& name, const MappedChannel& c) {
  if (name == "height") return findUnit("m");
  if (name == "specific_force") return findUnit("m/s^2");
  if (name == "gyro") return findUnit("rad/s");
  if (name == "velocity") return findUnit("m/s");
  if (name == "rotor_speed") return findUnit("rpm");
  if (name == "battery_voltage") return findUnit("V");
  if (name == "attitude" && c.frame == "euler") return findUnit("rad");
  return nullptr;
}

// The message of a LogError without its "SOURCE: " prefix.
std::string detailOf(const LogError& e) {
  const std::string what = e.what();
  return what.size() > e.file().size() + 2 ? what.substr(e.file().size() + 2) : what;
}

// The raw values that are throttle 0 and 1: the logged parameters the map names when the log
// has both and they make a range (ArduPilot leaves MOT_PWM_MIN and MOT_PWM_MAX at 0 to mean
// "the throttle channel's"), else the map's range. `notes` (when given) is told which.
std::array<double, 2> throttleRange(const LogData& log, const MappedChannel& c, std::vector<std::string>* notes) {
  std::array<double, 2> range = c.range;
  std::string why;
  if (c.range_params.size() == 2) {
    const auto lo = log.parameters.find(c.range_params[0]);
    const auto hi = log.parameters.find(c.range_params[1]);
    if (lo == log.parameters.end() || hi == log.parameters.end()) {
      why = "the log has no " + (lo == log.parameters.end() ? c.range_params[0] : c.range_params[1]);
    } else if (!(std::isfinite(lo->second) && std::isfinite(hi->second) && hi->second > lo->second &&
                 lo->second > 0.0)) {
      why = c.range_params[0] + " and " + c.range_params[1] + " do not make a range";
    } else {
      range = {lo->second, hi->second};
      why = "from " + c.range_params[0] + " and " + c.range_params[1];
    }
  }
  if (notes != nullptr) {
    char text[96];
    std::snprintf(text, sizeof text, "throttle: raw %g is 0 and %g is 1", range[0], range[1]);
    const bool from_log = why.rfind("from ", 0) == 0;
    const std::string origin = from_log ? why : "the map's range" + (why.empty() ? "" : ": " + why);
    notes->push_back(text + (" (" + origin + ")") + (c.nan_is_stopped ? "; a NaN is a stopped motor" : ""));
  }
  return range;
}

std::optional<Series> find(const LogData& log, const LogMap& map, const std::string& name,
                           std::vector<std::string>& notes) {
  const auto it = map.channels.find(name);
  if (it == map.channels.end()) {
    throw LogError(log.source, "the map " + map.source + " does not say which field is '" + name +
                                   "', which this fit needs");
  }
  const MappedChannel& c = it->second;
  Series s{name, {}, &c};
  const std::string where =
      "channel '" + name + "' of the map " + map.source + (c.line > 0 ? ":" + std::to_string(c.line) : "");
  for (std::size_t k = 0; k < c.fields.size(); ++k) {
    const unsigned instance = k < c.field_instances.size() ? c.field_instances[k] : c.instance;
    const bool option = k < c.from_option.size() && c.from_option[k];
    const ColumnExpression& e = c.expressions.at(k);
    const bool own_units = option || e.hasUnits();
    EvaluatedField f;
    try {
      f = evaluateOnLog(e, log, c.topic, instance, channelUnit(name, c), name, own_units);
    } catch (const MissingFieldError& error) {
      if (c.optional && !option) {
        notes.push_back(where + " (optional) left out: " + detailOf(error));
        return std::nullopt;
      }
      throw LogError(log.source, where + (option ? "" : " (required; `optional: true` in the map lets a log lack it)") +
                                     ": " + detailOf(error));
    }
    if (f.topic != nullptr && f.topic->size() < 2) {
      throw LogError(log.source, where + ": topic '" + f.topic->name + "' has " + std::to_string(f.topic->size()) +
                                     " samples");
    }
    // The map's unit, and electrical to mechanical rpm, for the map's own fields.
    const double scale = option ? 1.0 : (own_units ? 1.0 : c.scale) / (name == "rotor_speed" ? c.pole_pairs : 1.0);
    if (scale != 1.0) {
      for (auto& v : f.values) v *= scale;
    }
    if (name == "throttle") {
      // Into 0…1, and −1 for a stopped motor: a NaN where the map says so (PX4; its 0 is then an
      // armed motor at idle), else a value at or below throttle 0 (a disarmed ArduPilot output
      // at MOT_PWM_MIN, a Crazyflie motor at 0).
      const std::array<double, 2> range =
          option ? std::array<double, 2>{0.0, 1.0} : throttleRange(log, c, k == 0 ? &notes : nullptr);
      const bool nan_stops = c.nan_is_stopped && !option;
      for (auto& v : f.values) {
        if (std::isnan(v)) {
          if (nan_stops) v = kStoppedThrottle;
          continue;
        }
        v = (v - range[0]) / (range[1] - range[0]);
        if (!nan_stops && v <= 0.0) v = kStoppedThrottle;
      }
    }
    s.parts.push_back({f.topic, std::move(f.values), c.fields[k]});
  }
  return s;
}

// The log's motor number (1-based) of each rotor_speed field: from the map's numbers, a field
// of the log (its last value) or a logged parameter, motor_base meaning motor 1. Where the log
// does not say (no such field or parameter, a value that is no motor, two fields on one motor)
// the fields are taken in order, with a warning: a log from another firmware version must still
// be read, and a hover fit uses the sum of n² only.
std::vector<unsigned> motorNumbers(const LogData& log, const LogMap& map, const std::string& channel,
                                   const MappedChannel& c, std::vector<std::string>& warnings) {
  const std::size_t n = c.fields.size();
  std::vector<unsigned> in_order(n);
  for (std::size_t k = 0; k < n; ++k) in_order[k] = static_cast<unsigned>(k + 1);
  if (c.motor_of_field.empty()) return in_order;
  const auto fallback = [&](const std::string& why) {
    warnings.push_back(channel + " motor_of_field of the map " + map.source + ": " + why +
                       ": the fields are taken as motors 1 to " + std::to_string(n) + " in order");
    return in_order;
  };
  std::vector<unsigned> motors(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::string& m = c.motor_of_field[k];
    double value = 0.0;
    if (m.rfind("param:", 0) == 0) {
      const auto p = log.parameters.find(m.substr(6));
      if (p == log.parameters.end()) return fallback("the log has no parameter '" + m.substr(6) + "'");
      value = p->second;
    } else if (!m.empty() && std::isdigit(static_cast<unsigned char>(m.front())) != 0) {
      value = std::strtod(m.c_str(), nullptr);
    } else {
      const Topic* t = log.topic(c.topic, k < c.field_instances.size() ? c.field_instances[k] : c.instance);
      const Channel* ch = t != nullptr ? t->channel(m) : nullptr;
      if (ch == nullptr || ch->values.empty()) return fallback("the log has no field '" + m + "' in " + c.topic);
      value = ch->values.back();
    }
    const double motor = value - c.motor_base + 1.0;
    if (!(motor >= 1.0 && motor <= static_cast<double>(n)) || std::floor(motor) != motor) {
      char text[32];
      std::snprintf(text, sizeof text, "%g", value);
      return fallback("'" + m + "' is " + text + ", not one of motors 1 to " + std::to_string(n));
    }
    motors[k] = static_cast<unsigned>(motor);
    for (std::size_t j = 0; j < k; ++j) {
      if (motors[j] == motors[k]) {
        return fallback("'" + c.motor_of_field[j] + "' and '" + m + "' are both motor " + std::to_string(motors[k]));
      }
    }
  }
  return motors;
}

// Puts rotor speeds or throttles into geaware's rotor order (model::Mixer).
void toRotorOrder(const LogData& log, const LogMap& map, Series& s, std::vector<std::string>& notes,
                  std::vector<std::string>& warnings) {
  const MappedChannel& c = *s.spec;
  if (std::find(c.from_option.begin(), c.from_option.end(), true) != c.from_option.end()) {
    notes.push_back(s.name + ": --column gives them in geaware's rotor order; the map's motor order is not applied");
    return;
  }
  const std::vector<unsigned> motors = motorNumbers(log, map, s.name, c, warnings);
  std::vector<Component> ordered(s.parts.size());
  for (std::size_t k = 0; k < s.parts.size(); ++k) {
    const unsigned motor = motors[k];
    const unsigned rotor = c.rotor_of_motor.empty() ? motor : c.rotor_of_motor[motor - 1];
    ordered[rotor - 1] = std::move(s.parts[k]);
  }
  s.parts = std::move(ordered);
  if (!c.motor_of_field.empty() || !c.rotor_of_motor.empty()) {
    std::string text = s.name + " in geaware's rotor order:";
    for (std::size_t r = 0; r < s.parts.size(); ++r) {
      text += (r ? ", " : " ") + std::to_string(r + 1) + " = " + s.parts[r].field;
    }
    notes.push_back(text);
  }
}

std::string topicName(const Topic& t) { return t.name + "[" + std::to_string(t.instance) + "]"; }

// The time axis of each topic used: its own, or the map's time field scaled (a CSV export whose
// `timestamp` is in ms, not the µs readLog assumes).
class TimeAxes {
 public:
  TimeAxes(const LogMap& map, const LogData& log)
      : map_(map), source_(log.source), csv_(log.format == "csv" || log.format == "mat") {}
  const std::vector<double>& of(const Topic& t) {
    if (map_.time_field.empty()) return t.time_s;
    auto it = axes_.find(&t);
    if (it != axes_.end()) return it->second;
    const Channel* c = nullptr;
    for (const auto& ch : t.channels) {
      if (lowered(ch.name) == lowered(map_.time_field)) c = &ch;
    }
    if (c == nullptr && !csv_) return t.time_s;  // a binary log's own time axis
    if (c == nullptr) {
      throw LogError(source_, "topic '" + t.name + "' has no time field '" + map_.time_field + "' (time in " + map_.source + ")");
    }
    std::vector<double> axis(c->values);
    for (auto& v : axis) v *= map_.time_scale;
    return axes_.emplace(&t, std::move(axis)).first->second;
  }

 private:
  static std::string lowered(std::string s) {
    for (auto& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return s;
  }
  const LogMap& map_;
  std::string source_;
  bool csv_ = true;  // the map's time field is the time of a CSV export or a .mat file; logs have their own
  std::map<const Topic*, std::vector<double>> axes_;
};

const std::vector<double> kNoAxis;  // a constant's (never read)

// One row of channel `name` into `out`.
void store(const std::string& name, const std::vector<double>& r, MappedFlight& out) {
  if (name == "height") out.h_m.push_back(r[0]);
  if (name == "battery_voltage") out.vbat_V.push_back(r[0]);
  if (name == "armed") out.armed.push_back(r[0]);
  for (std::size_t i = 0; i < 3 && r.size() >= 3; ++i) {
    if (name == "specific_force") out.f_B_mps2[i].push_back(r[i]);
    if (name == "gyro") out.gyro_B_radps[i].push_back(r[i]);
    if (name == "velocity") out.v_W_mps[i].push_back(r[i]);
  }
  if (name == "attitude") {
    for (std::size_t i = 0; i < 4; ++i) out.q_WB[i].push_back(r[i]);
  }
  if (name == "rotor_speed" || name == "throttle") {
    auto& per_rotor = name == "rotor_speed" ? out.n_rpm : out.throttle;
    per_rotor.resize(r.size());
    for (std::size_t i = 0; i < r.size(); ++i) per_rotor[i].push_back(r[i]);
  }
}

double rateOf(const std::vector<double>& t) {
  return static_cast<double>(t.size() - 1) / (t.back() - t.front());
}

// Linear interpolation of `v` over `t` (increasing) at `x`; NaN outside [t.front(), t.back()].
struct Cursor {
  const std::vector<double>& t;
  std::size_t i = 0;
  // Index k with t[k] <= x <= t[k+1], or SIZE_MAX outside.
  std::size_t locate(double x) {
    if (x < t.front() || x > t.back()) return SIZE_MAX;
    while (i + 2 < t.size() && t[i + 1] < x) ++i;
    return i;
  }
};

// `period` > 0: an angle, interpolated the short way round (a yaw from 359° to 1°).
double interpolate(const std::vector<double>& t, const std::vector<double>& v, std::size_t k, double x,
                   double period = 0.0) {
  const double t0 = t[k], t1 = t[k + 1];
  if (!(t1 > t0)) return v[k];
  const double a = (x - t0) / (t1 - t0);
  // At a sample, its value only (the neighbour may be a NaN: a delta's first sample).
  if (a == 0.0) return v[k];
  if (a == 1.0) return v[k + 1];
  double d = v[k + 1] - v[k];
  if (period > 0.0) d -= period * std::round(d / period);
  return v[k] + a * d;
}

// NED → ENU for world vectors, FRD → FLU for body vectors, and the quaternion between them.
void toEnuFlu(const std::string& frame, std::vector<double>& x) {
  if (frame == "world") {
    std::swap(x[0], x[1]);
    x[2] = -x[2];
  } else if (frame == "body") {
    x[1] = -x[1];
    x[2] = -x[2];
  } else if (frame == "world_z") {
    x[0] = -x[0];
  } else if (frame == "quaternion") {
    // q_ENU_FLU = q(T_ENU_NED) · q_NED_FRD · q(T_FRD_FLU); T_FRD_FLU is π about x.
    static const Eigen::Quaterniond a(Eigen::Matrix3d{{0, 1, 0}, {1, 0, 0}, {0, 0, -1}});
    static const Eigen::Quaterniond b(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()));
    const Eigen::Quaterniond q = a * Eigen::Quaterniond(x[0], x[1], x[2], x[3]) * b;
    x = {q.w(), q.x(), q.y(), q.z()};
  }
}

// Roll, pitch, yaw [rad] → the quaternion w, x, y, z of R = Rz(yaw)·Ry(pitch)·Rx(roll).
void eulerToQuaternion(std::vector<double>& x) {
  const Eigen::Quaterniond e = Eigen::AngleAxisd(x[2], Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(x[1], Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(x[0], Eigen::Vector3d::UnitX());
  x = {e.w(), e.x(), e.y(), e.z()};
}

}  // namespace

MappedFlight mapFlight(const LogData& log, const LogMap& map, const std::vector<std::string>& wanted) {
  MappedFlight out;
  out.source = log.source;
  std::vector<Series> series;
  for (const auto& name : wanted) {
    if (auto s = find(log, map, name, out.notes)) series.push_back(std::move(*s));
  }
  for (auto& s : series) {
    if (s.name == "rotor_speed" || s.name == "throttle") toRotorOrder(log, map, s, out.notes, out.warnings);
  }
  // The time base: the slowest topic (interpolating it onto a faster one would invent data).
  TimeAxes axes(map, log);
  const Topic* base = nullptr;
  for (const auto& s : series) {
    std::vector<const Topic*> seen;
    for (const auto& part : s.parts) {
      const Topic* t = part.topic;
      if (t == nullptr || std::find(seen.begin(), seen.end(), t) != seen.end()) continue;
      seen.push_back(t);
      const double rate = rateOf(axes.of(*t));
      char text[64];
      std::snprintf(text, sizeof text, "%.4g Hz", rate);
      out.notes.push_back(s.name + ": " + topicName(*t) + ", " + std::to_string(t->size()) + " samples at " + text);
      const bool slow_is_fine = s.name == "battery_voltage" || s.name == "armed";
      if (rate < kMinFitRateHz && !slow_is_fine) {
        out.warnings.push_back(s.name + " (" + topicName(*t) + ") is logged at " + text + ", slower than the " +
                               std::to_string(static_cast<int>(kMinFitRateHz)) +
                               " Hz a fit of the vehicle's motion needs: the fit runs on its samples only");
      }
      // The battery voltage changes over minutes and the arming state is logged when it changes:
      // such topics are interpolated (the arming state held), never the time base (unless alone).
      if (slow_is_fine && series.size() > 1) continue;
      if (base == nullptr || rate < rateOf(axes.of(*base))) base = t;
    }
  }
  if (base == nullptr) throw LogError(log.source, "every mapped channel is a constant: no time axis from the log");
  out.time_base = topicName(*base);
  out.notes.push_back("time base: " + out.time_base + " (the slowest channel; the others are interpolated linearly)");
  std::vector<std::vector<Cursor>> cursors(series.size());
  for (std::size_t k = 0; k < series.size(); ++k) {
    for (const auto& part : series[k].parts) cursors[k].push_back({part.topic ? axes.of(*part.topic) : kNoAxis});
  }
  const bool convert = map.frames == "ned_frd";
  std::size_t outside = 0, with_nan = 0;
  std::vector<std::vector<double>> row(series.size());
  const std::vector<double> base_times = axes.of(*base);
  for (const double t : base_times) {
    bool ok = true, finite = true;
    for (std::size_t k = 0; k < series.size() && ok; ++k) {
      const Series& s = series[k];
      row[k].resize(s.parts.size());
      for (std::size_t f = 0; f < s.parts.size() && ok; ++f) {
        const Component& part = s.parts[f];
        if (part.topic == nullptr) {
          row[k][f] = part.values.front();
          continue;
        }
        const std::size_t at = cursors[k][f].locate(t);
        if (at == SIZE_MAX) {
          ok = false;
          break;
        }
        // The arming state holds its last logged value; the rest is linear.
        row[k][f] = s.name == "armed" ? (t >= cursors[k][f].t[at + 1] ? part.values[at + 1] : part.values[at])
                                      : interpolate(cursors[k][f].t, part.values, at, t,
                                                    s.spec->frame == "euler" ? 2.0 * M_PI : 0.0);
        // A gap in the battery voltage is kept as NaN (its user counts it), not a dropped row.
        finite = finite && (std::isfinite(row[k][f]) || s.name == "battery_voltage");
      }
      if (!ok) break;
      if (s.spec->frame == "quaternion") {
        double norm = 0.0;
        for (const double q : row[k]) norm += q * q;
        norm = std::sqrt(norm);
        for (double& q : row[k]) q /= norm;
        finite = finite && norm > 0.5;
      }
      const bool euler = s.spec->frame == "euler";
      if (euler) eulerToQuaternion(row[k]);
      if (convert) toEnuFlu(euler ? "quaternion" : s.spec->frame, row[k]);  // world_z: ENU z is the height
    }
    if (!ok) {
      ++outside;
      continue;
    }
    if (!finite) {
      ++with_nan;
      continue;
    }
    out.t_s.push_back(t);
    for (std::size_t k = 0; k < series.size(); ++k) store(series[k].name, row[k], out);
  }
  for (const auto& s : series) {
    if (s.name == "rotor_speed") {
      out.n_rpm.resize(s.parts.size());
      for (const auto& p : s.parts) out.rotor_fields.push_back(p.field);
    } else if (s.name == "throttle") {
      out.throttle.resize(s.parts.size());
      for (const auto& p : s.parts) out.throttle_fields.push_back(p.field);
    }
  }
  if (outside > 0) out.notes.push_back(std::to_string(outside) + " samples of the time base outside another channel's time span: dropped");
  if (with_nan > 0) out.notes.push_back(std::to_string(with_nan) + " samples with a NaN in a mapped field: dropped");
  return out;
}

bool logHasChannel(const LogData& log, const LogMap& map, const std::string& name) {
  const auto it = map.channels.find(name);
  if (it == map.channels.end() || it->second.expressions.empty()) return false;
  const MappedChannel& c = it->second;
  const bool option = !c.from_option.empty() && c.from_option[0];
  try {
    (void)evaluateOnLog(c.expressions[0], log, c.topic, c.field_instances.empty() ? c.instance : c.field_instances[0],
                        channelUnit(name, c), name, option || c.expressions[0].hasUnits());
  } catch (const MissingFieldError&) {
    return false;
  }
  return true;
}

}  // namespace geaware::io
