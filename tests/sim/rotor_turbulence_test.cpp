// SPDX-License-Identifier: BSD-3-Clause
// The per-rotor near-ground turbulence (sim::RotorTurbulence, docs/world.md §7): the law's
// closed forms (σ_T/T = κ·φ_i(h)), the per-rotor → body mapping through the mixer geometry,
// the statistics of independent and correlated rotors, determinism.

#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include <gtest/gtest.h>

#include "geaware/sim/plant.hpp"
#include "geaware/sim/rotor_turbulence.hpp"
#include "geaware/sim/terrains.hpp"
#include "geaware/sim/truth_params.hpp"
#include "geaware_test/eigen_matchers.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace geaware::sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
std::array<double, 4> all(double v) { return {v, v, v, v}; }

TruthParams paperTruth() { return fromNominal(geaware_test::paperParams()); }

GroundTurbulenceParams perRotor(double kappa = 0.25, double rho = 0.0) {
  GroundTurbulenceParams p;
  p.per_rotor = true;
  p.fluctuation_per_increment = kappa;
  p.rotor_correlation = rho;
  return p;
}

TEST(RotorTurbulence, RelativeStdIsKappaTimesTheInFlightIncrementOfEachRotor) {
  TruthParams truth = paperTruth();
  truth.aero.in_flight_cushion_scale = 0.4;
  const RotorTurbulence turb(perRotor(0.25), truth, 1);
  const RotorAerodynamics aero(truth.rotorGeometry(), truth.aero);
  double last = kInf;
  for (double h : {0.08, 0.1, 0.12, 0.18, 0.3, 0.6, 1.0, 1.5}) {
    const std::array<double, 4> s = turb.relativeStd(all(h));
    const RotorGroundFactors f = aero.flightFactors(all(h));
    for (std::size_t i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ(s[i], 0.25 * f.phi[i]) << h;
    EXPECT_LT(s[0], last) << "grows as the rotor nears the ground, h = " << h;
    EXPECT_GT(s[0], 0.0) << h;
    last = s[0];
  }
  // The in-flight scale enters once: 0.4 of the rig's φ.
  EXPECT_NEAR(turb.relativeStd(all(0.12))[0], 0.25 * 0.4 * aero.groundFactors(all(0.12)).phi[0], 1e-15);
  // The magnitudes of docs/world.md §7 (level, 0.12 m): the truth's rig φ ≈ 0.259, so
  // σ_T/T = 0.25 · 0.4 · 0.259 = 2.59 %; at 0.3 m 0.61 %, at 1 m 0.06 %.
  EXPECT_NEAR(turb.relativeStd(all(0.12))[0], 0.0259, 0.0001);
  EXPECT_NEAR(turb.relativeStd(all(0.3))[0], 0.0061, 0.0001);
  EXPECT_NEAR(turb.relativeStd(all(1.0))[0], 0.0006, 0.0001);
  // No surface: nothing.
  EXPECT_EQ(turb.relativeStd(all(kInf)), all(0.0));
  // Each rotor its own distance: a table edge under rotors 1 and 2 only.
  const std::array<double, 4> edge = turb.relativeStd({0.1, 0.1, kInf, kInf});
  EXPECT_GT(edge[0], 0.0);
  EXPECT_EQ(edge[2], 0.0);
  EXPECT_EQ(edge[3], 0.0);
}

TEST(RotorFluctuationWrench, ClosedFormOfTheMixerGeometry) {
  const RotorGeometry g = paperTruth().rotorGeometry();
  // One rotor alone: a vertical force δT and the torque r × δT·z plus its reaction torque.
  for (std::size_t i = 0; i < 4; ++i) {
    std::array<double, 4> dT{};
    dT[i] = 0.2;
    const Wrench w = rotorFluctuationWrench(g, dT);
    const Eigen::Vector3d r = g.position_B[i];
    const double q = g.spin[i] * g.k_I_Nm_per_rpm2[i] / g.k_T_N_per_rpm2[i] * 0.2;
    EXPECT_MATRIX_NEAR(w.force_B, Eigen::Vector3d(0, 0, 0.2), 1e-15);
    EXPECT_MATRIX_NEAR(w.torque_B, Eigen::Vector3d(0.2 * r.y(), -0.2 * r.x(), q), 1e-15);
  }
  // Equal fluctuations on all four rotors of a centred vehicle: force only, no torque.
  const Wrench eq = rotorFluctuationWrench(g, all(0.3));
  EXPECT_MATRIX_NEAR(eq.force_B, Eigen::Vector3d(0, 0, 1.2), 1e-14);
  EXPECT_MATRIX_NEAR(eq.torque_B, Eigen::Vector3d::Zero(), 1e-14);
}

TEST(RotorTurbulence, FullyCorrelatedEqualRotorsGiveNoTorque) {
  const TruthParams truth = paperTruth();  // centred CoM, level axes, equal k_T, k_I
  RotorTurbulence turb(perRotor(0.25, 1.0), truth, 7);
  ContributionContext ctx;
  ctx.n_rpm = all(10'000.0);
  ctx.surroundings.ground_distance_m = all(0.12);
  double fz2 = 0.0;
  for (int k = 0; k < 2'000; ++k) {
    turb.beginStep(k * 1e-3, 1e-3, PlantState{});
    const std::array<double, 4> x = turb.unitFluctuations();
    EXPECT_EQ(x[0], x[3]);
    const Wrench w = turb.wrench(ctx);
    ASSERT_LT(w.torque_B.norm(), 1e-12);
    fz2 += w.force_B.z() * w.force_B.z();
  }
  EXPECT_GT(fz2, 0.0);
}

TEST(RotorTurbulence, IndependentRotorsTorqueVarianceIsArmSquaredTimesTheSumOfVariances) {
  // 200 s at 1 kHz, τ_c = 20 ms: ≈ 10,000 correlation times; std within 6 %.
  const TruthParams truth = paperTruth();
  RotorTurbulence turb(perRotor(0.25, 0.0), truth, 11);
  const RotorGeometry& g = turb.geometry();
  ContributionContext ctx;
  ctx.n_rpm = {10'000.0, 10'200.0, 9'800.0, 10'100.0};
  ctx.surroundings.ground_distance_m = {0.10, 0.12, 0.14, 0.30};
  const std::array<double, 4> rel = turb.relativeStd(ctx.surroundings.ground_distance_m);
  double var_fz = 0.0, var_tx = 0.0, var_ty = 0.0, var_tz = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    const double s = rel[i] * g.k_T_N_per_rpm2[i] * ctx.n_rpm[i] * ctx.n_rpm[i];
    var_fz += s * s;
    var_tx += g.position_B[i].y() * g.position_B[i].y() * s * s;
    var_ty += g.position_B[i].x() * g.position_B[i].x() * s * s;
    const double q = g.k_I_Nm_per_rpm2[i] / g.k_T_N_per_rpm2[i];
    var_tz += q * q * s * s;
  }
  constexpr int kN = 200'000;
  Eigen::Array4d sum2 = Eigen::Array4d::Zero();
  for (int k = 0; k < kN; ++k) {
    turb.beginStep(k * 1e-3, 1e-3, PlantState{});
    const Wrench w = turb.wrench(ctx);
    sum2 += Eigen::Array4d(w.force_B.z(), w.torque_B.x(), w.torque_B.y(), w.torque_B.z()).square();
  }
  EXPECT_NEAR(std::sqrt(sum2[0] / kN / var_fz), 1.0, 0.06);
  EXPECT_NEAR(std::sqrt(sum2[1] / kN / var_tx), 1.0, 0.06);
  EXPECT_NEAR(std::sqrt(sum2[2] / kN / var_ty), 1.0, 0.06);
  EXPECT_NEAR(std::sqrt(sum2[3] / kN / var_tz), 1.0, 0.06);
  // The paper quad's arm: |y_i| = (b/2)·sin 45° = 0.1237 m, so σ_τx = 0.1237 m · √Σσ².
  EXPECT_NEAR(std::abs(g.position_B[0].y()), 0.35 / 2 * std::sqrt(0.5), 1e-9);
}

TEST(RotorTurbulence, HeldOverTheStepDeterministicPerSeedAndQuietFarAway) {
  const TruthParams truth = paperTruth();
  RotorTurbulence a(perRotor(), truth, 5), b(perRotor(), truth, 5), c(perRotor(), truth, 6);
  ContributionContext ctx;
  ctx.n_rpm = all(10'000.0);
  ctx.surroundings.ground_distance_m = all(0.1);
  int differ = 0;
  for (int k = 0; k < 100; ++k) {
    for (RotorTurbulence* t : {&a, &b, &c}) t->beginStep(k * 1e-3, 1e-3, PlantState{});
    const Wrench wa = a.wrench(ctx);
    EXPECT_EQ(wa.force_B, b.wrench(ctx).force_B);
    differ += wa.force_B != c.wrench(ctx).force_B;
    // The intensities are those of the step's first stage: a later stage at another height
    // sees the same wrench.
    ContributionContext later = ctx;
    later.surroundings.ground_distance_m = all(0.5);
    EXPECT_EQ(a.wrench(later).torque_B, wa.torque_B);
  }
  EXPECT_EQ(differ, 100);
  a.beginStep(0.1, 1e-3, PlantState{});
  ctx.surroundings.ground_distance_m = all(kInf);
  EXPECT_EQ(a.wrench(ctx).force_B, Eigen::Vector3d::Zero());
  EXPECT_STREQ(a.name(), "rotor_turbulence");
}

TEST(RotorTurbulence, InAPlantItShakesTheVehicleNearTheGroundOnly) {
  // Only the turbulence acts (gravity, rotor aerodynamics, motor torques off; the motors spin at
  // half throttle): held 0.12 m above the ground the vehicle spins far faster than at 3 m.
  PlantConfig cfg;
  cfg.gravity = false;
  cfg.rotor_aerodynamics = false;
  cfg.motor_reaction = false;
  cfg.gyroscopic = false;
  cfg.ground_strikes = false;
  const TruthParams truth = paperTruth();
  std::array<double, 2> spin{};
  for (std::size_t k = 0; k < 2; ++k) {
    PlantState s0;
    s0.p_W = Eigen::Vector3d(0.0, 0.0, k == 0 ? 0.12 : 3.0);
    s0.n_rpm = all(15'000.0);
    Plant plant(truth, std::make_shared<FlatGround>(0.0), cfg, s0);
    plant.addContribution(std::make_unique<RotorTurbulence>(perRotor(), truth, 4));
    for (int j = 0; j < 500; ++j) (void)plant.step({0.5, 0.5, 0.5, 0.5});
    spin[k] = plant.state().w_B.norm();
  }
  EXPECT_GT(spin[0], 1e-3);
  EXPECT_GT(spin[0], 20.0 * spin[1]);
}

TEST(RotorTurbulence, ValidationNamesTheFields) {
  GroundTurbulenceParams p = perRotor(-0.1, 1.5);
  try {
    RotorTurbulence t(p, paperTruth(), 1);
    FAIL() << "expected InvalidParameters";
  } catch (const std::exception& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("fluctuation_per_increment"), std::string::npos) << what;
    EXPECT_NE(what.find("rotor_correlation"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace geaware::sim
