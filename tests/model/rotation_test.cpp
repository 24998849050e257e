// SPDX-License-Identifier: BSD-3-Clause
// The rotation helpers: Log/Exp maps and the angle between attitudes.
#include "geaware/model/rotation.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "geaware_test/eigen_matchers.hpp"

namespace {

using Eigen::AngleAxisd;
using Eigen::Quaterniond;
using Eigen::Vector3d;
using geaware::model::angleBetween;
using geaware::model::expMap;
using geaware::model::logMap;

TEST(Rotation, ExpLogRoundTripAndShortestPath) {
  for (const Vector3d& th :
       {Vector3d(0.1, -0.2, 0.3), Vector3d(1e-12, 0, 0), Vector3d(0, 3.0, 0)}) {
    EXPECT_MATRIX_NEAR(logMap(expMap(th)), th, 1e-12);
  }
  const Quaterniond q = expMap(Vector3d(0.2, 0.1, -0.3));
  EXPECT_MATRIX_NEAR(logMap(Quaterniond(-q.coeffs())), logMap(q), 1e-12);
}

TEST(Rotation, ExpMatchesAngleAxisAndLogTakesTheShortWay) {
  const Vector3d axis = Vector3d(1.0, -2.0, 0.5).normalized();
  const Quaterniond expected(AngleAxisd(0.8, axis));
  EXPECT_MATRIX_NEAR(expMap(0.8 * axis).coeffs(), expected.coeffs(), 1e-15);
  // 1.5π about the axis is −0.5π about it.
  const Quaterniond long_way(AngleAxisd(1.5 * std::numbers::pi, axis));
  EXPECT_MATRIX_NEAR(logMap(long_way), -0.5 * std::numbers::pi * axis, 1e-12);
}

TEST(Rotation, AngleBetweenAttitudes) {
  const Vector3d axis = Vector3d(0.3, 0.4, -1.0).normalized();
  const Quaterniond a(AngleAxisd(0.4, Vector3d::UnitZ()));
  const Quaterniond b = a * Quaterniond(AngleAxisd(0.25, axis));
  EXPECT_NEAR(angleBetween(a, b), 0.25, 1e-14);
  EXPECT_NEAR(angleBetween(b, a), 0.25, 1e-14);
  // q and −q are one attitude; beyond π the short way is taken.
  EXPECT_NEAR(angleBetween(a, Quaterniond(-b.coeffs())), 0.25, 1e-14);
  const Quaterniond c = a * Quaterniond(AngleAxisd(1.5 * std::numbers::pi, axis));
  EXPECT_NEAR(angleBetween(a, c), 0.5 * std::numbers::pi, 1e-12);
  EXPECT_EQ(angleBetween(a, a), 0.0);
}

}  // namespace
