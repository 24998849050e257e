// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a log holds and whether its channels can be trusted (`geaware logs inspect`,
// docs/identification.md "Inspecting a log"): per topic instance the samples, time span, rate
// and gaps; per channel the range and its health problems:
//   dead        every value is 0 or NaN;
//   constant    every finite value is the same (not 0);
//   stuck       one non-zero value repeats for at least 10 samples and a quarter of the log
//               while the channel otherwise varies (at least 5 distinct values);
//   saturated   runs at the channel's minimum or maximum (other than 0, a motor at rest, and
//               other than a stuck value) of at least 10 samples, together at least 5 % of the
//               log (a channel with at least 5 distinct values);
//   alternating the channel flips between 0 and non-zero: at least 10 % zeros, 10 % non-zeros
//               and a flip at 20 % of the samples (a dead motor channel read between good ones).
// Integer flags and counters often read constant: a problem is a property of the data, and
// whether it matters depends on what the channel is used for.

#include <cstddef>
#include <string>
#include <vector>

#include "geaware/io/json.hpp"
#include "geaware/io/log_channels.hpp"

namespace geaware::io {

struct ChannelHealth {
  std::string name;
  std::string unit;
  FieldType type = FieldType::kDouble;
  std::size_t samples = 0;
  std::size_t nan_count = 0;
  double min = 0.0, max = 0.0, mean = 0.0;  ///< over the finite values (0 when none)
  std::vector<std::string> problems;        ///< "dead", "constant 3", "stuck at 2 for 40 samples from t = 1.2 s", …
};

struct TopicSummary {
  std::string name;
  unsigned instance = 0;
  std::size_t samples = 0;
  double t_first_s = 0.0, t_last_s = 0.0;
  double rate_hz = 0.0;          ///< (samples − 1) / span; 0 for fewer than 2 samples
  double median_dt_s = 0.0;
  std::size_t gaps = 0;          ///< intervals longer than 5 median intervals
  double longest_gap_s = 0.0;
  double longest_gap_at_s = 0.0; ///< time of the sample before the longest gap
  std::size_t backwards = 0;     ///< times that do not increase
  std::vector<ChannelHealth> channels;
};

struct LogSummary {
  std::string source;
  std::string format;
  double t_first_s = 0.0, t_last_s = 0.0;
  std::vector<TopicSummary> topics;
  std::size_t parameters = 0;
  std::size_t messages = 0;
  std::vector<Dropout> dropouts;
  std::vector<std::string> warnings;  ///< the reader's
};

/// The health of one channel over `time_s` (same length as its values); times in the problems
/// are given from `t0_s`, the start of the log. Padding fields (`_padding…`) and channels of
/// fewer than 2 samples get no problems.
[[nodiscard]] ChannelHealth channelHealth(const Channel& channel, const std::vector<double>& time_s, double t0_s = 0.0);
/// Every topic instance and channel of `log`.
[[nodiscard]] LogSummary inspectLog(const LogData& log);
/// The summary as text: one line per topic, then its channels with problems.
[[nodiscard]] std::string summaryText(const LogSummary& summary);
/// The summary as JSON (every channel, with or without problems).
[[nodiscard]] Json summaryJson(const LogSummary& summary);

}  // namespace geaware::io
