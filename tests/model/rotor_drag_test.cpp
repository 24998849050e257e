// SPDX-License-Identifier: BSD-3-Clause
// Height-dependent rotor-drag table: interpolation, clamping and the drag force.
#include "geaware/model/rotor_drag.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "geaware_test/eigen_matchers.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace {

using geaware::model::DragTableParams;
using geaware::model::RotorDragModel;

TEST(RotorDrag, InterpolatesLinearlyAndHoldsOutsideTheTable) {
  const DragTableParams t{{0.1, 0.5, 2.0}, {0.2, 0.3, 0.4}, {0.1, 0.2, 0.6}};
  const RotorDragModel drag(t);
  EXPECT_MATRIX_NEAR(drag.coefficients(0.1), Eigen::Vector2d(0.2, 0.1), 1e-15);
  EXPECT_MATRIX_NEAR(drag.coefficients(0.3), Eigen::Vector2d(0.25, 0.15), 1e-15);
  EXPECT_MATRIX_NEAR(drag.coefficients(1.25), Eigen::Vector2d(0.35, 0.4), 1e-15);
  EXPECT_MATRIX_NEAR(drag.coefficients(0.0), Eigen::Vector2d(0.2, 0.1), 0.0);   // below: first row
  EXPECT_MATRIX_NEAR(drag.coefficients(50.0), Eigen::Vector2d(0.4, 0.6), 0.0);  // above: last row
  EXPECT_MATRIX_NEAR(drag.highAltitudeCoefficients(), Eigen::Vector2d(0.4, 0.6), 0.0);
  EXPECT_TRUE(drag.coefficients(std::nan("")).hasNaN());
}

TEST(RotorDrag, SingleRowTableIsConstant) {
  const RotorDragModel drag(DragTableParams{{1.0}, {0.3}, {0.2}});
  for (double h : {0.0, 1.0, 7.0}) EXPECT_MATRIX_NEAR(drag.coefficients(h), Eigen::Vector2d(0.3, 0.2), 0.0);
}

TEST(RotorDrag, PaperVehicleReproducesTheMeasuredNearGroundRatio) {
  const auto& drag = geaware_test::paperVehicle().drag();
  const Eigen::Vector2d low = drag.coefficients(0.1);
  const Eigen::Vector2d high = drag.coefficients(2.0);
  // Paper, section on rotor drag: d_x(0.1)/d_x(2.0) = 0.5963, d_y(0.1)/d_y(2.0) = 0.6179.
  EXPECT_NEAR(low.x() / high.x(), 0.5963, 5e-4);
  EXPECT_NEAR(low.y() / high.y(), 0.6179, 5e-4);
  EXPECT_NEAR(high.x(), 0.397, 1e-12);
  EXPECT_NEAR(high.y(), 0.330, 1e-12);
}

TEST(RotorDrag, ForceOpposesInPlaneVelocityAndIgnoresAxialVelocity) {
  const Eigen::Vector2d d(0.4, 0.3);
  // Level: drag is −diag(d)·v in x and y, nothing along z.
  EXPECT_MATRIX_NEAR(RotorDragModel::force_W(Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 2, 3), d),
                     Eigen::Vector3d(-0.4, -0.6, 0.0), 1e-15);
  // Rotated: equals R·(−D·Rᵀv), and never adds energy (vᵀf ≤ 0).
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX())).toRotationMatrix();
  const Eigen::Vector3d v(2.0, -1.0, 0.5);
  const Eigen::Vector3d vb = R.transpose() * v;
  const Eigen::Vector3d expected = -R * Eigen::Vector3d(d.x() * vb.x(), d.y() * vb.y(), 0.0);
  EXPECT_MATRIX_NEAR(RotorDragModel::force_W(R, v, d), expected, 1e-15);
  EXPECT_LE(v.dot(RotorDragModel::force_W(R, v, d)), 0.0);
  // A purely axial velocity (along z_B) produces no rotor drag.
  EXPECT_MATRIX_NEAR(RotorDragModel::force_W(R, R.col(2) * 3.0, d), Eigen::Vector3d::Zero(), 1e-15);
  // The thrust-scaled form is the same with d·√T.
  EXPECT_MATRIX_NEAR(RotorDragModel::thrustScaledForce_W(R, v, d, 16.0),
                     RotorDragModel::force_W(R, v, 4.0 * d), 1e-15);
}

}  // namespace
