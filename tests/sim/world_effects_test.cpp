// SPDX-License-Identifier: BSD-3-Clause
// The as-built world's truth-side effects (docs/world.md), each against a closed form: the k_I
// spread, tilted thrust axes, the ESC/link dead time, the in-flight cushion scale, translational
// lift and airframe drag. Each default reproduces the ideal world exactly.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "geaware/model/units.hpp"
#include "geaware/sim/plant.hpp"
#include "geaware/sim/rigs.hpp"
#include "geaware/sim/terrains.hpp"
#include "geaware/sim/truth_params.hpp"
#include "geaware_test/eigen_matchers.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace geaware::sim {
namespace {

constexpr double kNoGround = std::numeric_limits<double>::infinity();
constexpr double kRpm = 10000.0;

TruthParams paperTruth() { return fromNominal(geaware_test::paperParams()); }

std::array<double, 4> distances(double h) { return {h, h, h, h}; }

RotorAeroOutput still(const RotorAerodynamics& a, const std::array<double, 4>& n, double h) {
  return a.compute(n, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(),
                   Eigen::Vector3d::Zero(), a.groundFactors(distances(h)));
}

// --- 1. k_I spread and thrust-axis misalignment ------------------------------------------------

TEST(WorldEffects, TorqueMultiplierScalesOnlyKI) {
  TruthParams p = paperTruth();
  p.thrust_multiplier = {1.0, 1.02, 0.98, 1.0};
  p.torque_multiplier = {1.04, 1.0, 0.97, 1.01};
  ASSERT_TRUE(p.validate().empty());
  const RotorGeometry g = p.rotorGeometry();
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(g.k_T_N_per_rpm2[i], p.k_T_N_per_rpm2 * p.thrust_multiplier[i]);
    EXPECT_EQ(g.k_I_Nm_per_rpm2[i], p.k_I_Nm_per_rpm2 * p.torque_multiplier[i]);
  }
  // Free air, equal speeds: the yaw torque is Σ spin_i·k_I,i·n² alone.
  const RotorAerodynamics a(g, p.aero);
  const RotorAeroOutput o = still(a, {kRpm, kRpm, kRpm, kRpm}, kNoGround);
  double yaw = 0.0;
  for (std::size_t i = 0; i < 4; ++i) yaw += g.spin[i] * g.k_I_Nm_per_rpm2[i] * kRpm * kRpm;
  EXPECT_NEAR(o.wrench.torque_B.z(), yaw, 1e-15);
  p.torque_multiplier[2] = 1.6;
  ASSERT_EQ(p.validate().size(), 1u);
  EXPECT_EQ(p.validate()[0].field, "torque_multiplier[2]");
}

TEST(WorldEffects, PerturbedMovesKIWithKTByTheSameFactor) {
  MismatchSpec spec;
  spec.thrust_spread_rel = 0.05;
  const TruthParams p = perturbed(paperTruth(), spec, 7);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NE(p.thrust_multiplier[i], 1.0);
    EXPECT_EQ(p.torque_multiplier[i], p.thrust_multiplier[i]);
  }
}

TEST(WorldEffects, TiltedAxisIsRyRxZ) {
  EXPECT_EQ(tiltedAxis(Eigen::Vector2d::Zero()), Eigen::Vector3d::UnitZ());
  const double tx = 0.01;
  const double ty = -0.017;
  const Eigen::Vector3d expected =
      (Eigen::AngleAxisd(ty, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(tx, Eigen::Vector3d::UnitX()) * Eigen::Vector3d::UnitZ());
  EXPECT_MATRIX_NEAR(tiltedAxis({tx, ty}), expected, 1e-16);
  EXPECT_NEAR(tiltedAxis({tx, ty}).norm(), 1.0, 1e-15);
}

TEST(WorldEffects, ATiltedRotorPushesSidewaysAndTwists) {
  // Rotor 1 (index 0) tilted by θ about body y: its thrust T = k_T·n² acts along
  // (sin θ, 0, cos θ) at r_0, its reaction torque Q = spin·k_I·n² along the same axis.
  TruthParams p = paperTruth();
  const double theta = 1.0 * model::kDegToRad;
  p.thrust_axis_tilt_rad[0] = Eigen::Vector2d(0.0, theta);
  ASSERT_TRUE(p.validate().empty());
  const RotorGeometry g = p.rotorGeometry();
  const RotorAerodynamics tilted(g, p.aero);
  const RotorAerodynamics straight(paperTruth().rotorGeometry(), p.aero);
  const std::array<double, 4> n{kRpm, kRpm, kRpm, kRpm};
  const Wrench w = still(tilted, n, kNoGround).wrench;
  const Wrench w0 = still(straight, n, kNoGround).wrench;
  const double T = g.k_T_N_per_rpm2[0] * kRpm * kRpm;
  const double Q = g.spin[0] * g.k_I_Nm_per_rpm2[0] * kRpm * kRpm;
  const Eigen::Vector3d r = g.position_B[0];
  const Eigen::Vector3d a(std::sin(theta), 0.0, std::cos(theta));
  // The change of the wrench is that of rotor 1's force and reaction torque turning.
  const Eigen::Vector3d dF = T * (a - Eigen::Vector3d::UnitZ());
  const Eigen::Vector3d dTau = r.cross(dF) + Q * (a - Eigen::Vector3d::UnitZ());
  EXPECT_NEAR(w.force_B.x(), T * std::sin(theta), 1e-12);
  EXPECT_MATRIX_NEAR(w.force_B - w0.force_B, dF, 1e-12);
  EXPECT_MATRIX_NEAR(w.torque_B - w0.torque_B, dTau, 1e-13);
}

TEST(WorldEffects, AllAxesTiltedAlikeGiveTheLateralAccelerationGTanTheta) {
  // Every rotor tilted by θ about body y, vehicle held level by nothing but symmetry: the net
  // force is (sin θ, 0, cos θ)·ΣT, no torque. With ΣT·cos θ = m·g the vehicle accelerates
  // along x at g·tan θ (the steady position error a real tilt causes under a position loop).
  TruthParams p = paperTruth();
  const double theta = 0.75 * model::kDegToRad;
  for (auto& t : p.thrust_axis_tilt_rad) t = Eigen::Vector2d(0.0, theta);
  p.battery.enabled = false;
  p.motor.J_R_kgm2 = 0.0;
  p.aero.drag_x_N_per_mps_per_rpm = 0.0;  // the rotor drag would brake the sideways drift
  p.aero.drag_y_N_per_mps_per_rpm = 0.0;
  const double n = std::sqrt(p.mass_kg * p.gravity_mps2 /
                             (4.0 * p.k_T_N_per_rpm2 * std::cos(theta)));
  PlantState x0;
  x0.p_W = Eigen::Vector3d(0.0, 0.0, 10.0);
  x0.n_rpm = {n, n, n, n};
  Plant plant(p, nullptr, {}, x0);
  const double t = plant.throttleForSteadySpeed(n);
  for (int k = 0; k < 100; ++k) ASSERT_FALSE(plant.step({t, t, t, t}).crash);
  EXPECT_NEAR(plant.state().a_W.x(), p.gravity_mps2 * std::tan(theta), 1e-6);
  EXPECT_NEAR(plant.state().a_W.z(), 0.0, 1e-6);
  EXPECT_MATRIX_NEAR(plant.state().w_B, Eigen::Vector3d::Zero(), 1e-9);
}

TEST(WorldEffects, TiltValidation) {
  TruthParams p = paperTruth();
  p.thrust_axis_tilt_rad[3] = Eigen::Vector2d(0.5, 0.0);
  ASSERT_EQ(p.validate().size(), 1u);
  EXPECT_EQ(p.validate()[0].field, "thrust_axis_tilt_rad[3].x");
  RotorGeometry g = paperTruth().rotorGeometry();
  g.thrust_axis_B[1] = Eigen::Vector3d(0.0, 0.0, 2.0);
  EXPECT_THROW(RotorAerodynamics(g, RotorAeroParams{}), std::invalid_argument);
}

// --- 2. ESC/link dead time ----------------------------------------------------------------------

TEST(WorldEffects, ThrottleDelayHoldsACommandExactlyKSteps) {
  ThrottleDelay d(0.005, 0.001);
  const std::array<double, 4> lo{0.3, 0.3, 0.3, 0.3};
  const std::array<double, 4> hi{0.6, 0.6, 0.6, 0.6};
  for (int k = 0; k < 20; ++k) {
    const double t = k * 0.001;
    const auto& out = d.apply(t, k < 10 ? lo : hi);
    EXPECT_EQ(out, k < 15 ? lo : hi) << "step " << k;
  }
  EXPECT_EQ(d.overflowed(), 0);
}

TEST(WorldEffects, DeadTimeDelaysTheMotorsByExactlyKSamples) {
  // A plant with a 7 ms dead time fed u[k] flies bit for bit like one without, fed u[k − 7]
  // (u[0] before): at 1 kHz the dead time is exactly 7 samples. With 6 ms it is not.
  TruthParams p = paperTruth();
  PlantConfig cfg;
  cfg.ground_strikes = false;
  PlantState x0;
  x0.p_W = Eigen::Vector3d(0.0, 0.0, 50.0);
  x0.n_rpm = {9000.0, 9000.0, 9000.0, 9000.0};
  std::vector<std::array<double, 4>> u;
  for (int k = 0; k < 60; ++k) {
    const double t = k < 20 ? 0.3 : 0.5 + 0.004 * k;  // a step, then a ramp
    u.push_back({t, t + 0.01, t - 0.01, t});
  }
  const auto fly = [&](double dead_time_s, int shift) {
    TruthParams q = p;
    q.motor.dead_time_s = dead_time_s;
    Plant plant(q, nullptr, cfg, x0);
    std::vector<PlantState> out;
    for (int k = 0; k < 60; ++k) {
      (void)plant.step(u[static_cast<std::size_t>(std::max(0, k - shift))]);
      out.push_back(plant.state());
    }
    return out;
  };
  const auto by_hand = fly(0.0, 7);
  const auto late = fly(0.007, 0);
  const auto sooner = fly(0.006, 0);
  for (std::size_t k = 0; k < u.size(); ++k) {
    EXPECT_EQ(late[k].n_rpm, by_hand[k].n_rpm) << k;
    EXPECT_EQ(late[k].p_W, by_hand[k].p_W) << k;
  }
  EXPECT_NE(sooner[30].n_rpm, by_hand[30].n_rpm);
  p.motor.dead_time_s = -0.001;
  ASSERT_EQ(p.validate().size(), 1u);
  EXPECT_EQ(p.validate()[0].field, "motor.dead_time_s");
}

// --- 3. In-flight cushion -----------------------------------------------------------------------

TEST(WorldEffects, CushionScaleActsInFlightOnly) {
  RotorAeroParams scaled;
  scaled.in_flight_cushion_scale = 0.45;
  const RotorGeometry g = paperTruth().rotorGeometry();
  const RotorAerodynamics a(g, scaled);
  const RotorAerodynamics a1(g, RotorAeroParams{});
  const auto d = std::array<double, 4>{0.10, 0.11, 0.12, 0.09};
  const RotorGroundFactors rig = a.groundFactors(d);
  const RotorGroundFactors flight = a.flightFactors(d);
  EXPECT_EQ(rig.phi, a1.groundFactors(d).phi);  // the rigs see the calibrated cushion
  EXPECT_EQ(a1.flightFactors(d).phi, rig.phi);  // scale 1: identical
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_GT(rig.phi[i], 0.1);
    EXPECT_EQ(flight.phi[i], 0.45 * rig.phi[i]);
    EXPECT_EQ(flight.drag_scale_x[i], rig.drag_scale_x[i]);
  }
  // The platform's wrench does not change with the scale.
  const PlatformParams quiet = [] {
    PlatformParams p;
    p.force_noise_N = 0.0;
    p.torque_noise_Nm = 0.0;
    return p;
  }();
  const ForceTorquePlatform rig_s(g, scaled, quiet);
  const ForceTorquePlatform rig_1(g, RotorAeroParams{}, quiet);
  const std::array<double, 4> n{12000.0, 12000.0, 12000.0, 12000.0};
  EXPECT_EQ(rig_s.wrench(0.1, 5.0, n).wrench.force_B, rig_1.wrench(0.1, 5.0, n).wrench.force_B);
  EXPECT_EQ(rig_s.wrench(0.1, 5.0, n).wrench.torque_B, rig_1.wrench(0.1, 5.0, n).wrench.torque_B);
}

TEST(WorldEffects, RigCalibrationStillPassesWithAnyCushionScale) {
  RotorAeroParams scaled;
  scaled.in_flight_cushion_scale = 0.45;
  EXPECT_TRUE(calibrate(geaware_test::paperParams(), scaled).allPass());
}

TEST(WorldEffects, ThePlantSeesTheScaledCushion) {
  // Level, at rest at 0.1 m, equal speeds: each rotor's gain is 1 + s·φ_i (fade 1 at rest,
  // own and shared parts equal).
  TruthParams p = paperTruth();
  p.aero.in_flight_cushion_scale = 0.45;
  const RotorAerodynamics rig(p.rotorGeometry(), p.aero);
  PlantState x0;
  x0.p_W = Eigen::Vector3d(0.0, 0.0, 0.1);
  x0.n_rpm = {kRpm, kRpm, kRpm, kRpm};
  PlantConfig cfg;
  cfg.ground_strikes = false;
  Plant plant(p, std::make_shared<FlatGround>(0.0), cfg, x0);
  (void)plant.step({0.0, 0.0, 0.0, 0.0});
  const auto phi = rig.groundFactors(distances(0.1)).phi;
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_NEAR(plant.lastAero().gain[i] - 1.0, 0.45 * phi[i], 1e-12);
  p.aero.in_flight_cushion_scale = -0.1;  // the truth's validation names the aerodynamics' fields
  ASSERT_EQ(p.validate().size(), 1u);
  EXPECT_EQ(p.validate()[0].field, "aero.in_flight_cushion_scale");
}

// --- 4. Translational lift and airframe drag ------------------------------------------------------

TEST(WorldEffects, TranslationalLiftIsOnePlusCVSquaredUpToItsCap) {
  RotorAeroParams lift;
  lift.translational_lift_per_mps2 = 0.002;
  lift.translational_lift_max = 0.05;
  const RotorGeometry g = paperTruth().rotorGeometry();
  const RotorAerodynamics a(g, lift);
  const RotorAerodynamics a0(g, RotorAeroParams{});
  const std::array<double, 4> n{kRpm, kRpm, kRpm, kRpm};
  const double t_free = 4.0 * g.k_T_N_per_rpm2[0] * kRpm * kRpm;
  const auto thrust = [&](const RotorAerodynamics& x, double v) {
    return x
        .compute(n, Eigen::Matrix3d::Identity(), Eigen::Vector3d(v, 0.0, 0.0),
                 Eigen::Vector3d::Zero(), x.flightFactors(distances(kNoGround)))
        .wrench.force_B.z();
  };
  EXPECT_NEAR(thrust(a, 0.0), t_free, 1e-12);
  EXPECT_NEAR(thrust(a, 3.0), t_free * (1.0 + 0.002 * 9.0), 1e-12);
  EXPECT_NEAR(thrust(a, 4.0), t_free * 1.032, 1e-12);
  EXPECT_NEAR(thrust(a, 10.0), t_free * 1.05, 1e-12);  // capped
  EXPECT_EQ(thrust(a0, 4.0), thrust(a0, 0.0));        // default: none
  EXPECT_DOUBLE_EQ(a.translationalLiftGain(4.0), 1.032);
}

TEST(WorldEffects, AirframeDragIsHalfRhoCdAVSquaredAgainstTheAirspeed) {
  // Rotors stopped (no rotor drag, no thrust), gravity off: the only force is the airframe's.
  TruthParams p = paperTruth();
  p.aero.airframe_drag_area_m2 = 0.02;
  p.motor.max_speed_rpm = 1e-3;  // the ESC would idle the rotors at ≈ 3,200 rpm
  PlantConfig cfg;
  cfg.gravity = false;
  cfg.ground_strikes = false;
  PlantState x0;
  x0.v_W = Eigen::Vector3d(4.0, 0.0, 0.0);
  x0.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  Plant plant(p, nullptr, cfg, x0);
  bool named = false;
  for (const auto& c : plant.contributions()) named |= std::string(c->name()) == "airframe_drag";
  EXPECT_TRUE(named);
  plant.setWind_W(Eigen::Vector3d(0.0, 1.0, 0.0));  // airspeed (4, −1, 0)
  (void)plant.step({0.0, 0.0, 0.0, 0.0});
  const Eigen::Vector3d v_air = plant.state().v_W - Eigen::Vector3d(0.0, 1.0, 0.0);
  const Eigen::Vector3d expected = -0.5 * 1.225 * 0.02 * v_air.norm() * v_air / p.mass_kg;
  EXPECT_MATRIX_NEAR(plant.state().a_W, expected, 1e-6);
  EXPECT_NEAR(expected.norm(), 0.5 * 1.225 * 0.02 * 17.0 / p.mass_kg, 1e-4);
  // Default: no such contribution.
  p.aero.airframe_drag_area_m2 = 0.0;
  Plant ideal(p, nullptr, cfg, x0);
  for (const auto& c : ideal.contributions()) EXPECT_STRNE(c->name(), "airframe_drag");
}

}  // namespace
}  // namespace geaware::sim
