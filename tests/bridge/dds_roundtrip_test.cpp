// SPDX-License-Identifier: BSD-3-Clause
// The generated types over a real DDS domain on this machine (unicast 127.0.0.1, no multicast,
// a domain of this test's own): the type names a ROS 2 node sees, and a sample written comes
// back field for field.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <string>
#include <thread>

#include "geaware/bridge/dds_node.hpp"
#include "geaware/bridge/px4_codec.hpp"

namespace geaware::bridge {
namespace {

TEST(DdsTypes, NamesAreThoseOfPx4MsgsAndRos2) {
  EXPECT_STREQ(px4_msgs_msg_dds__VehicleOdometry__desc.m_typename, "px4_msgs::msg::dds_::VehicleOdometry_");
  EXPECT_STREQ(px4_msgs_msg_dds__ActuatorMotors__desc.m_typename, "px4_msgs::msg::dds_::ActuatorMotors_");
  EXPECT_STREQ(rosgraph_msgs_msg_dds__Clock__desc.m_typename, "rosgraph_msgs::msg::dds_::Clock_");
  DdsSettings d;
  EXPECT_EQ(px4Topic(d, "out", "vehicle_odometry"), "rt/fmu/out/vehicle_odometry");
  d.px4_namespace = "px4_1";
  EXPECT_EQ(px4Topic(d, "in", "actuator_motors"), "rt/px4_1/fmu/in/actuator_motors");
  const std::string xml = cycloneConfig(DdsSettings{});
  EXPECT_NE(xml.find("<AllowMulticast>false</AllowMulticast>"), std::string::npos);
  EXPECT_NE(xml.find("<Peer address=\"127.0.0.1\"/>"), std::string::npos);
}

TEST(DdsTypes, OdometryAndMotorsRoundTripThroughADomain) {
  DdsSettings d;
  d.domain_id = 111;  // this test's own
  DdsParticipant p(d);
  const auto w = makeWriter(p, px4Topic(d, "out", "vehicle_odometry"),
                            &px4_msgs_msg_dds__VehicleOdometry__desc, {true, 4});
  const auto r = makeReader(p, px4Topic(d, "out", "vehicle_odometry"),
                            &px4_msgs_msg_dds__VehicleOdometry__desc, {true, 4});
  for (int i = 0; i < 200 && matchedReaders(w) < 1; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_GE(matchedReaders(w), 1);
  model::MocapSample s;
  s.t_s = 3.25;
  s.p_W = {0.5, 1.5, 0.2};
  Px4Odometry sent;
  encodePose(s, 3.255, sent);
  ASSERT_EQ(dds_write(w, &sent), DDS_RETCODE_OK);
  TakeBuffer<Px4Odometry, 4> got;
  int n = 0;
  for (int i = 0; i < 200 && n == 0; ++i) {
    n = got.take(r);
    if (n == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_EQ(n, 1);
  EXPECT_EQ(got[0].timestamp, sent.timestamp);
  EXPECT_EQ(got[0].timestamp_sample, sent.timestamp_sample);
  EXPECT_EQ(std::memcmp(got[0].position, sent.position, sizeof sent.position), 0);
  EXPECT_EQ(std::memcmp(got[0].q, sent.q, sizeof sent.q), 0);
  EXPECT_TRUE(std::isnan(got[0].velocity[1]));
  EXPECT_EQ(got[0].pose_frame, 1);
}

}  // namespace
}  // namespace geaware::bridge
