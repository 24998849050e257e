// SPDX-License-Identifier: BSD-3-Clause
// Channel health on channels built to have each problem (and one without), then on the real PX4
// log: its rates as logged, its dead motor channels found, its IMU healthy.

#include "geaware/io/log_inspect.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace {

using geaware::io::Channel;
using geaware::io::channelHealth;

std::vector<double> times(std::size_t n) {
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = 0.01 * static_cast<double>(i);
  return t;
}

Channel channel(std::vector<double> v) { return {"x", "", geaware::io::FieldType::kFloat, std::move(v)}; }

std::string problems(const std::vector<double>& v) {
  const auto h = channelHealth(channel(v), times(v.size()));
  std::string s;
  for (const auto& p : h.problems) s += p + ";";
  return s;
}

TEST(LogHealth, EachProblemIsFoundAndAHealthyChannelHasNone) {
  const std::size_t n = 200;
  std::vector<double> healthy(n), dead(n, 0.0), nan(n, std::numeric_limits<double>::quiet_NaN()), constant(n, 3.5);
  std::vector<double> alternating(n), stuck(n), saturated(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i);
    healthy[i] = std::sin(0.1 * x) + 2.0;
    alternating[i] = i % 2 == 0 ? 0.0 : 9900.0 + x;  // the motor-1 rpm
    stuck[i] = i >= 50 && i < 150 ? 1.25 : std::sin(0.1 * x);
    saturated[i] = std::clamp(3.0 * std::sin(0.05 * x), -1.0, 1.0);
  }
  dead[7] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(problems(healthy), "");
  EXPECT_EQ(problems(dead), "dead (all zero or NaN);");
  EXPECT_EQ(problems(nan), "dead (all NaN);");
  EXPECT_EQ(problems(constant), "constant 3.5;");
  EXPECT_EQ(problems(alternating), "alternating with zero (199 flips in 200 samples);");
  EXPECT_EQ(problems(stuck), "stuck at 1.25 for 100 samples from t = 0.500 s;");
  EXPECT_NE(problems(saturated).find("saturated at its minimum or maximum (-1, 1)"), std::string::npos)
      << problems(saturated);
  // A motor at rest before take-off is neither saturated nor stuck.
  std::vector<double> rest(n);
  for (std::size_t i = 0; i < n; ++i) rest[i] = i < 80 ? 0.0 : 9000.0 + 50.0 * std::sin(0.2 * static_cast<double>(i));
  EXPECT_EQ(problems(rest), "");
}

TEST(LogHealth, ThePx4SampleLogRatesAndDeadChannels) {
  const char* dir = std::getenv("GEAWARE_SOURCE_DIR");
  const auto file = std::filesystem::path(dir != nullptr ? dir : ".") / "tests/fixtures/px4/sample_px4_events.ulg";
  const auto s = geaware::io::inspectLog(geaware::io::readULog(file));
  const auto find = [&](const std::string& name) -> const geaware::io::TopicSummary& {
    for (const auto& t : s.topics) {
      if (t.name == name) return t;
    }
    throw std::runtime_error("no topic " + name);
  };
  // 7783 samples over 31.128 s: 250 Hz; esc_status at about 4 Hz (too slow for a rotor-speed fit).
  EXPECT_NEAR(find("sensor_combined").rate_hz, 250.0, 0.1);
  EXPECT_NEAR(find("esc_status").rate_hz, 4.0, 0.1);
  EXPECT_NEAR(find("vehicle_local_position").rate_hz, 10.0, 0.1);
  EXPECT_NEAR(s.t_last_s - s.t_first_s, 31.4, 0.1);
  const auto& motors = find("actuator_motors");
  for (const auto& c : motors.channels) {
    // This quadrotor uses 4 of the 12 motor outputs: the others are logged as NaN.
    const bool unused = c.name.starts_with("control[") && c.name != "control[0]" && c.name != "control[1]" &&
                        c.name != "control[2]" && c.name != "control[3]";
    EXPECT_EQ(!c.problems.empty() && c.problems[0] == "dead (all NaN)", unused) << c.name;
  }
  for (const auto& c : find("sensor_combined").channels) {
    if (c.name.starts_with("accelerometer_m_s2") || c.name.starts_with("gyro_rad")) {
      EXPECT_TRUE(c.problems.empty()) << c.name << ": " << c.problems.front();
    }
  }
  const auto j = geaware::io::summaryJson(s);
  EXPECT_EQ(j["format"], "ulog");
  EXPECT_EQ(j["topics"].size(), s.topics.size());
}

}  // namespace
