// SPDX-License-Identifier: BSD-3-Clause
// geaware samples ↔ PX4 messages (bridge/px4_codec.hpp, bridge/ranger_zones.hpp): round trips,
// and the fields a PX4 reader relies on (frames, units, motor order).
#include <gtest/gtest.h>

#include <cmath>

#include "geaware/bridge/px4_codec.hpp"
#include "geaware/bridge/ranger_zones.hpp"

namespace geaware::bridge {
namespace {

TEST(Codec, ImuRoundTripAndFrdOnTheWire) {
  model::ImuSample s;
  s.t_s = 1.234;
  s.gyro_B = {0.1, -0.2, 0.3};
  s.accel_B = {0.5, 0.25, 9.81};
  Px4SensorCombined m;
  encodeImu(s, 0.005, m);
  EXPECT_EQ(m.timestamp, 1234000u);
  EXPECT_EQ(m.gyro_integral_dt, 5000u);
  EXPECT_FLOAT_EQ(m.accelerometer_m_s2[2], -9.81f);  // at rest PX4 reads −g on z (FRD)
  EXPECT_FLOAT_EQ(m.gyro_rad[1], 0.2f);
  const model::ImuSample back = decodeImu(m);
  EXPECT_DOUBLE_EQ(back.t_s, 1.234);
  EXPECT_TRUE(back.gyro_B.isApprox(s.gyro_B, 1e-7));
  EXPECT_TRUE(back.accel_B.isApprox(s.accel_B, 1e-7));
}

TEST(Codec, PoseRoundTripKeepsCaptureAndDeliveryTimes) {
  model::MocapSample s;
  s.t_s = 2.0;
  s.p_W = {1.0, -0.5, 0.12};
  s.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, -0.4, 1.0).normalized()));
  Px4Odometry m;
  encodePose(s, 2.004, m);
  EXPECT_EQ(m.timestamp, 2004000u);
  EXPECT_EQ(m.timestamp_sample, 2000000u);
  EXPECT_EQ(m.pose_frame, 1);
  EXPECT_FLOAT_EQ(m.position[2], -0.12f);  // down
  EXPECT_FLOAT_EQ(m.position[0], -0.5f);   // north = ENU y
  EXPECT_TRUE(std::isnan(m.velocity[0]));
  const DecodedPose d = decodePose(m);
  ASSERT_TRUE(d.valid);
  EXPECT_DOUBLE_EQ(d.delivered_t_s, 2.004);
  EXPECT_DOUBLE_EQ(d.pose.t_s, 2.0);
  EXPECT_TRUE(d.pose.p_W.isApprox(s.p_W, 1e-7));
  EXPECT_LT(d.pose.q_WB.angularDistance(s.q_WB), 1e-6);
  m.pose_frame = 2;  // FRD: not a frame the estimator can use
  EXPECT_FALSE(decodePose(m).valid);
}

TEST(Codec, EscFollowsTheMotorMap) {
  model::RotorTelemetry r;
  r.t_s = 0.5;
  r.n_rpm = {10000.4, 11000.6, 12000.0, 13000.0};
  MotorMap map;
  map.px4_index = {2, 0, 3, 1};
  Px4EscStatus m;
  encodeEsc(r, map, m);
  EXPECT_EQ(m.esc[2].esc_rpm, 10000);
  EXPECT_EQ(m.esc[0].esc_rpm, 11001);
  EXPECT_EQ(m.esc[3].actuator_function, 104);
  EXPECT_EQ(m.esc_online_flags, 0x0f);
  const model::RotorTelemetry back = decodeEsc(m, map);
  EXPECT_EQ(back.n_rpm, Eigen::Vector4d(10000, 11001, 12000, 13000));
}

TEST(Codec, MotorsThroughThrustModelAndMap) {
  MotorMap map;
  map.px4_index = {1, 0, 3, 2};
  Px4ActuatorMotors m;
  encodeMotors(1.0, 0.995, {0.1, 0.2, 0.3, 0.4}, 0.5, map, m);
  EXPECT_EQ(m.timestamp_sample, 995000u);
  EXPECT_NEAR(m.control[1], 0.5 * 0.01 + 0.5 * 0.1, 1e-7);  // rotor 1 → PX4 motor 2
  EXPECT_TRUE(std::isnan(m.control[4]));                   // unused motors stopped
  const auto u = decodeMotors(m, 0.5, map);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(u[i], 0.1 * static_cast<double>(i + 1), 1e-6);
  m.control[0] = std::nanf("");
  EXPECT_EQ(decodeMotors(m, 0.5, map)[1], 0.0);  // NaN: disarmed, stopped
}

TEST(Codec, ClockInMicroseconds) {
  RosClock c;
  encodeClock(12.345678, c);
  EXPECT_EQ(c.clock.sec, 12);
  EXPECT_EQ(c.clock.nanosec, 345678000u);
  EXPECT_EQ(decodeClockUs(c), 12345678u);
}

TEST(Codec, LatticeZonesReassembleIntoTheFrame) {
  model::RangerFrame f;
  f.t_s = 0.03;
  f.side = 4;
  f.fov_rad = 0.7;
  for (int z = 0; z < 16; ++z) {
    f.range_m[static_cast<std::size_t>(z)] = 0.1 + 0.01 * z;
    f.valid[static_cast<std::size_t>(z)] = z != 5;
  }
  RangerAssembler a(Eigen::Vector3d(0.0, 0.0, -0.03));
  Px4DistanceSensor m;
  for (int z = 15; z >= 0; --z) {  // any order
    encodeRangerZone(f, z, 4.0, m);
    EXPECT_EQ(a.add(m), z == 0) << z;
  }
  const model::RangerFrame& g = a.frame();
  EXPECT_EQ(g.side, 4);
  EXPECT_NEAR(g.fov_rad, 0.7, 1e-7);
  EXPECT_DOUBLE_EQ(g.t_s, 0.03);
  EXPECT_EQ(g.mount_B, Eigen::Vector3d(0.0, 0.0, -0.03));
  for (int z = 0; z < 16; ++z) {
    const auto k = static_cast<std::size_t>(z);
    EXPECT_EQ(g.valid[k], z != 5);
    EXPECT_NEAR(g.range_m[k], f.range_m[k], 1e-7);
  }
  // The zone's q turns the sensor's +x onto the zone's ray (FRD).
  encodeRangerZone(f, 7, 4.0, m);
  const Eigen::Quaterniond q(m.q[0], m.q[1], m.q[2], m.q[3]);
  EXPECT_TRUE((q * Eigen::Vector3d::UnitX()).isApprox(fluToFrd(f.zoneDirection_B(1, 3)), 1e-6));
}

TEST(Codec, IncompleteLatticeFrameIsDroppedAndSingleBeamIsOneZone) {
  model::RangerFrame f;
  f.side = 2;
  f.fov_rad = 0.5;
  f.t_s = 0.01;
  RangerAssembler a(Eigen::Vector3d::Zero());
  Px4DistanceSensor m;
  encodeRangerZone(f, 0, 4.0, m);
  EXPECT_FALSE(a.add(m));
  f.t_s = 0.02;
  for (int z = 0; z < 4; ++z) {
    encodeRangerZone(f, z, 4.0, m);
    (void)a.add(m);
  }
  EXPECT_EQ(a.droppedFrames(), 1u);
  // A plain downward rangefinder (PX4's own device id): a 1×1 frame looking straight down.
  Px4DistanceSensor lidar{};
  lidar.timestamp = 50000;
  lidar.device_id = 0x00123456;
  lidar.current_distance = 0.42f;
  lidar.signal_quality = -1;
  ASSERT_TRUE(a.add(lidar));
  EXPECT_EQ(a.frame().side, 1);
  EXPECT_TRUE(a.frame().valid[0]);
  EXPECT_TRUE(a.frame().zoneDirection_B(0, 0).isApprox(-Eigen::Vector3d::UnitZ()));
}

}  // namespace
}  // namespace geaware::bridge
