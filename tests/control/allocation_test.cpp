// SPDX-License-Identifier: BSD-3-Clause
// The control allocation: exact inversion inside the range, and the priorities (thrust, then
// roll/pitch, then yaw) when the wrench does not fit.
#include "geaware/control/allocation.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "geaware/model/mixer.hpp"
#include "geaware_test/eigen_matchers.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace {

using geaware::control::allocateRotorSpeeds;
using geaware::control::RotorAllocation;

class Allocation : public ::testing::Test {
 protected:
  geaware::model::Mixer mixer{geaware_test::paperParams()};
  double n_min = 2000.0, n_max = 20000.0;
  [[nodiscard]] double lo() const { return n_min * n_min; }
  [[nodiscard]] double hi() const { return n_max * n_max; }
  /// The wrench of a speed pattern inside the range.
  [[nodiscard]] Eigen::Vector4d wrenchOf(const Eigen::Vector4d& n_rpm) const {
    return mixer.wrench(n_rpm.cwiseProduct(n_rpm));
  }
};

TEST_F(Allocation, InvertsTheMixerExactlyInsideTheRange) {
  const Eigen::Vector4d w = wrenchOf(Eigen::Vector4d(11000, 12500, 11800, 12100));
  const RotorAllocation a = allocateRotorSpeeds(mixer.inverse(), w(0), w.tail<3>(), n_min, n_max);
  EXPECT_FALSE(a.thrust_saturated || a.roll_pitch_saturated || a.yaw_saturated);
  EXPECT_MATRIX_NEAR(mixer.wrench(a.n_sq_rpm2), w, 1e-9 * w.norm());
}

TEST_F(Allocation, ThrustIsClippedToTheRangeAndTorquesKeepTheirShare) {
  const Eigen::Vector4d high = wrenchOf(Eigen::Vector4d::Constant(25000.0));
  const RotorAllocation a = allocateRotorSpeeds(mixer.inverse(), high(0), Eigen::Vector3d::Zero(), n_min, n_max);
  EXPECT_TRUE(a.thrust_saturated);
  EXPECT_MATRIX_NEAR(a.n_sq_rpm2, Eigen::Vector4d::Constant(hi()), 1e-6);
  const RotorAllocation b = allocateRotorSpeeds(mixer.inverse(), -1.0, Eigen::Vector3d::Zero(), n_min, n_max);
  EXPECT_TRUE(b.thrust_saturated);
  EXPECT_MATRIX_NEAR(b.n_sq_rpm2, Eigen::Vector4d::Constant(lo()), 1e-6);
}

TEST_F(Allocation, YawIsCutBeforeRollAndPitch) {
  // Near full thrust a large roll and yaw demand cannot both fit: roll is kept, yaw cut.
  const Eigen::Vector4d base = wrenchOf(Eigen::Vector4d::Constant(17000.0));
  const Eigen::Vector4d roll = wrenchOf(Eigen::Vector4d(16000, 18000, 18000, 16000)) - base;
  const Eigen::Vector4d yaw = wrenchOf(Eigen::Vector4d(16000, 16000, 18000, 18000)) - base;
  const Eigen::Vector3d tau(roll(1), 0.0, 3.0 * yaw(3));
  const RotorAllocation a = allocateRotorSpeeds(mixer.inverse(), base(0), tau, n_min, n_max);
  EXPECT_FALSE(a.thrust_saturated);
  EXPECT_FALSE(a.roll_pitch_saturated);
  EXPECT_TRUE(a.yaw_saturated);
  const Eigen::Vector4d got = mixer.wrench(a.n_sq_rpm2);
  EXPECT_NEAR(got(0), base(0), 1e-9 * base(0));  // thrust kept
  EXPECT_NEAR(got(1), tau.x(), 1e-9 * std::abs(tau.x()));  // roll kept
  EXPECT_GT(std::abs(got(3)), 0.0);
  EXPECT_LT(std::abs(got(3)), std::abs(tau.z()));  // yaw reduced, same sign
  EXPECT_GT(got(3) * tau.z(), 0.0);
  EXPECT_LE(a.n_sq_rpm2.maxCoeff(), hi());
  EXPECT_GE(a.n_sq_rpm2.minCoeff(), lo());
  // Some rotor sits on a bound: yaw got the largest share that fits.
  EXPECT_TRUE((a.n_sq_rpm2.array() >= hi() * (1 - 1e-12)).any() ||
              (a.n_sq_rpm2.array() <= lo() * (1 + 1e-12)).any());
}

TEST_F(Allocation, RollPitchScaledWhenTheyDoNotFit) {
  const Eigen::Vector4d base = wrenchOf(Eigen::Vector4d::Constant(19000.0));
  const Eigen::Vector3d tau(10.0, -10.0, 0.0);  // far beyond what 1000 rpm of headroom gives
  const RotorAllocation a = allocateRotorSpeeds(mixer.inverse(), base(0), tau, n_min, n_max);
  EXPECT_TRUE(a.roll_pitch_saturated);
  EXPECT_FALSE(a.yaw_saturated);
  const Eigen::Vector4d got = mixer.wrench(a.n_sq_rpm2);
  // Scaled as a whole: the direction of (τx, τy) is kept.
  EXPECT_NEAR(got(1) / got(2), tau.x() / tau.y(), 1e-9);
  EXPECT_NEAR(got(0), base(0), 1e-9 * base(0));
}

}  // namespace
