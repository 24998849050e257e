// SPDX-License-Identifier: BSD-3-Clause
// The X-quadrotor mixer of paper eq. 2 and N_base of eq. 4.
#include "geaware/model/mixer.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "geaware_test/eigen_matchers.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace {

using geaware::model::Mixer;

TEST(Mixer, InverseIsTheInverse) {
  const Mixer mixer(geaware_test::paperParams());
  // Entries of M are ~1e-8; relative tolerance on the identity.
  EXPECT_MATRIX_NEAR(Eigen::Matrix4d(mixer.matrix() * mixer.inverse()), Eigen::Matrix4d::Identity(), 1e-12);
  EXPECT_MATRIX_NEAR(Eigen::Matrix4d(mixer.inverse() * mixer.matrix()), Eigen::Matrix4d::Identity(), 1e-12);
  const Eigen::Vector4d w(16.6, 0.05, -0.03, 0.01);
  EXPECT_MATRIX_NEAR(mixer.wrench(mixer.squaredSpeeds(w)), w, 1e-12);
}

TEST(Mixer, MatrixMatchesThePaper) {
  const auto& p = geaware_test::paperParams();
  const Mixer mixer(p);
  const double arm = std::sqrt(2.0) * p.diagonal_rotor_distance_m / 4.0;
  Eigen::Matrix4d expected;
  expected << 1, 1, 1, 1, -1, 1, 1, -1, -1, 1, -1, 1, -1, -1, 1, 1;
  expected.row(0) *= p.rotor.k_T_N_per_rpm2;
  expected.row(1) *= arm * p.rotor.k_TX_N_per_rpm2;
  expected.row(2) *= arm * p.rotor.k_TY_N_per_rpm2;
  expected.row(3) *= p.rotor.k_I_Nm_per_rpm2;
  EXPECT_MATRIX_NEAR(mixer.matrix(), expected, 0.0);
}

TEST(Mixer, EqualSpeedsGivePureThrust) {
  const auto& p = geaware_test::paperParams();
  const Mixer mixer(p);
  const Eigen::Vector4d n_sq = Eigen::Vector4d::Constant(10000.0 * 10000.0);
  const Eigen::Vector4d w = mixer.wrench(n_sq);
  EXPECT_NEAR(w(0), 4.0 * p.rotor.k_T_N_per_rpm2 * 1e8, 1e-12);
  EXPECT_MATRIX_NEAR(w.tail<3>(), Eigen::Vector3d::Zero(), 1e-15);
  // N_base of a pure-thrust input is pure thrust: Σn² in the first entry, zero elsewhere.
  const Eigen::Vector4d base = mixer.baseSpeeds(n_sq);
  EXPECT_NEAR(base(0), 4e8, 1e-6);
  EXPECT_MATRIX_NEAR(base.tail<3>(), Eigen::Vector3d::Zero(), 1e-9);
  // And pure thrust maps back to equal speeds.
  const Eigen::Vector4d back = mixer.squaredSpeeds(Eigen::Vector4d(w(0), 0, 0, 0));
  EXPECT_MATRIX_NEAR(back, n_sq, 1e-3);
}

TEST(Mixer, BaseSpeedsUndoTheCoefficients) {
  const auto& p = geaware_test::paperParams();
  const Mixer mixer(p);
  const Eigen::Vector4d n_sq(1.0e8, 1.1e8, 0.9e8, 1.05e8);
  const Eigen::Vector4d k(p.rotor.k_T_N_per_rpm2, p.rotor.k_TX_N_per_rpm2, p.rotor.k_TY_N_per_rpm2,
                          p.rotor.k_I_Nm_per_rpm2);
  // Paper eq. 4: N_base = diag(k)⁻¹·M·N².
  EXPECT_MATRIX_NEAR(mixer.baseSpeeds(n_sq), Eigen::Vector4d(k.cwiseInverse().cwiseProduct(mixer.wrench(n_sq))), 1e-3);
}

TEST(Mixer, RotorLayoutIsConsistentWithTheTorqueRows) {
  const auto& p = geaware_test::paperParams();
  const Mixer mixer(p);
  const auto r = Mixer::rotorPositions_B(p.diagonal_rotor_distance_m);
  // Rotor 1 front-right, 2 rear-left, 3 front-left, 4 rear-right; diagonal distance b.
  EXPECT_GT(r[0].x(), 0.0);
  EXPECT_LT(r[0].y(), 0.0);
  EXPECT_LT(r[1].x(), 0.0);
  EXPECT_GT(r[1].y(), 0.0);
  EXPECT_NEAR((r[0] - r[1]).norm(), p.diagonal_rotor_distance_m, 1e-15);
  EXPECT_NEAR((r[2] - r[3]).norm(), p.diagonal_rotor_distance_m, 1e-15);
  // Physics: a thrust f on one rotor at r gives the torque r × (0,0,f); the mixer's roll and
  // pitch rows must say the same when k_TX = k_TY = k_T.
  auto q = p;
  q.rotor.k_TX_N_per_rpm2 = q.rotor.k_TY_N_per_rpm2 = q.rotor.k_T_N_per_rpm2;
  const Mixer iso(q);
  for (int i = 0; i < 4; ++i) {
    Eigen::Vector4d n_sq = Eigen::Vector4d::Zero();
    n_sq(i) = 1e8;
    const Eigen::Vector4d w = iso.wrench(n_sq);
    const Eigen::Vector3d torque = r[static_cast<std::size_t>(i)].cross(Eigen::Vector3d(0, 0, w(0)));
    EXPECT_NEAR(w(1), torque.x(), 1e-12) << "rotor " << i + 1;
    EXPECT_NEAR(w(2), torque.y(), 1e-12) << "rotor " << i + 1;
    EXPECT_NEAR(w(3), Mixer::yawSigns()(i) * q.rotor.k_I_Nm_per_rpm2 * 1e8, 1e-15) << "rotor " << i + 1;
  }
}

}  // namespace
