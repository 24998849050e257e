// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Checks shared by the trajectory tests: analytic derivatives against finite differences of
// the derivative below, and continuity of p…snap across a joint.

#include <cmath>
#include <type_traits>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "geaware/traj/trajectory.hpp"
#include "geaware_test/eigen_matchers.hpp"

namespace geaware_test {

/// Fourth-order central difference (f(t−2h) − 8f(t−h) + 8f(t+h) − f(t+2h)) / 12h. Its
/// truncation error is h⁴/30·f⁽⁵⁾ and its rounding error about 1.5·ε·|f|/h, so with h = 1e-3
/// both are far below 1e-8 for the trajectories tested here, as long as the stencil does not
/// straddle a joint where a derivative above snap jumps (callers keep 2h away from joints).
/// The result is evaluated (no Eigen expression left pointing at temporaries).
template <typename F>
auto centralDifference(const F& f, double t, double h) -> std::decay_t<decltype(f(t))> {
  using R = std::decay_t<decltype(f(t))>;
  const R m2 = f(t - 2.0 * h);
  const R m1 = f(t - h);
  const R p1 = f(t + h);
  const R p2 = f(t + 2.0 * h);
  return R(((m2 - p2) + 8.0 * (p1 - m1)) / (12.0 * h));
}

/// Each of v, a, j, snap, ψ̇, ψ̈ equals the central difference of the one below it at t, to
/// tol·(1 + |expected|).
inline void expectDerivativesMatchFiniteDifferences(const geaware::traj::Trajectory& traj, double t,
                                                    double h, double tol) {
  SCOPED_TRACE(::testing::Message() << "t = " << t);
  using geaware::traj::FlatOutput;
  const FlatOutput o = traj.sample(t);
  const auto check = [&](const Eigen::Vector3d& analytic, auto member) {
    const Eigen::Vector3d fd = centralDifference(
        [&](double s) -> Eigen::Vector3d { return traj.sample(s).*member; }, t, h);
    EXPECT_MATRIX_NEAR(analytic, fd, tol * (1.0 + analytic.cwiseAbs().maxCoeff()));
  };
  check(o.v_W, &FlatOutput::p_W);
  check(o.a_W, &FlatOutput::v_W);
  check(o.j_W, &FlatOutput::a_W);
  check(o.s_W, &FlatOutput::j_W);
  const double yaw_rate = centralDifference([&](double s) { return traj.sample(s).yaw_rad; }, t, h);
  const double yaw_acc =
      centralDifference([&](double s) { return traj.sample(s).yaw_rate_radps; }, t, h);
  EXPECT_NEAR(o.yaw_rate_radps, yaw_rate, tol * (1.0 + std::abs(o.yaw_rate_radps)));
  EXPECT_NEAR(o.yaw_acc_radps2, yaw_acc, tol * (1.0 + std::abs(o.yaw_acc_radps2)));
}

/// p, v, a, j, snap and ψ, ψ̇, ψ̈ agree at t − δ and t + δ to tol. With δ tiny, a continuous
/// quantity changes by at most 2δ·max|next derivative|; a jump of any size above tol fails.
inline void expectContinuousAt(const geaware::traj::Trajectory& traj, double t, double delta,
                               double tol) {
  SCOPED_TRACE(::testing::Message() << "joint at t = " << t);
  const geaware::traj::FlatOutput l = traj.sample(t - delta);
  const geaware::traj::FlatOutput r = traj.sample(t + delta);
  EXPECT_MATRIX_NEAR(l.p_W, r.p_W, tol);
  EXPECT_MATRIX_NEAR(l.v_W, r.v_W, tol);
  EXPECT_MATRIX_NEAR(l.a_W, r.a_W, tol);
  EXPECT_MATRIX_NEAR(l.j_W, r.j_W, tol);
  EXPECT_MATRIX_NEAR(l.s_W, r.s_W, tol);
  EXPECT_NEAR(l.yaw_rad, r.yaw_rad, tol);
  EXPECT_NEAR(l.yaw_rate_radps, r.yaw_rate_radps, tol);
  EXPECT_NEAR(l.yaw_acc_radps2, r.yaw_acc_radps2, tol);
}

}  // namespace geaware_test
