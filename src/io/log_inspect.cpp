// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/log_inspect.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace geaware::io {
namespace {

constexpr std::size_t kMinRun = 10;          // samples in a stuck or saturated run
constexpr std::size_t kMinDistinct = 5;      // a channel that varies
constexpr double kStuckFraction = 0.25;
constexpr double kSaturatedFraction = 0.05;
constexpr double kAlternatingShare = 0.10;   // least share of zeros and of non-zeros
constexpr double kAlternatingFlips = 0.20;   // least share of samples that flip
constexpr double kGapFactor = 5.0;           // a gap: an interval over 5 median intervals

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string secs(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

std::size_t distinctAtLeast(const std::vector<double>& values, std::size_t enough) {
  std::vector<double> seen;
  for (const double v : values) {
    if (std::isnan(v) || std::find(seen.begin(), seen.end(), v) != seen.end()) continue;
    seen.push_back(v);
    if (seen.size() >= enough) break;
  }
  return seen.size();
}

double timeAt(const std::vector<double>& t, std::size_t i) { return i < t.size() ? t[i] : 0.0; }

// The longest run of one non-zero value, and the runs at the minimum or maximum.
void runs(const Channel& c, const std::vector<double>& t, double t0, ChannelHealth& h) {
  const auto& v = c.values;
  std::size_t best = 0, best_start = 0;
  for (std::size_t i = 0; i < v.size();) {
    std::size_t j = i + 1;
    while (j < v.size() && v[j] == v[i]) ++j;
    if (v[i] != 0.0 && j - i > best) best = j - i, best_start = i;
    i = j;
  }
  const auto n = static_cast<double>(v.size());
  const bool stuck = best >= kMinRun && static_cast<double>(best) >= kStuckFraction * n;
  if (stuck) {
    h.problems.push_back("stuck at " + num(v[best_start]) + " for " + std::to_string(best) + " samples from t = " +
                         secs(timeAt(t, best_start) - t0) + " s");
  }
  // Runs at a bound other than 0 (a motor at rest is not saturated) and other than the stuck value.
  std::size_t at_bound = 0;
  for (std::size_t i = 0; i < v.size();) {
    std::size_t j = i + 1;
    while (j < v.size() && v[j] == v[i]) ++j;
    const bool bound = v[i] != 0.0 && (v[i] == h.min || v[i] == h.max) && !(stuck && v[i] == v[best_start]);
    if (j - i >= kMinRun && bound) at_bound += j - i;
    i = j;
  }
  if (at_bound > 0 && static_cast<double>(at_bound) >= kSaturatedFraction * n) {
    h.problems.push_back("saturated at its minimum or maximum (" + num(h.min) + ", " + num(h.max) + ") for " +
                         std::to_string(at_bound) + " samples");
  }
}

}  // namespace

ChannelHealth channelHealth(const Channel& c, const std::vector<double>& time_s, double t0_s) {
  ChannelHealth h;
  h.name = c.name;
  h.unit = c.unit;
  h.type = c.type;
  h.samples = c.values.size();
  double sum = 0.0;
  std::size_t finite = 0, zeros = 0;
  h.min = std::numeric_limits<double>::infinity();
  h.max = -h.min;
  for (std::size_t i = 0; i < c.values.size(); ++i) {
    const double v = c.values[i];
    if (std::isnan(v)) {
      ++h.nan_count;
      continue;
    }
    if (v == 0.0) ++zeros;
    if (std::isfinite(v)) {
      ++finite;
      sum += v;
      h.min = std::min(h.min, v);
      h.max = std::max(h.max, v);
    }
  }
  if (finite == 0) h.min = h.max = 0.0;
  h.mean = finite > 0 ? sum / static_cast<double>(finite) : 0.0;
  // Padding bytes of a nested type hold nothing by design.
  if (h.samples < 2 || c.name.starts_with("_padding") || c.name.find("._padding") != std::string::npos) return h;
  const auto n = static_cast<double>(h.samples);
  if (zeros + h.nan_count == h.samples) {
    h.problems.emplace_back(h.nan_count == h.samples ? "dead (all NaN)" : "dead (all zero or NaN)");
    return h;
  }
  if (finite > 0 && h.min == h.max && finite + h.nan_count == h.samples) {
    h.problems.push_back("constant " + num(h.min));
    return h;
  }
  // Alternating: "zero" is anything within 1e-6 of the channel's largest magnitude (an idle
  // motor command logged as 1e-10 is at rest).
  const double tiny = 1e-6 * std::max(std::abs(h.min), std::abs(h.max));
  std::size_t small = 0, flips = 0;
  bool prev_small = false, have_prev = false;
  for (const double v : c.values) {
    if (std::isnan(v)) continue;
    const bool is_small = std::abs(v) <= tiny;
    small += is_small ? 1 : 0;
    if (have_prev && is_small != prev_small) ++flips;
    prev_small = is_small, have_prev = true;
  }
  const auto nonzero = static_cast<double>(h.samples - small - h.nan_count);
  if (static_cast<double>(small) >= kAlternatingShare * n && nonzero >= kAlternatingShare * n &&
      flips >= kMinRun && static_cast<double>(flips) >= kAlternatingFlips * n) {
    h.problems.push_back("alternating with zero (" + std::to_string(flips) + " flips in " +
                         std::to_string(h.samples) + " samples)");
  }
  if (distinctAtLeast(c.values, kMinDistinct) >= kMinDistinct) runs(c, time_s, t0_s, h);
  return h;
}

LogSummary inspectLog(const LogData& log) {
  LogSummary s;
  s.source = log.source;
  s.format = log.format;
  s.parameters = log.parameters.size();
  s.messages = log.messages.size();
  s.dropouts = log.dropouts;
  s.warnings = log.warnings;
  // The log's start: the earliest non-zero time (a ULog timestamp of 0 means "not set").
  bool any = false;
  for (const auto& t : log.topics) {
    for (const double x : t.time_s) {
      if (x > 0.0) {
        s.t_first_s = any ? std::min(s.t_first_s, x) : x;
        any = true;
        break;
      }
    }
  }
  for (const auto& t : log.topics) {
    TopicSummary ts;
    ts.name = t.name;
    ts.instance = t.instance;
    ts.samples = t.size();
    if (!t.time_s.empty()) {
      ts.t_first_s = t.time_s.front();
      ts.t_last_s = t.time_s.back();
      s.t_last_s = std::max(s.t_last_s, ts.t_last_s);
    }
    if (t.size() >= 2) {
      std::vector<double> dt(t.size() - 1);
      for (std::size_t i = 1; i < t.size(); ++i) {
        dt[i - 1] = t.time_s[i] - t.time_s[i - 1];
        if (!(dt[i - 1] > 0.0)) ++ts.backwards;
      }
      std::vector<double> sorted = dt;
      std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
      ts.median_dt_s = sorted[sorted.size() / 2];
      const double span = ts.t_last_s - ts.t_first_s;
      ts.rate_hz = span > 0.0 ? static_cast<double>(t.size() - 1) / span : 0.0;
      for (std::size_t i = 0; i < dt.size(); ++i) {
        if (ts.median_dt_s > 0.0 && dt[i] > kGapFactor * ts.median_dt_s) {
          ++ts.gaps;
          if (dt[i] > ts.longest_gap_s) ts.longest_gap_s = dt[i], ts.longest_gap_at_s = t.time_s[i];
        }
      }
    }
    for (const auto& c : t.channels) ts.channels.push_back(channelHealth(c, t.time_s, s.t_first_s));
    s.topics.push_back(std::move(ts));
  }
  return s;
}

std::string summaryText(const LogSummary& s) {
  std::string out = s.source + ": " + s.format + " log, " + std::to_string(s.topics.size()) +
                     " topic instances over " + secs(s.t_last_s - s.t_first_s) + " s (times below from its start, t = " +
                    secs(s.t_first_s) + " s on the log clock), " + std::to_string(s.parameters) + " parameters, " +
                    std::to_string(s.messages) + " messages, " + std::to_string(s.dropouts.size()) + " dropouts\n";
  char line[512];
  std::snprintf(line, sizeof line, "%-36s %8s %9s %9s %9s %5s %11s %6s %s\n", "topic[instance]", "samples", "from [s]",
                "span [s]", "rate [Hz]", "gaps", "longest [s]", "fields", "problems");
  out += line;
  for (const auto& t : s.topics) {
    std::size_t flagged = 0;
    for (const auto& c : t.channels) flagged += c.problems.empty() ? 0 : 1;
    const std::string name = t.name + "[" + std::to_string(t.instance) + "]";
    std::snprintf(line, sizeof line, "%-36s %8zu %9.3f %9.3f %9.2f %5zu %11.3f %6zu %zu\n", name.c_str(), t.samples,
                  t.samples > 0 && t.t_first_s > 0.0 ? t.t_first_s - s.t_first_s : 0.0, t.t_last_s - t.t_first_s, t.rate_hz, t.gaps,
                  t.longest_gap_s, t.channels.size(), flagged);
    out += line;
    if (t.backwards > 0) out += "    time does not increase " + std::to_string(t.backwards) + " times\n";
    if (t.gaps > 0) {
      out += "    longest gap " + num(t.longest_gap_s) + " s from t = " + secs(t.longest_gap_at_s - s.t_first_s) + " s\n";
    }
    // Integer fields (flags, counters, ids) that read dead or constant are listed together.
    std::string quiet;
    std::size_t quiet_count = 0;
    for (const auto& c : t.channels) {
      const bool integer = c.type != FieldType::kFloat && c.type != FieldType::kDouble;
      for (const auto& p : c.problems) {
        if (integer && (p.starts_with("dead") || p.starts_with("constant"))) {
          quiet += (quiet_count++ == 0 ? "" : ", ") + c.name;
          continue;
        }
        out += "    " + c.name + (c.unit.empty() ? "" : " [" + c.unit + "]") + ": " + p + "\n";
      }
    }
    if (quiet_count > 0) {
      out += "    integer fields dead or constant (" + std::to_string(quiet_count) + "): " + quiet + "\n";
    }
  }
  for (const auto& d : s.dropouts) {
    out += "dropout at t = " + secs(d.time_s - s.t_first_s) + " s for " + num(d.duration_s) + " s\n";
  }
  for (const auto& w : s.warnings) out += "reader warning: " + w + "\n";
  return out;
}

Json summaryJson(const LogSummary& s) {
  Json doc{{"log", s.source}, {"format", s.format}, {"t_first_s", s.t_first_s}, {"t_last_s", s.t_last_s},
           {"parameters", s.parameters}, {"messages", s.messages}};
  Json& drops = doc["dropouts"] = Json::array();
  for (const auto& d : s.dropouts) drops.push_back({{"t_s", d.time_s}, {"duration_s", d.duration_s}});
  doc["warnings"] = s.warnings;
  Json& topics = doc["topics"] = Json::array();
  for (const auto& t : s.topics) {
    Json channels = Json::array();
    for (const auto& c : t.channels) {
      channels.push_back({{"name", c.name}, {"unit", c.unit}, {"type", std::string(fieldTypeName(c.type))},
                          {"samples", c.samples}, {"nan", c.nan_count}, {"min", c.min}, {"max", c.max},
                          {"mean", c.mean}, {"problems", c.problems}});
    }
    topics.push_back({{"name", t.name}, {"instance", t.instance}, {"samples", t.samples},
                      {"t_first_s", t.t_first_s}, {"t_last_s", t.t_last_s}, {"rate_hz", t.rate_hz},
                      {"median_dt_s", t.median_dt_s}, {"gaps", t.gaps}, {"longest_gap_s", t.longest_gap_s},
                      {"longest_gap_at_s", t.longest_gap_at_s}, {"time_backwards", t.backwards},
                      {"channels", std::move(channels)}});
  }
  return doc;
}

}  // namespace geaware::io
