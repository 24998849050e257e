// SPDX-License-Identifier: BSD-3-Clause
// FlatOutput::allFinite: each of its eighteen numbers, and finite extremes whose sum overflows.
#include "geaware/traj/flat_output.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMax = std::numeric_limits<double>::max();

TEST(FlatOutput, FlatOutputChecksEachOfItsEighteenNumbers) {
  geaware::traj::FlatOutput f;
  f.p_W = {kMax, kMax, -kMax};
  f.s_W = {kMax, 0.0, 0.0};
  EXPECT_TRUE(f.allFinite());
  for (int k = 0; k < 18; ++k) {
    for (double bad : {kInf, -kInf, kNaN}) {
      geaware::traj::FlatOutput g = f;
      double* slot = k < 15 ? &(k < 3    ? g.p_W
                                : k < 6  ? g.v_W
                                : k < 9  ? g.a_W
                                : k < 12 ? g.j_W
                                         : g.s_W)[k % 3]
                   : k == 15 ? &g.yaw_rad
                   : k == 16 ? &g.yaw_rate_radps
                             : &g.yaw_acc_radps2;
      *slot = bad;
      EXPECT_FALSE(g.allFinite()) << "number " << k << " = " << bad;
    }
  }
}

}  // namespace
