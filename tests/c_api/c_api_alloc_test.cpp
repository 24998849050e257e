// SPDX-License-Identifier: BSD-3-Clause
// The C interface's update allocates nothing (c_api.h promises it): counted with the test
// allocation counter over a second of hover and garbage inputs, after creation.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geaware/c_api.h"
#include "geaware_test/allocation_counter.hpp"

TEST(CApi, UpdateNeverAllocatesAfterCreation) {
  geaware_vehicle v;
  ASSERT_EQ(geaware_vehicle_builtin(&v), GEAWARE_OK);
  geaware_controller* c = nullptr;
  char msg[256];
  ASSERT_EQ(geaware_controller_create(&v, "recommended", 200.0, &c, msg, sizeof msg), GEAWARE_OK)
      << msg;
  geaware_controller_input in{};
  in.ref_position_m[2] = in.position_m[2] = in.height_m = 0.2;
  in.attitude_wxyz[0] = 1.0;
  in.accel_mps2[2] = 9.81;
  in.height_valid = 1;
  for (double& n : in.rotor_speeds_rpm) n = 10000.0;
  geaware_controller_output out{};
  const long before = geaware_test::allocationCount();
  for (int i = 0; i < 200; ++i) {
    in.t_s = i / 200.0;
    in.gyro_radps[0] = i % 50 == 7 ? std::numeric_limits<double>::quiet_NaN() : 0.0;
    ASSERT_EQ(geaware_controller_update(c, &in, &out), GEAWARE_OK);
    for (double t : out.throttle) ASSERT_TRUE(t >= 0.0 && t <= 1.0);
  }
  EXPECT_EQ(geaware_test::allocationCount() - before, 0);
  geaware_controller_destroy(c);
}
