// SPDX-License-Identifier: BSD-3-Clause
// Log maps with expressions, optional channels, --column/--const, motor order and pole pairs
// (io/log_map.hpp), on synthetic logs whose values are known in closed form.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "geaware/io/config_error.hpp"
#include "geaware/io/log_map.hpp"

namespace {

using geaware::io::ColumnDefinition;
using geaware::io::LogData;
using geaware::io::LogError;
using geaware::io::mapFlight;
using geaware::io::parseColumnDefinition;
using geaware::io::parseLogMap;
using geaware::io::Topic;

Topic topic(const std::string& name, double dt, std::size_t n,
            const std::vector<std::pair<std::string, double>>& fields, unsigned instance = 0) {
  Topic t;
  t.name = name;
  t.instance = instance;
  for (std::size_t i = 0; i < n; ++i) t.time_s.push_back(dt * static_cast<double>(i));
  for (const auto& [field, value] : fields) {
    t.channels.push_back(
        {field, "", geaware::io::FieldType::kFloat, std::vector<double>(n, value)});
  }
  return t;
}

std::string mapError(const std::string& yaml) {
  try {
    (void)parseLogMap(yaml, "map.yaml", "map");
  } catch (const geaware::io::ConfigError& e) {
    return e.what();
  }
  return {};
}

template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
}

// A synthetic log: a 100 Hz IMU, a 50 Hz position topic, a 50 Hz ESC topic with four motors.
LogData sampleLog() {
  LogData log;
  log.source = "synthetic.log";
  log.topics.push_back(
      topic("imu", 0.01, 102, {{"ax", 0.0}, {"ay", 0.0}, {"az", -1.0}, {"gz", 90.0}}));
  log.topics.push_back(topic("pos", 0.02, 51, {{"z", 250.0}, {"vz", 0.0}}));
  auto& pos = log.topics.back();
  for (std::size_t i = 0; i < pos.size(); ++i)
    pos.channels[1].values[i] = 0.5 * pos.time_s[i];  // vz = t/2
  log.topics.push_back(topic("esc", 0.02, 51,
                             {{"r0", 7000.0},
                              {"r1", 14000.0},
                              {"r2", 21000.0},
                              {"r3", 28000.0},
                              {"f0", 103.0},
                              {"f1", 101.0},
                              {"f2", 104.0},
                              {"f3", 102.0}}));
  return log;
}

TEST(LogMapColumns, FieldsAreExpressionsWithTheirOwnUnits) {
  const auto simple = parseLogMap(R"(family: t
frames: enu_flu
channels:
  height: {topic: pos, fields: ["z[mm] + 50[mm]"]}
  specific_force: {topic: imu, fields: [ax, ay, "-az"], unit: g, frame: body}
  gyro: {topic: imu, fields: ["0", "0", "gz[deg/s]"], frame: body}
  velocity: {topic: pos, fields: ["0[m/s]", "0[m/s]", "delta(vz[m/s]) * 0 + vz[m/s]"]}
)",
                                  "map.yaml", "t");
  const auto f = mapFlight(sampleLog(), simple, {"height", "specific_force", "gyro", "velocity"});
  ASSERT_EQ(f.time_base, "pos[0]");
  ASSERT_EQ(f.size(), 50u) << ::testing::PrintToString(
      f.notes);  // the first pos sample has no delta: dropped
  EXPECT_DOUBLE_EQ(f.h_m[0], 0.3);
  EXPECT_DOUBLE_EQ(f.f_B_mps2[2][0], 9.80665);  // the map's unit g, on an expression
  EXPECT_DOUBLE_EQ(f.gyro_B_radps[2][0], M_PI / 2.0);
  EXPECT_DOUBLE_EQ(f.gyro_B_radps[0][0], 0.0);   // a constant
  EXPECT_DOUBLE_EQ(f.v_W_mps[2][9], 0.5 * 0.2);  // sample 10 of pos: t = 0.2 s
}

TEST(LogMapColumns, MapErrorsNameTheFileLineAndCharacter) {
  const std::string e = mapError(
      "family: t\nframes: enu_flu\nchannels:\n  height: {topic: pos, fields: [\"z[mm\"]}\n");
  EXPECT_NE(e.find("map.yaml:4"), std::string::npos) << e;
  EXPECT_NE(e.find("height fields[0] 'z[mm': character 2: expected ']' closing the unit"),
            std::string::npos)
      << e;
  const std::string u = mapError(
      "family: t\nframes: enu_flu\nchannels:\n  height: {topic: pos, fields: [\"z[mm]\"], unit: "
      "m}\n");
  EXPECT_NE(u.find("a field writes its own unit"), std::string::npos) << u;
  const std::string none =
      mapError("family: t\nframes: enu_flu\nchannels:\n  height: {topic: pos, fields: [z]}\n");
  EXPECT_NE(none.find("unit"), std::string::npos) << none;  // no unit anywhere: the map must say
  const std::string order = mapError(
      "family: t\nframes: enu_flu\nchannels:\n  rotor_speed: {topic: esc, fields: [a, b, c, d], "
      "unit: rpm, "
      "rotor_of_motor: [1, 2, 2, 4]}\n");
  EXPECT_NE(order.find("expected each of the rotor numbers 1 to 4 once"), std::string::npos)
      << order;
}

TEST(LogMapColumns, AMissingRequiredChannelNamesTheMapTheChannelAndTheFieldsTheLogHas) {
  const auto map = parseLogMap(R"(family: t
frames: enu_flu
channels:
  height: {topic: pos, fields: [dist], unit: m}
  battery_voltage: {topic: bat, fields: [v], unit: V, optional: true}
)",
                               "map.yaml", "t");
  const LogData log = sampleLog();
  EXPECT_EQ(errorOf([&] { (void)mapFlight(log, map, {"height"}); }),
            "synthetic.log: channel 'height' of the map map.yaml:4 (required; `optional: true` in "
            "the map lets a log "
            "lack it): height fields[0] 'dist': character 1: topic pos[0] has no field 'dist' (its "
            "fields: z, vz)");
  // The optional battery voltage is left out of a log without it, and the notes say so.
  const auto ok = parseLogMap(R"(family: t
frames: enu_flu
channels:
  height: {topic: pos, fields: [z], unit: mm}
  battery_voltage: {topic: bat, fields: [v], unit: V, optional: true}
)",
                              "map.yaml", "t");
  const auto f = mapFlight(log, ok, {"height", "battery_voltage"});
  EXPECT_EQ(f.size(), 51u);
  EXPECT_TRUE(f.vbat_V.empty());
  ASSERT_FALSE(f.notes.empty());
  EXPECT_NE(
      f.notes[0].find("channel 'battery_voltage' of the map map.yaml:5 (optional) left out: "),
      std::string::npos)
      << f.notes[0];
  EXPECT_NE(f.notes[0].find("the log has no topic 'bat' instance 0 (its topics: esc, imu, pos)"),
            std::string::npos);
}

TEST(LogMapColumns, FieldsNameTheirTopicAndInstanceAndComeFromOneTopic) {
  LogData log = sampleLog();
  log.topics.push_back(topic("imu", 0.01, 102, {{"ax", 2.0}}, 1));
  const auto e = [](const std::string& text) {
    return geaware::io::ColumnExpression::parse(text, "--column 'x'");
  };
  const auto one = geaware::io::evaluateOnLog(e("imu[1].ax * 2"), log, "", 0, nullptr, "x", true);
  EXPECT_EQ(one.topic, &log.topics.back());
  EXPECT_DOUBLE_EQ(one.values[0], 4.0);
  EXPECT_DOUBLE_EQ(
      geaware::io::evaluateOnLog(e("imu.ax"), log, "", 0, nullptr, "x", true).values[0], 0.0);
  EXPECT_DOUBLE_EQ(geaware::io::evaluateOnLog(e("ax"), log, "imu", 1, nullptr, "x", true).values[0],
                   2.0);
  EXPECT_EQ(
      errorOf([&] { (void)geaware::io::evaluateOnLog(e("ax"), log, "", 0, nullptr, "x", true); }),
      "synthetic.log: --column 'x': character 1: field 'ax' is in imu[0] and in imu[1]: name the "
      "topic, e.g. "
      "imu[1].ax");
  EXPECT_EQ(errorOf([&] {
              (void)geaware::io::evaluateOnLog(e("imu.ax + pos.z"), log, "", 0, nullptr, "x", true);
            }),
            "synthetic.log: --column 'x': character 10: field 'pos.z' is in pos[0], an earlier one "
            "in imu[0]: the "
            "fields of one expression come from one topic (one time axis)");
  EXPECT_EQ(errorOf([&] {
              (void)geaware::io::evaluateOnLog(e("2 * nope"), log, "", 0, nullptr, "x", true);
            }),
            "synthetic.log: --column 'x': character 5: no topic of the log has a field 'nope' (its "
            "topics: esc, imu, "
            "pos)");
}

// Motors permuted in the log: field k drives motor (f_k − 100); the map's rotor_of_motor puts
// motor m on geaware's rotor; electrical rpm divided by the pole pairs.
TEST(LogMapColumns, MotorOrderAndPolePairsPutTheLogsMotorsOnGeawaresRotors) {
  const std::string yaml = R"(family: t
frames: enu_flu
channels:
  height: {topic: pos, fields: [z], unit: mm}
  rotor_speed:
    topic: esc
    fields: [r0, r1, r2, r3]
    unit: rpm
    motor_of_field: [f0, f1, f2, f3]
    motor_base: 101
    rotor_of_motor: [1, 4, 2, 3]
    pole_pairs: 7
)";
  LogData log = sampleLog();
  const auto f = mapFlight(log, parseLogMap(yaml, "map.yaml", "t"), {"height", "rotor_speed"});
  // r0 is motor 3 → rotor 2, r1 motor 1 → rotor 1, r2 motor 4 → rotor 3, r3 motor 2 → rotor 4.
  ASSERT_EQ(f.n_rpm.size(), 4u);
  EXPECT_DOUBLE_EQ(f.n_rpm[0][0], 2000.0);
  EXPECT_DOUBLE_EQ(f.n_rpm[1][0], 1000.0);
  EXPECT_DOUBLE_EQ(f.n_rpm[2][0], 3000.0);
  EXPECT_DOUBLE_EQ(f.n_rpm[3][0], 4000.0);
  EXPECT_EQ(f.rotor_fields, (std::vector<std::string>{"r1", "r0", "r2", "r3"}));
  EXPECT_TRUE(f.warnings.empty());
  // The motor numbers from logged parameters (ArduPilot's SERVOn_FUNCTION, 33 = Motor1).
  std::string by_param = yaml;
  by_param.replace(by_param.find("[f0, f1, f2, f3]"), 16,
                   "[\"param:S1\", \"param:S2\", \"param:S3\", \"param:S4\"]");
  by_param.replace(by_param.find("101"), 3, "33");
  log.parameters = {{"S1", 36.0}, {"S2", 35.0}, {"S3", 34.0}, {"S4", 33.0}};  // motors 4, 3, 2, 1
  const auto p = mapFlight(log, parseLogMap(by_param, "map.yaml", "t"), {"rotor_speed"});
  // r0 motor 4 → rotor 3, r1 motor 3 → rotor 2, r2 motor 2 → rotor 4, r3 motor 1 → rotor 1.
  EXPECT_EQ(p.rotor_fields, (std::vector<std::string>{"r3", "r1", "r0", "r2"}));
  EXPECT_DOUBLE_EQ(p.n_rpm[0][0], 4000.0);
  // A log that does not say (an unset function, 0): the fields in order, with a warning.
  log.topics[2].channels[4].values.assign(51, 0.0);
  const auto w = mapFlight(log, parseLogMap(yaml, "map.yaml", "t"), {"rotor_speed"});
  ASSERT_EQ(w.warnings.size(), 1u);
  EXPECT_NE(
      w.warnings[0].find(
          "'f0' is 0, not one of motors 1 to 4: the fields are taken as motors 1 to 4 in order"),
      std::string::npos)
      << w.warnings[0];
  // Fields as motors 1-4, then rotor_of_motor [1, 4, 2, 3]: rotor 2 is motor 3 (r2).
  EXPECT_EQ(w.rotor_fields, (std::vector<std::string>{"r0", "r2", "r3", "r1"}));
}

TEST(LogMapColumns, ColumnAndConstOptionsReplaceOrAddChannels) {
  auto map = parseLogMap(R"(family: t
frames: ned_frd
channels:
  height: {topic: pos, fields: [nope], unit: m}
  specific_force: {topic: imu, fields: [ax, ay, az], unit: g, frame: body}
)",
                         "map.yaml", "t");
  const std::vector<ColumnDefinition> defs = {
      parseColumnDefinition("h_m=pos.z[mm]", "--column"),
      parseColumnDefinition("a_z_mps2=az * 9", "--column"),
      parseColumnDefinition("vbat_V=12.5", "--const", true)};
  geaware::io::applyColumnDefinitions(map, defs);
  const auto f = mapFlight(sampleLog(), map, {"height", "specific_force", "battery_voltage"});
  EXPECT_DOUBLE_EQ(f.h_m[0], 0.25);
  EXPECT_DOUBLE_EQ(f.f_B_mps2[2][0],
                   9.0);  // in the column's unit (m/s², not the map's g); FRD → FLU
  EXPECT_DOUBLE_EQ(f.f_B_mps2[1][0], 0.0);
  EXPECT_DOUBLE_EQ(f.vbat_V[0], 12.5);
  auto again = map;
  EXPECT_EQ(errorOf([&] {
              geaware::io::applyColumnDefinitions(again,
                                                  {parseColumnDefinition("vx_mps=1", "--const")});
            }),
            "--column: the map map.yaml has no velocity: define all 3 of its columns");
  EXPECT_NE(errorOf([&] {
              geaware::io::applyColumnDefinitions(again,
                                                  {parseColumnDefinition("foo_m=1", "--const")});
            })
                .find("--const 'foo_m=1': character 1: 'foo_m' is not a column a log map has (h_m, "
                      "a_x_mps2"),
            std::string::npos);
}

}  // namespace
