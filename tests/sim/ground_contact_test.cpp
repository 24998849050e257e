// SPDX-License-Identifier: BSD-3-Clause
// The landing gear on the ground (sim/ground_contact.hpp), against closed forms: the static
// compression m·g/(N·k), the rebound of a level drop (the damped oscillator's velocity where its
// force returns to zero, found here by bisection on the analytic solution), the sliding
// deceleration μ·g, mechanical energy that never grows while the feet touch; and the strike
// rules (a foot may sink as far as its leg gives, a rotor disc never; contact off keeps the
// pre-contact rule).
#include "geaware/sim/ground_contact.hpp"

#include <cmath>
#include <memory>
#include <numbers>

#include <gtest/gtest.h>

#include "geaware/sim/plant.hpp"
#include "geaware/sim/terrains.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace geaware::sim {
namespace {

TruthParams paperTruth() { return fromNominal(geaware_test::paperParams()); }

/// Rotors off, so that only gravity and the gear act (the rigid body alone otherwise).
PlantConfig gearOnly(bool gravity = true) {
  PlantConfig c;
  c.rotor_aerodynamics = false;
  c.motor_reaction = false;
  c.gyroscopic = false;
  c.gravity = gravity;
  c.ground_contact = true;
  return c;
}

/// The geometric centre's height at which the feet just touch flat ground at z = 0.
double touchHeight(const TruthParams& p) { return -p.landing_feet_B.front().z(); }

PlantState level(double z_m, const Eigen::Vector3d& v_W = Eigen::Vector3d::Zero()) {
  PlantState s;
  s.p_W = Eigen::Vector3d(0.0, 0.0, z_m);
  s.v_W = v_W;
  return s;
}

TEST(GroundContact, TheDefaultGearIsDocumented) {
  const TruthParams p = paperTruth();
  ASSERT_EQ(p.landing_feet_B.size(), 4u);
  EXPECT_NEAR(p.landing_gear.stiffness_N_per_m,
              p.mass_kg * p.gravity_mps2 / (4.0 * kDefaultGearStaticDeflectionM), 1e-9);
  EXPECT_NEAR(p.landing_gear.stiffness_N_per_m, 1386.48, 0.005);  // docs/world.md §9, config/truths/ideal.yaml
  EXPECT_EQ(p.landing_gear.damping_ratio, kDefaultGearDampingRatio);
  EXPECT_EQ(p.landing_gear.friction_coefficient, kDefaultGearFrictionCoefficient);
  EXPECT_EQ(p.landing_gear.max_compression_m, kDefaultGearMaxCompressionM);
  EXPECT_TRUE(p.validate().empty());
  TruthParams bad = p;
  bad.landing_gear.stiffness_N_per_m = -1.0;
  bad.landing_gear.max_compression_m = 0.0;
  const auto errors = bad.validate();
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0].field, "landing_gear.stiffness_N_per_m");
  EXPECT_EQ(errors[1].field, "landing_gear.max_compression_m");
}

TEST(GroundContact, AtRestEachFootCarriesAQuarterOfTheWeight) {
  const TruthParams p = paperTruth();
  Plant plant(p, std::make_shared<FlatGround>(0.0), gearOnly(), level(touchHeight(p)));
  ASSERT_NE(plant.contact(), nullptr);
  for (int k = 0; k < 5000; ++k) ASSERT_FALSE(plant.step({0, 0, 0, 0}).crash) << k;
  const double k_N_per_m = p.landing_gear.stiffness_N_per_m;
  const double expected = p.mass_kg * p.gravity_mps2 / (4.0 * k_N_per_m);
  EXPECT_NEAR(expected, kDefaultGearStaticDeflectionM, 1e-12);
  ASSERT_EQ(plant.contact()->touchingFeet(), 4);
  for (const FootContact& f : plant.contact()->feet()) {
    EXPECT_NEAR(f.compression_m, expected, 1e-7);
    EXPECT_NEAR(f.normal_force_N, 0.25 * p.mass_kg * p.gravity_mps2, 1e-3);
  }
  EXPECT_NEAR(plant.state().p_W.z(), touchHeight(p) - expected, 1e-7);
  EXPECT_LT(plant.state().v_W.norm(), 1e-6);
}

/// The analytic level drop: penetration x(t) = v₀/ω_d·e^(−ζωt)·sin(ω_d t) while the leg's force
/// k·x + c·ẋ is positive; the rebound velocity is ẋ where that force first returns to zero.
double analyticReboundSpeed(double v0, double k, double c, double m_foot) {
  const double w = std::sqrt(k / m_foot);
  const double zeta = c / (2.0 * std::sqrt(k * m_foot));
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  const auto x = [&](double t) { return v0 / wd * std::exp(-zeta * w * t) * std::sin(wd * t); };
  const auto xdot = [&](double t) {
    return v0 * std::exp(-zeta * w * t) * (std::cos(wd * t) - zeta * w / wd * std::sin(wd * t));
  };
  const auto force = [&](double t) { return k * x(t) + c * xdot(t); };
  double lo = 0.5 * std::numbers::pi / wd;  // force > 0 (x at its peak region, ẋ ≤ 0 after)
  double hi = std::numbers::pi / wd;        // x = 0, ẋ < 0: force < 0
  EXPECT_GT(force(lo), 0.0);
  EXPECT_LT(force(hi), 0.0);
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (force(mid) > 0.0 ? lo : hi) = mid;
  }
  return -xdot(lo);
}

TEST(GroundContact, ALevelDropReboundsAsTheDampedOscillator) {
  const TruthParams p = paperTruth();
  const double v0 = 0.5;
  Plant plant(p, std::make_shared<FlatGround>(0.0), gearOnly(/*gravity=*/false),
              level(touchHeight(p) + 1e-4, {0.0, 0.0, -v0}));
  bool touched = false;
  for (int k = 0; k < 20000; ++k) {
    ASSERT_FALSE(plant.step({0, 0, 0, 0}, 1e-5).crash);
    const int n = plant.contact()->touchingFeet();
    if (n > 0) touched = true;
    if (touched && n == 0) break;
  }
  ASSERT_TRUE(touched);
  ASSERT_EQ(plant.contact()->touchingFeet(), 0);
  const double expected = analyticReboundSpeed(v0, p.landing_gear.stiffness_N_per_m,
                                               plant.contact()->dampingNsPerM(), p.mass_kg / 4.0);
  EXPECT_NEAR(plant.state().v_W.z(), expected, 2e-3 * v0);
  EXPECT_NEAR(plant.state().v_W.head<2>().norm(), 0.0, 1e-12);
  // The restitution the default gear gives (docs/truth-file.md, "Landing gear").
  EXPECT_NEAR(expected / v0, 0.45, 0.01);
}

TEST(GroundContact, ASlidingVehicleDeceleratesAtMuG) {
  const TruthParams p = paperTruth();
  const double mu = p.landing_gear.friction_coefficient;
  const double z_rest = touchHeight(p) - kDefaultGearStaticDeflectionM;
  Plant plant(p, std::make_shared<FlatGround>(0.0), gearOnly(), level(z_rest, {1.0, 0.0, 0.0}));
  for (int k = 0; k < 100; ++k) ASSERT_FALSE(plant.step({0, 0, 0, 0}).crash);
  // v(t) = 1 − μ·g·t until it nearly stops (the feet's friction also pitches the body a little,
  // moving the load between the legs, not its sum).
  EXPECT_NEAR(plant.state().v_W.x(), 1.0 - mu * p.gravity_mps2 * 0.1, 0.02);
  for (int k = 0; k < 1000; ++k) ASSERT_FALSE(plant.step({0, 0, 0, 0}).crash);
  EXPECT_LT(plant.state().v_W.norm(), 0.01);
}

TEST(GroundContact, MechanicalEnergyNeverGrowsWhileTheFeetTouch) {
  const TruthParams p = paperTruth();
  PlantState s = level(touchHeight(p) + 0.02, {0.3, -0.2, 0.0});
  s.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.05, Eigen::Vector3d(1, 2, 0).normalized()));
  s.w_B = Eigen::Vector3d(0.5, -0.3, 0.2);
  Plant plant(p, std::make_shared<FlatGround>(0.0), gearOnly(), s);
  const double k_N_per_m = p.landing_gear.stiffness_N_per_m;
  const auto energy = [&] {
    const RigidBodyState& b = plant.centreOfMassState();
    double e = 0.5 * p.mass_kg * b.v_W.squaredNorm() +
               0.5 * b.w_B.dot(p.inertia_kgm2 * b.w_B) + p.mass_kg * p.gravity_mps2 * b.p_W.z();
    for (const FootContact& f : plant.contact()->feet())
      e += 0.5 * k_N_per_m * f.compression_m * f.compression_m;
    return e;
  };
  double previous = energy();
  const double start = previous;
  int touching_steps = 0;
  for (int k = 0; k < 3000; ++k) {
    const auto r = plant.step({0, 0, 0, 0});
    ASSERT_FALSE(r.crash) << k << ": " << describe(*r.crash);
    const double e = energy();
    // The spring energy of a foot that touches mid-step is counted from the step's end only;
    // a joule-scale budget would hide a wrong sign, a micro-joule one does not.
    EXPECT_LE(e, previous + 2e-5) << "step " << k;
    touching_steps += plant.contact()->touchingFeet() > 0 ? 1 : 0;
    previous = e;
  }
  EXPECT_GT(touching_steps, 2000);
  EXPECT_LT(previous, start - 0.5 * p.mass_kg * p.gravity_mps2 * 0.02);
  EXPECT_LT(plant.state().v_W.norm(), 1e-3);
}

TEST(GroundContact, AFootMaySinkAsFarAsItsLegGivesARotorDiscNever) {
  const TruthParams p = paperTruth();
  // 0.5 m/s: the legs give ≈ 6 mm, no strike with contact; a strike at once without it.
  {
    Plant plant(p, std::make_shared<FlatGround>(0.0), gearOnly(), level(touchHeight(p) + 0.01, {0, 0, -0.5}));
    for (int k = 0; k < 500; ++k) ASSERT_FALSE(plant.step({0, 0, 0, 0}).crash) << k;
  }
  {
    PlantConfig off = gearOnly();
    off.ground_contact = false;
    Plant plant(p, std::make_shared<FlatGround>(0.0), off, level(touchHeight(p) + 0.01, {0, 0, -0.5}));
    EXPECT_EQ(plant.contact(), nullptr);
    std::optional<Crash> crash;
    for (int k = 0; k < 500 && !crash; ++k) crash = plant.step({0, 0, 0, 0}).crash;
    ASSERT_TRUE(crash);
    EXPECT_EQ(crash->part, StrikePart::kLandingFoot);
  }
  // 3 m/s: the legs would give ≈ 3 cm, beyond their 2 cm: a strike of a foot.
  {
    Plant plant(p, std::make_shared<FlatGround>(0.0), gearOnly(), level(touchHeight(p) + 0.01, {0, 0, -3.0}));
    std::optional<Crash> crash;
    for (int k = 0; k < 500 && !crash; ++k) crash = plant.step({0, 0, 0, 0}).crash;
    ASSERT_TRUE(crash);
    EXPECT_EQ(crash->part, StrikePart::kLandingFoot);
    EXPECT_GT(crash->depth_m, p.landing_gear.max_compression_m);
  }
  // Rolled 50° onto two feet: a rotor disc reaches the ground while the legs hold.
  {
    PlantState s = level(touchHeight(p) + 0.01);
    s.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.87, Eigen::Vector3d::UnitX()));
    Plant plant(p, std::make_shared<FlatGround>(0.0), gearOnly(), s);
    std::optional<Crash> crash;
    for (int k = 0; k < 2000 && !crash; ++k) crash = plant.step({0, 0, 0, 0}).crash;
    ASSERT_TRUE(crash);
    EXPECT_EQ(crash->part, StrikePart::kRotorDisc);
  }
}

TEST(GroundContact, StandingOnAGentleSlopeCreepsSlowerThanTheSlipSpeed) {
  TruthParams p = paperTruth();
  const double slope = 10.0 * std::numbers::pi / 180.0;
  auto plane = std::make_shared<TiltedPlane>(TiltedPlane::fromTilt(Eigen::Vector3d::Zero(), 0.0, slope));
  PlantState s = level(touchHeight(p) + 0.002);
  s.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(slope, Eigen::Vector3d::UnitY()));
  Plant plant(p, plane, gearOnly(), s);
  for (int k = 0; k < 3000; ++k) ASSERT_FALSE(plant.step({0, 0, 0, 0}).crash) << k;
  EXPECT_EQ(plant.contact()->touchingFeet(), 4);
  // Regularised Coulomb friction: v ≈ v_s·tan θ/√(μ² − tan² θ) along the slope.
  const double t = std::tan(slope);
  const double mu = p.landing_gear.friction_coefficient;
  const double creep = p.landing_gear.slip_speed_mps * t / std::sqrt(mu * mu - t * t);
  EXPECT_NEAR(plant.state().v_W.norm(), creep, 0.1 * creep);
}

}  // namespace
}  // namespace geaware::sim
