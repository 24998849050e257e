// SPDX-License-Identifier: BSD-3-Clause
// Log maps: the file format's errors, the NED/FRD → ENU/FLU conversion on closed-form cases,
// the time base, and the observer's a_ext on a hover where thrust balances weight.

#include "geaware/io/config_error.hpp"
#include "geaware/io/log_map.hpp"
#include "geaware/ident/rig_logs.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

namespace {

using geaware::io::LogData;
using geaware::io::Topic;

Topic topic(const std::string& name, double dt, std::size_t n,
            const std::vector<std::pair<std::string, double>>& constant_fields) {
  Topic t;
  t.name = name;
  for (std::size_t i = 0; i < n; ++i) t.time_s.push_back(10.0 + dt * static_cast<double>(i));
  for (const auto& [field, value] : constant_fields) {
    t.channels.push_back({field, "", geaware::io::FieldType::kFloat, std::vector<double>(n, value)});
  }
  return t;
}

const char* kMap = R"(family: test
frames: ned_frd
channels:
  height: {topic: lpos, fields: [z], unit: m, frame: world_z}
  specific_force: {topic: imu, fields: [ax, ay, az], unit: m/s^2, frame: body}
  attitude: {topic: att, fields: [qw, qx, qy, qz], frame: quaternion}
  velocity: {topic: lpos, fields: [vx, vy, vz], unit: mm/s, frame: world}
  rotor_speed: {topic: esc, fields: [n1, n2, n3, n4], unit: rpm}
)";

TEST(LogMap, BuiltInPx4MapLoads) {
  const auto m = geaware::io::loadLogMap("px4");
  EXPECT_EQ(m.frames, "ned_frd");
  EXPECT_EQ(m.channels.at("rotor_speed").fields.size(), 4u);
  EXPECT_EQ(m.channels.at("attitude").topic, "vehicle_attitude");
  EXPECT_THROW((void)geaware::io::loadLogMap("no_such_map"), std::runtime_error);
}

TEST(LogMap, ErrorsNameTheLineAndKey) {
  try {
    (void)geaware::io::parseLogMap("family: x\nframes: ned_frd\nchannels:\n  hieght: {topic: a, fields: [b]}\n"
                                   "  gyro: {topic: a, fields: [b, c], unit: deg/s}\n  velocity: {topic: a, fields: [a, b, c], unit: km/h}\n",
                                   "bad.yaml", "bad");
    FAIL() << "no error";
  } catch (const geaware::io::ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad.yaml:4"), std::string::npos) << what;  // unknown channel 'hieght'
    EXPECT_NE(what.find("hieght"), std::string::npos) << what;
    EXPECT_NE(what.find("2 fields, expected 3"), std::string::npos) << what;
    EXPECT_NE(what.find("km/h"), std::string::npos) << what;
  }
}

TEST(LogMap, NedFrdBecomesEnuFluOnOneTimeBase) {
  LogData log;
  log.source = "synthetic";
  const double s = std::sqrt(0.5);
  // Level, nose east: in NED a yaw of +90° about down; in ENU/FLU the identity.
  log.topics.push_back(topic("att", 0.01, 400, {{"qw", s}, {"qx", 0.0}, {"qy", 0.0}, {"qz", s}}));
  log.topics.push_back(topic("imu", 0.004, 1000, {{"ax", 0.5}, {"ay", 0.25}, {"az", -9.81}}));
  log.topics.push_back(topic("lpos", 0.1, 40, {{"z", -1.5}, {"vx", 1000.0}, {"vy", 2000.0}, {"vz", 3000.0}}));
  log.topics.push_back(topic("esc", 0.25, 16, {{"n1", 5000}, {"n2", 5000}, {"n3", 5000}, {"n4", 5000}}));
  const auto map = geaware::io::parseLogMap(kMap, "map.yaml", "test");
  const auto f = geaware::io::mapFlight(log, map, {"height", "specific_force", "attitude", "velocity", "rotor_speed"});
  EXPECT_EQ(f.time_base, "esc[0]");
  ASSERT_EQ(f.size(), 16u);  // every esc time lies inside the others' spans (10 … 13.75 s)
  EXPECT_DOUBLE_EQ(f.t_s[3], 10.75);
  EXPECT_DOUBLE_EQ(f.h_m[3], 1.5);
  EXPECT_DOUBLE_EQ(f.f_B_mps2[0][3], 0.5);
  EXPECT_DOUBLE_EQ(f.f_B_mps2[1][3], -0.25);
  EXPECT_DOUBLE_EQ(f.f_B_mps2[2][3], 9.81);
  EXPECT_NEAR(f.v_W_mps[0][3], 2.0, 1e-12);  // mm/s scaled, north/east swapped
  EXPECT_NEAR(f.v_W_mps[1][3], 1.0, 1e-12);
  EXPECT_NEAR(f.v_W_mps[2][3], -3.0, 1e-12);
  EXPECT_NEAR(std::abs(f.q_WB[0][3]), 1.0, 1e-12);
  for (int k = 1; k < 4; ++k) EXPECT_NEAR(f.q_WB[static_cast<std::size_t>(k)][3], 0.0, 1e-12);
  // Below 20 Hz: the height and velocity (10 Hz) and the rotor speeds (4 Hz) are named.
  ASSERT_EQ(f.warnings.size(), 3u);
  EXPECT_NE(f.warnings[2].find("rotor_speed (esc[0]) is logged at 4 Hz"), std::string::npos) << f.warnings[2];
  EXPECT_THROW((void)geaware::io::mapFlight(log, map, {"gyro"}), geaware::io::LogError);
}

TEST(LogMap, TheObserverGivesZeroExternalAccelerationInABalancedHover) {
  geaware::io::MappedFlight f;
  f.source = "hover";
  const double m = 1.5, k_T = 2e-8, g = 9.81;
  const double n = std::sqrt(m * g / (4.0 * k_T));  // Σ k_T n² = m g
  for (std::size_t i = 0; i < 5; ++i) {
    f.t_s.push_back(static_cast<double>(i));
    f.h_m.push_back(1.0);
    f.f_B_mps2[0].push_back(0.0), f.f_B_mps2[1].push_back(0.0), f.f_B_mps2[2].push_back(g);
    f.q_WB[0].push_back(1.0), f.q_WB[1].push_back(0.0), f.q_WB[2].push_back(0.0), f.q_WB[3].push_back(0.0);
  }
  f.n_rpm.assign(4, std::vector<double>(5, n));
  // Resting (dropped), for 1 s: less than kMinRestingS, so no resting height is taken from it.
  f.n_rpm[0][2] = f.n_rpm[1][2] = f.n_rpm[2][2] = f.n_rpm[3][2] = 0.0;
  for (auto& t : f.t_s) t *= 0.5;
  const auto r = geaware::ident::flightLogFromMapped(f, m, k_T);
  ASSERT_EQ(r.log.size(), 4u);
  ASSERT_EQ(r.notes.size(), 1u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(r.log.a_ext_W[2][i], 0.0, 1e-12);
  // 10 % more thrust than weight: a_ext = -0.1 g (the observer sees a force pulling down).
  f.n_rpm.assign(4, std::vector<double>(5, n * std::sqrt(1.1)));
  EXPECT_NEAR(geaware::ident::flightLogFromMapped(f, m, k_T).log.a_ext_W[2][0], -0.1 * g, 1e-9);
}

}  // namespace

namespace {

// The ArduPilot map on channels laid out as ArduPilot logs them: Euler angles in degrees (yaw
// wrapping through 360°), one ESC message type per motor instance, NED/FRD.
TEST(LogMap, ArduPilotEulerAnglesAndPerMotorInstances) {
  const auto map = geaware::io::loadLogMap("ardupilot");
  LogData log;
  log.source = "synthetic.bin";
  auto att = topic("ATT", 0.1, 3, {{"Roll", 0.0}, {"Pitch", 0.0}, {"Yaw", 0.0}});
  att.channels[2].values = {89.0, 91.0, 93.0};  // about nose east (yaw 90° in NED)
  log.topics.push_back(att);
  auto wrap = topic("ATT", 0.1, 3, {{"Roll", 0.0}, {"Pitch", 0.0}, {"Yaw", 0.0}});
  for (unsigned m = 0; m < 4; ++m) {
    auto esc = topic("ESC", 0.1, 3, {{"RPM", 4000.0 + 100.0 * m}});
    esc.instance = m;
    log.topics.push_back(esc);
  }
  auto imu = topic("IMU", 0.01, 30, {{"AccX", 0.0}, {"AccY", 0.0}, {"AccZ", -9.81}});
  log.topics.push_back(imu);
  log.topics.push_back(topic("RFND", 0.01, 30, {{"Dist", 0.42}}));
  const auto f = geaware::io::mapFlight(log, map, {"height", "specific_force", "attitude", "rotor_speed"});
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f.time_base, "ATT[0]");  // ATT and ESC both at 10 Hz: the first of them asked for
  ASSERT_EQ(f.n_rpm.size(), 4u);
  EXPECT_DOUBLE_EQ(f.n_rpm[3][1], 4300.0);
  EXPECT_DOUBLE_EQ(f.h_m[0], 0.42);
  EXPECT_DOUBLE_EQ(f.f_B_mps2[2][0], 9.81);
  // Yaw 91° NED (nose 1° south of east) at t = 10.1 s: in ENU a yaw of −1°.
  const double half = -0.5 * 1.0 * M_PI / 180.0;
  EXPECT_NEAR(std::abs(f.q_WB[0][1]), std::cos(half), 1e-12);
  EXPECT_NEAR(f.q_WB[3][1] * (f.q_WB[0][1] > 0 ? 1.0 : -1.0), std::sin(half), 1e-12);
  // The yaw interpolated the short way round through 360°: 359° and 1° give 0° half way.
  wrap.channels[2].values = {359.0, 1.0, 3.0};
  log.topics[0] = wrap;
  for (std::size_t m = 1; m <= 4; ++m) {  // the ESCs at 5 Hz, the time base, from 10.05 s
    log.topics[m].time_s = {10.05, 10.25};
    log.topics[m].channels[0].values.resize(2);
  }
  const auto g = geaware::io::mapFlight(log, map, {"attitude", "rotor_speed"});
  // ESC at 10.05 s lies half way between the ATT samples 359° and 1°: yaw 0° NED = north, in
  // ENU a yaw of +90°; at 10.25 s the attitude has ended (dropped, noted).
  ASSERT_EQ(g.time_base, "ESC[0]");
  ASSERT_EQ(g.size(), 1u);
  EXPECT_NEAR(std::abs(g.q_WB[0][0]), std::cos(M_PI / 4.0), 1e-12);
  EXPECT_NEAR(std::abs(g.q_WB[3][0]), std::sin(M_PI / 4.0), 1e-12);
  EXPECT_GT(g.q_WB[0][0] * g.q_WB[3][0], 0.0);
}

}  // namespace

namespace {

// The Crazyflie map on a CSV export as its logging framework writes it: Timestamp in ms, acc in
// g, ENU/FLU already (no conversion, the height not negated).
TEST(LogMap, CrazyflieCsvExportInMillisecondsAndG) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / "geaware_log_map_cf";
  std::filesystem::create_directories(dir);
  const auto file = dir / "cf.csv";
  {
    std::ofstream out(file);
    out << "Timestamp,stateEstimate.z,acc.x,acc.y,acc.z,stateEstimate.qw,stateEstimate.qx,stateEstimate.qy,"
           "stateEstimate.qz,rpm.m1,rpm.m2,rpm.m3,rpm.m4,pm.vbatMV\n";
    for (int i = 0; i < 50; ++i) {
      out << 1000 + 10 * i << "," << 0.05 + 0.001 * i << ",0.01,-0.02,1.0,1,0,0,0,15000,15100,15200,15300,3900\n";
    }
  }
  const auto log = geaware::io::readLog(file);
  const auto map = geaware::io::loadLogMap("crazyflie");
  const auto f = geaware::io::mapFlight(log, map, {"height", "specific_force", "attitude", "rotor_speed", "battery_voltage"});
  ASSERT_EQ(f.size(), 50u);
  EXPECT_DOUBLE_EQ(f.t_s[1], 1.01);                   // ms → s
  EXPECT_TRUE(f.warnings.empty());                   // 100 Hz
  EXPECT_DOUBLE_EQ(f.h_m[2], 0.052);                 // up, not negated
  EXPECT_DOUBLE_EQ(f.f_B_mps2[2][0], 9.80665);       // g → m/s²
  EXPECT_DOUBLE_EQ(f.f_B_mps2[1][0], -0.02 * 9.80665);  // FLU kept
  // Crazyflie m1-m4 are front-right, rear-right, rear-left, front-left: geaware's rotor 4
  // (rear-right) is m2, rotor 2 (rear-left) m3, rotor 3 (front-left) m4.
  EXPECT_DOUBLE_EQ(f.n_rpm[0][0], 15000.0);
  EXPECT_DOUBLE_EQ(f.n_rpm[1][0], 15200.0);
  EXPECT_DOUBLE_EQ(f.n_rpm[2][0], 15300.0);
  EXPECT_DOUBLE_EQ(f.n_rpm[3][0], 15100.0);
  EXPECT_DOUBLE_EQ(f.vbat_V[0], 3.9);
  EXPECT_DOUBLE_EQ(f.q_WB[0][0], 1.0);
}

}  // namespace

namespace {

// --- vehicles without rotor-speed telemetry (issue 11 item 4) ----------------------------------

const char* kThrottleMap = R"(family: test
frames: enu_flu
channels:
  height: {topic: pos, fields: [h], unit: m}
  specific_force: {topic: pos, fields: [ax, ay, az], unit: m/s^2, frame: body}
  attitude: {topic: pos, fields: [qw, qx, qy, qz], frame: quaternion}
  throttle:
    topic: out
    fields: [C1, C2, C3, C4]
    range: [1000, 2000]
    range_params: [MOT_PWM_MIN, MOT_PWM_MAX]
    rotor_of_motor: [1, 2, 4, 3]
)";

LogData throttleLog(double c1, double c3) {
  LogData log;
  log.source = "pwm.bin";
  log.topics.push_back(topic("pos", 0.1, 11, {{"h", 0.5}, {"ax", 0.0}, {"ay", 0.0}, {"az", 9.81}, {"qw", 1.0},
                                              {"qx", 0.0}, {"qy", 0.0}, {"qz", 0.0}}));
  log.topics.push_back(topic("out", 0.1, 11, {{"C1", c1}, {"C2", 1500.0}, {"C3", c3}, {"C4", 2000.0}}));
  return log;
}

TEST(LogMapThrottle, PwmIsScaledByTheLoggedRangeAndReordered) {
  const auto map = geaware::io::parseLogMap(kThrottleMap, "map.yaml", "test");
  LogData log = throttleLog(1300.0, 1000.0);
  // Without the parameters: the map's 1000…2000 us; at 1000 us the motor is stopped.
  auto f = geaware::io::mapFlight(log, map, {"height", "throttle"});
  ASSERT_EQ(f.throttle.size(), 4u);
  EXPECT_DOUBLE_EQ(f.throttle[0][0], 0.3);
  EXPECT_DOUBLE_EQ(f.throttle[1][0], 0.5);
  EXPECT_DOUBLE_EQ(f.throttle[2][0], 1.0);  // the log's motor 4 is geaware's rotor 3
  EXPECT_DOUBLE_EQ(f.throttle[3][0], geaware::io::kStoppedThrottle);
  EXPECT_EQ(f.throttle_fields[2], "C4");
  bool said = false;
  for (const auto& n : f.notes) said = said || n.find("raw 1000 is 0 and 2000 is 1 (the map's range: the log has no MOT_PWM_MIN)") != std::string::npos;
  EXPECT_TRUE(said);
  // With MOT_PWM_MIN and MOT_PWM_MAX logged: 1100…1900 us.
  log.parameters = {{"MOT_PWM_MIN", 1100.0}, {"MOT_PWM_MAX", 1900.0}};
  f = geaware::io::mapFlight(log, map, {"height", "throttle"});
  EXPECT_DOUBLE_EQ(f.throttle[0][0], 0.25);
  EXPECT_DOUBLE_EQ(f.throttle[2][0], 1.125);
  // ArduPilot's 0 for "the throttle channel's range" is no range: the map's again.
  log.parameters = {{"MOT_PWM_MIN", 0.0}, {"MOT_PWM_MAX", 0.0}};
  EXPECT_DOUBLE_EQ(geaware::io::mapFlight(log, map, {"height", "throttle"}).throttle[0][0], 0.3);
}

TEST(LogMapThrottle, PX4NaNIsAStoppedMotorAndZeroAnIdleOne) {
  const auto map = geaware::io::loadLogMap("px4");
  const auto& c = map.channels.at("throttle");
  EXPECT_TRUE(c.nan_is_stopped);
  LogData log;
  log.source = "px4.ulg";
  log.topics.push_back(topic("vehicle_local_position", 0.1, 5, {{"dist_bottom", 0.3}}));
  auto motors = topic("actuator_motors", 0.1, 5, {{"control[0]", 0.0}, {"control[1]", 0.4}, {"control[2]", 0.4},
                                                  {"control[3]", 0.4}});
  motors.channels[0].values[3] = std::nan("");
  log.topics.push_back(motors);
  // actuator_armed, logged when it changes: disarmed at 10.0 s, armed from 10.25 s.
  auto armed = topic("actuator_armed", 0.25, 3, {{"armed", 0.0}});
  armed.time_s = {10.0, 10.25, 10.4};
  armed.channels[0].values = {0.0, 1.0, 1.0};
  log.topics.push_back(armed);
  auto f = geaware::io::mapFlight(log, map, {"height", "throttle", "armed"});
  ASSERT_EQ(f.size(), 5u);  // the NaN is a value, not a gap; the slow arming state is no time base
  EXPECT_EQ(f.time_base, "vehicle_local_position[0]");
  EXPECT_DOUBLE_EQ(f.throttle[0][0], 0.0);
  EXPECT_DOUBLE_EQ(f.throttle[0][3], geaware::io::kStoppedThrottle);
  EXPECT_DOUBLE_EQ(f.throttle[1][3], 0.4);
  // Held, not interpolated: 0 at 10.1 and 10.2 s, 1 from 10.25 s (10.3, 10.4 s).
  EXPECT_EQ(f.armed, (std::vector<double>{0.0, 0.0, 0.0, 1.0, 1.0}));
  // Through the curve: every motor stopped where disarmed, the idle motor at √c0 where armed.
  geaware::model::ThrottleCurveParams curve;
  curve.c1_rpm2 = 4e8, curve.c0_rpm2 = 1e6;
  const auto r = geaware::ident::rotorSpeedsFromThrottle(f, curve);
  for (std::size_t m = 0; m < 4; ++m) EXPECT_EQ(f.n_rpm[m][2], 0.0);
  EXPECT_DOUBLE_EQ(f.n_rpm[1][4], std::sqrt(4e8 * 0.4 + 1e6));
  EXPECT_DOUBLE_EQ(f.n_rpm[0][4], 1000.0);  // armed at 0: idle
  EXPECT_EQ(f.n_rpm[0][3], 0.0);           // NaN: stopped although armed
  bool said = false;
  for (const auto& n : r.notes) said = said || n.find("3 of 5 samples disarmed") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(LogMapThrottle, BadRangesAreNamed) {
  try {
    (void)geaware::io::parseLogMap("family: x\nframes: enu_flu\nchannels:\n  throttle:\n    fields: [a]\n"
                                   "    range: [2000, 1000]\n    range_params: [LO]\n    pole_pairs: 7\n",
                                   "t.yaml", "t");
    FAIL() << "no error";
  } catch (const geaware::io::ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("t.yaml:6"), std::string::npos) << what;
    EXPECT_NE(what.find("with the second larger"), std::string::npos) << what;
    EXPECT_NE(what.find("expected two parameter names"), std::string::npos) << what;
    EXPECT_NE(what.find("pole_pairs"), std::string::npos) << what;  // a rotor_speed key only
  }
}

geaware::io::MappedFlight throttleFlight(std::vector<double> throttles, std::vector<double> volts) {
  geaware::io::MappedFlight f;
  f.source = "thr";
  for (std::size_t i = 0; i < throttles.size(); ++i) f.t_s.push_back(0.01 * static_cast<double>(i));
  f.throttle.assign(4, throttles);
  f.throttle_fields = {"a", "b", "c", "d"};
  f.vbat_V = std::move(volts);
  return f;
}

TEST(LogMapThrottle, RotorSpeedsFollowTheCurveAndTheBatteryVoltage) {
  geaware::model::ThrottleCurveParams curve;
  curve.c2_rpm2 = -1e8, curve.c1_rpm2 = 5e8, curve.c0_rpm2 = 1e7;
  curve.reference_voltage_V = 16.0, curve.voltage_exponent = 1.0;
  auto f = throttleFlight({0.5, -1.0, 1.25, 0.0}, {15.0, 15.0, 16.0, 16.8});
  const auto r = geaware::ident::rotorSpeedsFromThrottle(f, curve);
  ASSERT_EQ(f.n_rpm.size(), 4u);
  EXPECT_NEAR(f.n_rpm[0][0], std::sqrt(-1e8 * 0.25 + 5e8 * 0.5 + 1e7) * 15.0 / 16.0, 1e-9);
  EXPECT_EQ(f.n_rpm[2][1], 0.0);                                          // stopped
  EXPECT_NEAR(f.n_rpm[1][2], std::sqrt(-1e8 + 5e8 + 1e7), 1e-9);          // 1.25 taken as 1
  EXPECT_NEAR(f.n_rpm[3][3], std::sqrt(1e7) * 16.8 / 16.0, 1e-9);         // idle at 0
  EXPECT_EQ(f.rotor_fields[0], "throttle a");
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("4 throttle values above 1"), std::string::npos) << r.warnings[0];
  // Without a logged voltage the curve holds at V_ref, and that is said.
  auto g = throttleFlight({0.5, 0.5}, {});
  const auto w = geaware::ident::rotorSpeedsFromThrottle(g, curve);
  EXPECT_NEAR(g.n_rpm[0][0], std::sqrt(-1e8 * 0.25 + 5e8 * 0.5 + 1e7), 1e-9);
  ASSERT_EQ(w.warnings.size(), 1u);
  EXPECT_NE(w.warnings[0].find("the log has none"), std::string::npos);
  EXPECT_THROW((void)geaware::ident::rotorSpeedsFromThrottle(g, geaware::model::ThrottleCurveParams{}),
               std::invalid_argument);
}

// A take-off: 3 s disarmed on the ground at 0.10 m, 2 s spinning up there (thrust from 10 % to
// 90 % of the weight), then 5 s of hover at 0.5 m with thrust = weight.
TEST(LogMapThrottle, RowsStandingOnTheGroundAreNotReadAsGroundEffect) {
  geaware::io::MappedFlight f;
  f.source = "takeoff";
  const double m = 1.5, k_T = 2e-8, g = 9.81, dt = 0.05;
  const double n_hover = std::sqrt(m * g / (4.0 * k_T));
  f.n_rpm.assign(4, {});
  for (int i = 0; i < 200; ++i) {
    const double t = dt * i;
    double n = 0.0, h = 0.10;
    if (t >= 3.0 && t < 5.0) n = n_hover * std::sqrt(0.1 + 0.8 * (t - 3.0) / 2.0);
    if (t >= 5.0) n = n_hover, h = 0.5;
    f.t_s.push_back(t);
    f.h_m.push_back(h + 0.003 * std::sin(7.0 * i));  // a range finder's few mm of noise
    f.f_B_mps2[0].push_back(0.0), f.f_B_mps2[1].push_back(0.0), f.f_B_mps2[2].push_back(g);
    f.q_WB[0].push_back(1.0), f.q_WB[1].push_back(0.0), f.q_WB[2].push_back(0.0), f.q_WB[3].push_back(0.0);
    for (auto& r : f.n_rpm) r.push_back(n);
  }
  const auto r = geaware::ident::flightLogFromMapped(f, m, k_T);
  ASSERT_EQ(r.log.size(), 100u);  // the hover only
  for (std::size_t i = 0; i < r.log.size(); ++i) EXPECT_NEAR(r.log.a_ext_W[2][i], 0.0, 1e-9);
  ASSERT_EQ(r.notes.size(), 2u);
  EXPECT_NE(r.notes[0].find("60 of 200 samples with every rotor at 0 rpm"), std::string::npos) << r.notes[0];
  EXPECT_NE(r.notes[1].find("40 of 200 samples standing on the ground"), std::string::npos) << r.notes[1];
  // The same spin-up with no disarmed rows (PX4 armed at idle): the thrust far below what the
  // IMU shows held up marks the ground, with no k_T needed (a k_T 3 times too large changes nothing).
  for (auto& rotor : f.n_rpm) {
    for (std::size_t i = 0; i < 60; ++i) rotor[i] = 0.2 * n_hover;
  }
  EXPECT_EQ(geaware::ident::flightLogFromMapped(f, m, k_T).log.size(), 100u);
  EXPECT_EQ(geaware::ident::flightLogFromMapped(f, m, 3.0 * k_T).log.size(), 100u);
}

}  // namespace

namespace {

// A Crazyflie CSV export without the rpm deck: its PWM ratios (0…65535) are the throttle, in the
// rpm deck's motor order; a cell left empty (a merged export) or -inf in a column the map does not
// use does not stop the read, and a row with a gap in a mapped field is dropped and counted.
TEST(LogMap, CrazyflieCsvWithPwmOnlyAndGaps) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / "geaware_log_map_cf_pwm";
  std::filesystem::create_directories(dir);
  const auto file = dir / "cf_pwm.csv";
  {
    std::ofstream out(file);
    out << "Timestamp,stateEstimate.z,pwm.m1_pwm,pwm.m2_pwm,pwm.m3_pwm,pwm.m4_pwm,unused,pm.vbatMV\n";
    for (int i = 0; i < 30; ++i) {
      out << 1000 + 10 * i << "," << (i == 7 ? std::string() : "0.3") << ",32767.5,0,65535,13107,"
          << (i % 2 == 0 ? "-inf" : "") << "," << (i == 12 ? std::string() : "3900") << "\n";
    }
  }
  const auto log = geaware::io::readLog(file);
  const auto map = geaware::io::loadLogMap("crazyflie");
  const auto f = geaware::io::mapFlight(log, map, {"height", "throttle", "battery_voltage"});
  ASSERT_EQ(f.size(), 29u);  // the height's gap drops its row; the battery's is kept as NaN
  EXPECT_TRUE(std::isnan(f.vbat_V[11]));  // row 12 of the file, after the dropped row 7
  EXPECT_DOUBLE_EQ(f.vbat_V[10], 3.9);
  EXPECT_DOUBLE_EQ(f.throttle[0][0], 0.5);                           // m1: rotor 1
  EXPECT_DOUBLE_EQ(f.throttle[3][0], geaware::io::kStoppedThrottle);  // m2 at 0: rotor 4, stopped
  EXPECT_DOUBLE_EQ(f.throttle[1][0], 1.0);                           // m3: rotor 2
  EXPECT_DOUBLE_EQ(f.throttle[2][0], 0.2);                           // m4: rotor 3
  bool counted = false;
  for (const auto& n : f.notes) counted = counted || n == "1 samples with a NaN in a mapped field: dropped";
  EXPECT_TRUE(counted);
}

}  // namespace
