// SPDX-License-Identifier: BSD-3-Clause
// Differential flatness with ground effect: closed-form hover cases, reduction to the plain
// drag-aware map, finite-difference checks of ω and ω̇, and the oracle test — the map's inputs
// integrated through the model it inverts reproduce the trajectory.
#include "geaware/flatness/flat_map.hpp"

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "geaware/model/units.hpp"
#include "geaware/traj/hover_descent.hpp"
#include "geaware/traj/lemniscate.hpp"
#include "geaware_test/eigen_matchers.hpp"
#include "geaware_test/flat_model_plant.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace {

using geaware::flatness::FlatMap;
using geaware::flatness::FlatMapStatus;
using geaware::flatness::FlatState;
using geaware::flatness::GroundEffectTerms;
using geaware::model::kGravity;
using geaware::traj::FlatOutput;
using geaware_test::paperVehicle;

FlatOutput hoverAt(double z, double yaw = 0.0, double yaw_rate = 0.0) {
  FlatOutput r;
  r.p_W = Eigen::Vector3d(1.0, -2.0, z);
  r.yaw_rad = yaw;
  r.yaw_rate_radps = yaw_rate;
  return r;
}

/// The paper's exp-7 lemniscate: ±4 m × ±1.7 m at 0.18 m, 3 m/s peak.
geaware::traj::Lemniscate fastLemniscate() {
  geaware::traj::LemniscateParams p;
  p.half_extent_x_m = 4.0;
  p.half_extent_y_m = 1.7;
  p.height_m = 0.18;
  p.peak_speed_mps = 3.0;
  p.ramp_time_s = 2.0;
  p.yaw_rad = 0.4;
  return geaware::traj::Lemniscate(p);
}

TEST(FlatMap, HoverThrustIncludesTheGroundEffect) {
  const auto& v = paperVehicle();
  const FlatMap map(v);
  for (double h : {0.072, 0.12, 0.18, 0.5, 2.0}) {
    const FlatState s = map.evaluate(hoverAt(h, 0.3), h);
    ASSERT_TRUE(s.ok());
    // STYLE.md, closed form: at hover T = m·g/(1 + F_G(h)).
    EXPECT_NEAR(s.thrust_N, v.params().mass_kg * kGravity / (1.0 + v.groundEffect().thrustRatio(h)), 1e-12);
    EXPECT_MATRIX_NEAR(s.w_B, Eigen::Vector3d::Zero(), 1e-15);
    EXPECT_MATRIX_NEAR(s.w_dot_B, Eigen::Vector3d::Zero(), 1e-15);
    EXPECT_MATRIX_NEAR(s.tau_B, Eigen::Vector3d::Zero(), 1e-15);
    EXPECT_MATRIX_NEAR(s.R_WB, Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix(), 1e-15);
    EXPECT_MATRIX_NEAR(s.rotor_speeds_rpm, Eigen::Vector4d::Constant(v.hoverSpeedRpm(h)), 1e-6);
    EXPECT_TRUE(s.rotor_speeds_feasible);
  }
}

TEST(FlatMap, HoverWithYawRateSpinsAboutBodyZ) {
  const FlatMap map(paperVehicle());
  const FlatState s = map.evaluate(hoverAt(1.0, -1.2, 0.7), 1.0);
  ASSERT_TRUE(s.ok());
  EXPECT_MATRIX_NEAR(s.w_B, Eigen::Vector3d(0.0, 0.0, 0.7), 1e-14);
  // A yaw torque appears only with yaw acceleration.
  FlatOutput r = hoverAt(1.0, -1.2, 0.7);
  r.yaw_acc_radps2 = 2.0;
  const FlatState s2 = map.evaluate(r, 1.0);
  EXPECT_MATRIX_NEAR(s2.w_dot_B, Eigen::Vector3d(0.0, 0.0, 2.0), 1e-14);
  EXPECT_NEAR(s2.tau_B.z(), paperVehicle().params().inertia_kgm2.z() * 2.0, 1e-15);
}

TEST(FlatMap, WithoutDragItIsTheClassicMap) {
  // No drag: ω_x = −y_Bᵀj/c and ω_y = x_Bᵀj/c (Mellinger & Kumar 2011; Faessler et al. 2018).
  auto p = geaware_test::paperParams();
  for (auto& d : p.drag.d_x_N_per_mps) d = 0.0;
  for (auto& d : p.drag.d_y_N_per_mps) d = 0.0;
  const geaware::model::VehicleModel v(p);
  const FlatMap map(v);
  const auto traj = fastLemniscate();
  for (double t = 0.5; t < traj.duration(); t += 0.77) {
    const FlatOutput r = traj.sample(t);
    const FlatState s = map.evaluate(r, r.p_W.z());
    ASSERT_TRUE(s.ok());
    const double c = s.collective_acc_mps2;
    EXPECT_NEAR(s.w_B.x(), -s.R_WB.col(1).dot(r.j_W) / c, 1e-12) << "t = " << t;
    EXPECT_NEAR(s.w_B.y(), s.R_WB.col(0).dot(r.j_W) / c, 1e-12) << "t = " << t;
    EXPECT_NEAR(c, (r.a_W + Eigen::Vector3d(0, 0, kGravity)).norm(), 1e-12);
  }
}

TEST(FlatMap, GroundEffectOffIsThePlainDragAwareMap) {
  // Invariant: with every ground-effect term off the map equals the all-terms map of a vehicle
  // without ground effect (g2 = 0, M_G = 0) whose drag is the high-altitude value everywhere.
  auto p = geaware_test::paperParams();
  p.additional_thrust.g2_m2 = 0.0;
  p.leveling_torque.scale_m4 = 0.0;
  const double dx = p.drag.d_x_N_per_mps.back();
  const double dy = p.drag.d_y_N_per_mps.back();
  p.drag = {{1.0}, {dx}, {dy}};
  const geaware::model::VehicleModel plain(p);
  const FlatMap off(paperVehicle(), GroundEffectTerms::none());
  const FlatMap reference(plain, GroundEffectTerms::all());
  const auto traj = fastLemniscate();
  for (double t = 0.0; t < traj.duration(); t += 0.31) {
    const FlatOutput r = traj.sample(t);
    for (double h : {0.1, 0.18, 3.0}) {
      const FlatState a = off.evaluate(r, h);
      const FlatState b = reference.evaluate(r, h);
      ASSERT_TRUE(a.ok() && b.ok());
      EXPECT_NEAR(a.thrust_N, b.thrust_N, 1e-12);
      EXPECT_MATRIX_NEAR(a.R_WB, b.R_WB, 1e-15);
      EXPECT_MATRIX_NEAR(a.w_B, b.w_B, 1e-15);
      EXPECT_MATRIX_NEAR(a.w_dot_B, b.w_dot_B, 1e-15);
      EXPECT_MATRIX_NEAR(a.tau_B, b.tau_B, 1e-15);
    }
  }
}

TEST(FlatMap, EachGroundEffectTermActsOnItsOutputOnly) {
  const auto traj = fastLemniscate();
  const FlatOutput r = traj.sample(5.0);
  const double h = 0.18;
  const FlatState none = FlatMap(paperVehicle(), GroundEffectTerms::none()).evaluate(r, h);
  const FlatState thrust = FlatMap(paperVehicle(), {true, false, false}).evaluate(r, h);
  const FlatState drag = FlatMap(paperVehicle(), {false, true, false}).evaluate(r, h);
  const FlatState inertia = FlatMap(paperVehicle(), {false, false, true}).evaluate(r, h);
  // F_G only scales the thrust.
  EXPECT_NEAR(thrust.thrust_N * (1.0 + paperVehicle().groundEffect().thrustRatio(h)), none.thrust_N, 1e-12);
  EXPECT_MATRIX_NEAR(thrust.w_B, none.w_B, 0.0);
  // D(h) changes the attitude and rates (less drag to lean against near the ground).
  EXPECT_GT((drag.R_WB - none.R_WB).norm(), 1e-4);
  // J'(h) changes only the torque, in roll and pitch.
  EXPECT_MATRIX_NEAR(inertia.w_dot_B, none.w_dot_B, 0.0);
  EXPECT_GT((inertia.tau_B - none.tau_B).head<2>().norm(), 1e-6);
}

TEST(FlatMap, BodyRatesMatchFiniteDifferencesOfTheAttitude) {
  const FlatMap map(paperVehicle());
  const auto traj = fastLemniscate();
  const double dt = 1e-5;
  // Includes times inside both ramps (0–2 s and the last 2 s) and the cruise.
  for (double t = 0.3; t < traj.duration() - 0.3; t += 0.53) {
    const auto at = [&](double ti) { return map.evaluate(traj.sample(ti), 0.18); };
    const FlatState s = at(t);
    const FlatState sp = at(t + dt);
    const FlatState sm = at(t - dt);
    ASSERT_TRUE(s.ok() && sp.ok() && sm.ok());
    // ω = vee(Rᵀ·Ṙ); central difference error ~dt²·|R'''| ≈ 1e-9, rounding ~1e-11.
    const Eigen::Matrix3d W = s.R_WB.transpose() * (sp.R_WB - sm.R_WB) / (2.0 * dt);
    const Eigen::Vector3d w_fd(0.5 * (W(2, 1) - W(1, 2)), 0.5 * (W(0, 2) - W(2, 0)), 0.5 * (W(1, 0) - W(0, 1)));
    EXPECT_MATRIX_NEAR(s.w_B, w_fd, 1e-7) << "t = " << t;
    const Eigen::Vector3d wdot_fd = (sp.w_B - sm.w_B) / (2.0 * dt);
    EXPECT_MATRIX_NEAR(s.w_dot_B, wdot_fd, 1e-6) << "t = " << t;
  }
}

TEST(FlatMap, RotorSpeedsReproduceThrustAndTorque) {
  const auto& v = paperVehicle();
  const FlatMap map(v);
  const auto traj = fastLemniscate();
  for (double t = 0.0; t < traj.duration(); t += 0.9) {
    const FlatState s = map.evaluate(traj.sample(t), 0.18);
    ASSERT_TRUE(s.ok());
    EXPECT_TRUE(s.rotor_speeds_feasible);
    const Eigen::Vector4d n_sq = s.rotor_speeds_rpm.cwiseAbs2();
    const Eigen::Vector4d w = v.mixer().wrench(n_sq);
    EXPECT_NEAR(w(0), s.thrust_N, 1e-9);
    EXPECT_MATRIX_NEAR(Eigen::Vector3d(w.tail<3>()), s.tau_B, 1e-10);
    EXPECT_NEAR(Eigen::Quaterniond(s.R_WB).angularDistance(s.q_WB), 0.0, 1e-12);
  }
}

/// Flies `traj` open loop through the model the map inverts; returns the largest position
/// error [m]. RK4 at 1 kHz with the map evaluated at the sub-steps (a continuous input).
double openLoopError(const geaware::traj::Trajectory& traj, GroundEffectTerms terms, double t_end) {
  const auto& v = paperVehicle();
  const FlatMap map(v, terms);
  const geaware_test::FlatModelPlant plant(v, terms);
  const auto input = [&](double t) {
    const FlatOutput r = traj.sample(t);
    const FlatState s = map.evaluate(r, r.p_W.z());
    return geaware_test::PlantInput{s.thrust_N, s.tau_B};
  };
  const FlatOutput r0 = traj.sample(0.0);
  const FlatState s0 = map.evaluate(r0, r0.p_W.z());
  geaware_test::PlantState x;
  x.p = r0.p_W;
  x.v = r0.v_W;
  x.q = s0.q_WB;
  x.w = s0.w_B;
  const double dt = 1e-3;
  double worst = 0.0;
  const int steps = static_cast<int>(std::lround(t_end / dt));
  for (int k = 0; k < steps; ++k) {
    plant.step(x, k * dt, dt, input);
    worst = std::max(worst, (x.p - traj.sample((k + 1) * dt).p_W).norm());
  }
  return worst;
}

TEST(FlatMap, OpenLoopThroughTheModelReproducesTheFastLemniscate) {
  const auto traj = fastLemniscate();
  // Issue requirement: < 1 mm over 10 s of the 3 m/s lemniscate, with and without the
  // ground-effect terms.
  EXPECT_LT(openLoopError(traj, GroundEffectTerms::all(), 10.0), 1e-3);
  EXPECT_LT(openLoopError(traj, GroundEffectTerms::none(), 10.0), 1e-3);
}

TEST(FlatMap, OpenLoopReproducesTheHoverDescentThroughVaryingGroundEffect) {
  geaware::traj::HoverDescentParams p;
  p.from_height_m = 0.6;
  p.to_height_m = 0.1;
  p.descent_rate_mps = 0.1;
  const geaware::traj::HoverDescent traj(p);
  // F_G and J' change by 25 % and 10 % along the way; the thrust tracks them exactly.
  EXPECT_LT(openLoopError(traj, GroundEffectTerms::all(), traj.duration()), 1e-3);
}

TEST(FlatMap, MismatchedGroundEffectDoesNotReproduceTheTrajectory) {
  // The oracle has teeth: the map without F_G flying the plant with F_G climbs away.
  const auto traj = fastLemniscate();
  const auto& v = paperVehicle();
  const FlatMap map(v, GroundEffectTerms::none());
  const geaware_test::FlatModelPlant plant(v, GroundEffectTerms::all());
  const auto input = [&](double t) {
    const FlatState s = map.evaluate(traj.sample(t), 0.18);
    return geaware_test::PlantInput{s.thrust_N, s.tau_B};
  };
  geaware_test::PlantState x;
  x.p = traj.sample(0.0).p_W;
  for (int k = 0; k < 1000; ++k) plant.step(x, k * 1e-3, 1e-3, input);
  EXPECT_GT((x.p - traj.sample(1.0).p_W).norm(), 0.1);
}

TEST(FlatMap, RejectsNonFiniteInputAndDegenerateStates) {
  const FlatMap map(paperVehicle());
  FlatOutput r = hoverAt(1.0);
  r.a_W.x() = std::nan("");
  EXPECT_EQ(map.evaluate(r, 1.0).status, FlatMapStatus::kNonFiniteInput);
  EXPECT_EQ(map.evaluate(hoverAt(1.0), std::numeric_limits<double>::infinity()).status,
            FlatMapStatus::kNonFiniteInput);
  // Free fall: no thrust direction.
  r = hoverAt(1.0);
  r.a_W = Eigen::Vector3d(0, 0, -kGravity);
  EXPECT_EQ(map.evaluate(r, 1.0).status, FlatMapStatus::kNoThrust);
  // Thrust direction along the heading's y axis: body x undefined.
  r = hoverAt(1.0);
  r.a_W = Eigen::Vector3d(0, 5.0, -kGravity);
  EXPECT_EQ(map.evaluate(r, 1.0).status, FlatMapStatus::kYawSingular);
  EXPECT_STREQ(geaware::flatness::toString(FlatMapStatus::kYawSingular),
               "yaw singular (heading parallel to thrust direction)");
}

TEST(FlatMap, FlagsRotorSpeedsBeyondTheThrottleCurve) {
  const FlatMap map(paperVehicle());
  FlatOutput r = hoverAt(2.0);
  r.a_W.z() = 3.0 * kGravity;  // 4·m·g ≈ 66.5 N > 4·k_T·n_max² ≈ 62 N
  const FlatState s = map.evaluate(r, 2.0);
  ASSERT_TRUE(s.ok());
  EXPECT_FALSE(s.rotor_speeds_feasible);
  r.a_W.z() = 1.0;
  EXPECT_TRUE(map.evaluate(r, 2.0).rotor_speeds_feasible);
}

}  // namespace

namespace {

// With a forward fade, the thrust of a steady level run is m·c/(1 + fade·F_G(h)); without one,
// the map's numbers are bit for bit the paper's.
TEST(FlatMap, ForwardFadeWeakensTheCushionWithSpeed) {
  auto p = geaware_test::paperParams();
  p.forward_fade_induced_velocity_mps = 8.26;
  const geaware::model::VehicleModel fading(p);
  const FlatMap faded(fading);
  const FlatMap plain(paperVehicle());
  FlatOutput run = hoverAt(0.15);
  run.v_W = Eigen::Vector3d(4.0, 3.0, 0.0);  // 5 m/s, level, steady
  const double h = 0.15;
  const FlatState a = faded.evaluate(run, h);
  const FlatState b = plain.evaluate(run, h);
  ASSERT_TRUE(a.ok() && b.ok());
  const double fade = 8.26 * 8.26 / (8.26 * 8.26 + 25.0);
  const double F = fading.groundEffect().thrustRatio(h);
  EXPECT_NEAR(a.thrust_N, p.mass_kg * a.collective_acc_mps2 / (1.0 + fade * F), 1e-12);
  EXPECT_NEAR(b.thrust_N, p.mass_kg * b.collective_acc_mps2 / (1.0 + F), 1e-12);
  EXPECT_GT(a.thrust_N, b.thrust_N);  // less cushion: more thrust to hold the height
  // At rest the fade is 1: the same thrust bit for bit.
  EXPECT_EQ(faded.evaluate(hoverAt(h), h).thrust_N, plain.evaluate(hoverAt(h), h).thrust_N);
}

}  // namespace

namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// evaluateRates() is evaluate()'s attitude, thrust, rates and angular acceleration, bit for bit,
// along a yawed, fast lemniscate at 0.18 m and in each degenerate case (same status); the
// fields it leaves out keep their defaults.
TEST(FlatMap, RatesAreTheFullMapsBitForBit) {
  const FlatMap map(paperVehicle());
  const auto lem = fastLemniscate();
  for (int i = 0; i <= 200; ++i) {
    const FlatOutput r = lem.sample(lem.duration() * i / 200.0);
    const FlatState full = map.evaluate(r, 0.18);
    const FlatState rates = map.evaluateRates(r, 0.18, std::cos(r.yaw_rad), std::sin(r.yaw_rad));
    ASSERT_TRUE(full.ok());
    ASSERT_EQ(rates.status, full.status);
    EXPECT_TRUE(sameBits(rates.thrust_N, full.thrust_N)) << i;
    EXPECT_TRUE(sameBits(rates.collective_acc_mps2, full.collective_acc_mps2)) << i;
    for (int k = 0; k < 9; ++k) EXPECT_TRUE(sameBits(rates.R_WB(k), full.R_WB(k))) << i << " R " << k;
    for (int k = 0; k < 3; ++k) {
      EXPECT_TRUE(sameBits(rates.w_B(k), full.w_B(k))) << i << " w " << k;
      EXPECT_TRUE(sameBits(rates.w_dot_B(k), full.w_dot_B(k))) << i << " w_dot " << k;
    }
    EXPECT_EQ(rates.tau_B, Eigen::Vector3d::Zero());
    EXPECT_EQ(rates.rotor_speeds_rpm, Eigen::Vector4d::Zero());
  }
  FlatOutput free_fall = hoverAt(1.0);
  free_fall.a_W = Eigen::Vector3d(0, 0, -kGravity);
  FlatOutput nan = hoverAt(1.0);
  nan.j_W.y() = std::nan("");
  for (const FlatOutput& r : {free_fall, nan}) {
    EXPECT_EQ(map.evaluateRates(r, 1.0, 1.0, 0.0).status, map.evaluate(r, 1.0).status);
  }
}

}  // namespace
