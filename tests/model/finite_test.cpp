// SPDX-License-Identifier: BSD-3-Clause
// model::allFinite against Eigen's allFinite() (the oracle), on every kind of non-finite value
// in every position and on finite extremes whose sum would overflow.
#include "geaware/model/finite.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Geometry>


namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMax = std::numeric_limits<double>::max();
constexpr double kDenorm = std::numeric_limits<double>::denorm_min();

TEST(AllFinite, AgreesWithEigenForEveryValueInEveryPosition) {
  const double values[] = {0.0, -0.0, 1.0, -kMax, kMax, kDenorm, -kDenorm, kInf, -kInf, kNaN, -kNaN};
  for (double a : values) {
    for (int pos = 0; pos < 4; ++pos) {
      Eigen::Vector4d v(1.0, -2.0, kMax, -kMax);  // finite, though their sum overflows
      v[pos] = a;
      EXPECT_EQ(geaware::model::allFinite(v), v.allFinite()) << "value " << a << " at " << pos;
      Eigen::Matrix3d m = Eigen::Matrix3d::Constant(kMax);
      m(pos % 3, (pos + 1) % 3) = a;
      EXPECT_EQ(geaware::model::allFinite(m), m.allFinite()) << "value " << a << " at " << pos;
      const Eigen::Quaterniond q(v[0], v[1], v[2], v[3]);
      EXPECT_EQ(geaware::model::allFinite(q.coeffs()), q.coeffs().allFinite());
    }
  }
  EXPECT_TRUE(geaware::model::allFinite(Eigen::Vector3d(kMax, kMax, kMax)));
  EXPECT_FALSE(geaware::model::allFinite(Eigen::Vector3d(kInf, -kInf, 0.0)));
}

TEST(AllFinite, RandomPatternsOfTheDynamicSizes) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> pick(0, 9);
  for (int trial = 0; trial < 500; ++trial) {
    Eigen::MatrixXd m(1 + trial % 7, 1 + trial % 5);
    for (Eigen::Index i = 0; i < m.size(); ++i) {
      const int k = pick(rng);
      m(i) = k == 0 ? kInf : k == 1 ? kNaN : k == 2 ? -kInf : (k - 5) * 1e300;
    }
    EXPECT_EQ(geaware::model::allFinite(m), m.allFinite()) << m;
  }
}

}  // namespace
