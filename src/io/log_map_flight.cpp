// SPDX-License-Identifier: BSD-3-Clause
// mapFlight (io/log_map.hpp): mapped channels onto one time axis, in SI units and ENU/FLU.

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>

#include "geaware/io/log_map.hpp"

namespace geaware::io {
namespace {

// One mapped channel as read: its topic's time axis and its fields, scaled.
struct Series {
  std::string name;
  const Topic* topic = nullptr;
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
  Series s{name, log.topic(c.topic, c.instance), {}, &c};
  const std::string where = " (" + name + " in " + map.source + (c.line > 0 ? ":" + std::to_string(c.line) : "") + ")";
  if (s.topic == nullptr) {
    throw LogError(log.source, "no topic '" + c.topic + "' instance " + std::to_string(c.instance) + where);
  }
  if (s.topic->size() < 2) {
    throw LogError(log.source, "topic '" + c.topic + "' has " + std::to_string(s.topic->size()) + " samples" + where);
  }
  for (const auto& f : c.fields) {
    const Channel* ch = s.topic->channel(f);
    if (ch == nullptr) throw LogError(log.source, "topic '" + c.topic + "' has no field '" + f + "'" + where);
    s.fields.push_back(ch);
  }
  return s;
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

double interpolate(const std::vector<double>& t, const std::vector<double>& v, std::size_t k, double x) {
  const double t0 = t[k], t1 = t[k + 1];
  if (!(t1 > t0)) return v[k];
  const double a = (x - t0) / (t1 - t0);
  return v[k] + a * (v[k + 1] - v[k]);
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

}  // namespace

MappedFlight mapFlight(const LogData& log, const LogMap& map, const std::vector<std::string>& wanted) {
  std::vector<Series> series;
  for (const auto& name : wanted) series.push_back(find(log, map, name));
  MappedFlight out;
  out.source = log.source;
  // The time base: the slowest channel (interpolating it onto a faster one would invent data).
  const Series* base = &series.front();
  for (const auto& s : series) {
    const double rate = static_cast<double>(s.topic->size() - 1) / (s.topic->time_s.back() - s.topic->time_s.front());
    out.notes.push_back(s.name + ": " + s.spec->topic + "[" + std::to_string(s.spec->instance) + "], " +
                        std::to_string(s.topic->size()) + " samples at " + std::to_string(rate).substr(0, 6) + " Hz");
    if (rate < kMinFitRateHz) {
      char text[64];
      std::snprintf(text, sizeof text, "%.3g Hz", rate);
      out.warnings.push_back(s.name + " (" + s.spec->topic + "[" + std::to_string(s.spec->instance) + "]) is logged at " +
                             text + ", slower than the " + std::to_string(static_cast<int>(kMinFitRateHz)) +
                             " Hz a fit of the vehicle's motion needs: the fit runs on its samples only");
    }
    if (s.topic->size() < base->topic->size()) base = &s;
  }
  out.time_base = base->spec->topic + "[" + std::to_string(base->spec->instance) + "]";
  out.notes.push_back("time base: " + out.time_base + " (the slowest channel; the others are interpolated linearly)");
  std::vector<Cursor> cursors;
  for (const auto& s : series) cursors.push_back({s.topic->time_s});
  const bool convert = map.frames == "ned_frd";
  std::size_t outside = 0, with_nan = 0;
  std::vector<std::vector<double>> row(series.size());
  for (const double t : base->topic->time_s) {
    bool ok = true, finite = true;
    for (std::size_t k = 0; k < series.size() && ok; ++k) {
      const Series& s = series[k];
      const std::size_t at = cursors[k].locate(t);
      if (at == SIZE_MAX) {
        ok = false;
        break;
      }
      row[k].resize(s.fields.size());
      for (std::size_t f = 0; f < s.fields.size(); ++f) {
        row[k][f] = interpolate(s.topic->time_s, s.fields[f]->values, at, t) * s.spec->scale;
        finite = finite && std::isfinite(row[k][f]);
      }
      if (s.spec->frame == "quaternion") {
        double norm = 0.0;
        for (const double q : row[k]) norm += q * q;
        norm = std::sqrt(norm);
        for (double& q : row[k]) q /= norm;
        finite = finite && norm > 0.5;
      }
      if (convert || s.spec->frame == "world_z") toEnuFlu(s.spec->frame, row[k]);
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
