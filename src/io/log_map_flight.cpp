// SPDX-License-Identifier: BSD-3-Clause
// mapFlight (io/log_map.hpp): mapped channels onto one time axis, in SI units and ENU/FLU.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <cstdio>

#include <Eigen/Geometry>

#include "geaware/io/log_map.hpp"

namespace geaware::io {
namespace {

// One mapped channel as read: each field with the topic instance it comes from, scaled.
struct Series {
  std::string name;
  std::vector<const Topic*> topics;  // per field
  std::vector<const Channel*> fields;
  const MappedChannel* spec = nullptr;
};

Series find(const LogData& log, const LogMap& map, const std::string& name) {
  const auto it = map.channels.find(name);
  if (it == map.channels.end()) {
    throw LogError(log.source, "the map " + map.source + " does not say which field is '" + name +
                                   "', which this fit needs");
  }
  const MappedChannel& c = it->second;
  Series s{name, {}, {}, &c};
  const std::string where = " (" + name + " in " + map.source + (c.line > 0 ? ":" + std::to_string(c.line) : "") + ")";
  for (std::size_t k = 0; k < c.fields.size(); ++k) {
    const unsigned instance = k < c.field_instances.size() ? c.field_instances[k] : c.instance;
    const Topic* topic = log.topic(c.topic, instance);
    if (topic == nullptr) {
      throw LogError(log.source, "no topic '" + c.topic + "' instance " + std::to_string(instance) + where);
    }
    if (topic->size() < 2) {
      throw LogError(log.source, "topic '" + c.topic + "' has " + std::to_string(topic->size()) + " samples" + where);
    }
    const Channel* ch = topic->channel(c.fields[k]);
    if (ch == nullptr) throw LogError(log.source, "topic '" + c.topic + "' has no field '" + c.fields[k] + "'" + where);
    s.topics.push_back(topic);
    s.fields.push_back(ch);
  }
  return s;
}

std::string topicName(const Topic& t) { return t.name + "[" + std::to_string(t.instance) + "]"; }

// The time axis of each topic used: its own, or the map's time field scaled (a CSV export whose
// `timestamp` is in ms, not the µs readLog assumes).
class TimeAxes {
 public:
  TimeAxes(const LogMap& map, const std::string& source) : map_(map), source_(source) {}
  const std::vector<double>& of(const Topic& t) {
    if (map_.time_field.empty()) return t.time_s;
    auto it = axes_.find(&t);
    if (it != axes_.end()) return it->second;
    const Channel* c = nullptr;
    for (const auto& ch : t.channels) {
      if (lowered(ch.name) == lowered(map_.time_field)) c = &ch;
    }
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
  std::map<const Topic*, std::vector<double>> axes_;
};

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
  std::vector<Series> series;
  for (const auto& name : wanted) series.push_back(find(log, map, name));
  MappedFlight out;
  out.source = log.source;
  // The time base: the slowest topic (interpolating it onto a faster one would invent data).
  TimeAxes axes(map, log.source);
  const Topic* base = series.front().topics.front();
  for (const auto& s : series) {
    std::vector<const Topic*> seen;
    for (const Topic* t : s.topics) {
      if (std::find(seen.begin(), seen.end(), t) != seen.end()) continue;
      seen.push_back(t);
      const double rate = rateOf(axes.of(*t));
      char text[64];
      std::snprintf(text, sizeof text, "%.4g Hz", rate);
      out.notes.push_back(s.name + ": " + topicName(*t) + ", " + std::to_string(t->size()) + " samples at " + text);
      if (rate < kMinFitRateHz) {
        out.warnings.push_back(s.name + " (" + topicName(*t) + ") is logged at " + text + ", slower than the " +
                               std::to_string(static_cast<int>(kMinFitRateHz)) +
                               " Hz a fit of the vehicle's motion needs: the fit runs on its samples only");
      }
      if (rate < rateOf(axes.of(*base))) base = t;
    }
  }
  out.time_base = topicName(*base);
  out.notes.push_back("time base: " + out.time_base + " (the slowest channel; the others are interpolated linearly)");
  std::vector<std::vector<Cursor>> cursors(series.size());
  for (std::size_t k = 0; k < series.size(); ++k) {
    for (const Topic* t : series[k].topics) cursors[k].push_back({axes.of(*t)});
  }
  const bool convert = map.frames == "ned_frd";
  std::size_t outside = 0, with_nan = 0;
  std::vector<std::vector<double>> row(series.size());
  const std::vector<double> base_times = axes.of(*base);
  for (const double t : base_times) {
    bool ok = true, finite = true;
    for (std::size_t k = 0; k < series.size() && ok; ++k) {
      const Series& s = series[k];
      const double period = s.spec->frame == "euler" ? 2.0 * M_PI / s.spec->scale : 0.0;
      row[k].resize(s.fields.size());
      for (std::size_t f = 0; f < s.fields.size() && ok; ++f) {
        const std::size_t at = cursors[k][f].locate(t);
        if (at == SIZE_MAX) {
          ok = false;
          break;
        }
        row[k][f] = interpolate(cursors[k][f].t, s.fields[f]->values, at, t, period) * s.spec->scale;
        finite = finite && std::isfinite(row[k][f]);
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
    for (std::size_t k = 0; k < series.size(); ++k) {
      const std::string& name = series[k].name;
      const auto& r = row[k];
      if (name == "height") out.h_m.push_back(r[0]);
      if (name == "battery_voltage") out.vbat_V.push_back(r[0]);
      for (std::size_t i = 0; i < 3 && r.size() >= 3; ++i) {
        if (name == "specific_force") out.f_B_mps2[i].push_back(r[i]);
        if (name == "gyro") out.gyro_B_radps[i].push_back(r[i]);
        if (name == "velocity") out.v_W_mps[i].push_back(r[i]);
      }
      if (name == "attitude") {
        for (std::size_t i = 0; i < 4; ++i) out.q_WB[i].push_back(r[i]);
      }
      if (name == "rotor_speed") {
        out.n_rpm.resize(r.size());
        for (std::size_t i = 0; i < r.size(); ++i) out.n_rpm[i].push_back(r[i]);
      }
    }
  }
  if (outside > 0) out.notes.push_back(std::to_string(outside) + " samples of the time base outside another channel's time span: dropped");
  if (with_nan > 0) out.notes.push_back(std::to_string(with_nan) + " samples with a NaN in a mapped field: dropped");
  return out;
}

}  // namespace geaware::io
