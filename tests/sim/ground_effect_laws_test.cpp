// SPDX-License-Identifier: BSD-3-Clause
// The closed-form ground-effect law families of the truth aerodynamics (GroundEffectLaw;
// docs/sim-aerodynamics.md, "Other law families"), each against its formula computed here from
// the rotor geometry: Cheeseman & Bennett 1955 per rotor and Sanchez-Cuevas et al. 2017 per
// rotor, both held at z ≥ R/2, each rotor's increment on its own thrust.
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "geaware/sim/rotor_aerodynamics.hpp"
#include "geaware/sim/truth_params.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace geaware::sim {
namespace {

TruthParams paperTruth() { return fromNominal(geaware_test::paperParams()); }

RotorAerodynamics withLaw(GroundEffectLaw law) {
  TruthParams p = paperTruth();
  p.aero.law = law;
  return RotorAerodynamics(p.rotorGeometry(), p.aero);
}

double taper(double z) { return 1.0 - std::pow(z / 3.0, 4); }

/// (R/4z)², the rotor's own image.
double imageTerm(double R, double z) { return (R / (4.0 * z)) * (R / (4.0 * z)); }

/// Sanchez-Cuevas et al. 2017: the terms under 1/(1 − x), from the geometry as given.
double sanchezCuevasTerms(const RotorGeometry& g, double K_b, double z) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& r : g.position_B) centre += r / 4.0;
  double b = 0.0;  // rotor-to-centre distance in the rotor plane
  for (const auto& r : g.position_B) b += (r - centre).head<2>().norm() / 4.0;
  const double d = std::sqrt(2.0) * b;  // adjacent rotors of the X layout
  const double R = g.radius_m;
  const double z2 = 4.0 * z * z;
  return imageTerm(R, z) + R * R * z / std::pow(d * d + z2, 1.5) +
         0.5 * R * R * z / std::pow(2.0 * d * d + z2, 1.5) +
         2.0 * R * R * K_b * z / std::pow(b * b + z2, 1.5);
}

TEST(GroundEffectLaws, DefaultIsTheCalibratedLaw) {
  EXPECT_EQ(RotorAeroParams{}.law, GroundEffectLaw::kCalibrated);
  EXPECT_STREQ(toString(GroundEffectLaw::kCalibrated), "calibrated");
  EXPECT_STREQ(toString(GroundEffectLaw::kCheesemanBennett), "cheeseman_bennett");
  EXPECT_STREQ(toString(GroundEffectLaw::kSanchezCuevas), "sanchez_cuevas");
}

TEST(GroundEffectLaws, CheesemanBennettPerRotorIsItsClosedForm) {
  const RotorAerodynamics a = withLaw(GroundEffectLaw::kCheesemanBennett);
  const double R = a.geometry().radius_m;
  // Each rotor at its own distance: the law of that distance alone.
  const std::array<double, 4> z = {0.08, 0.12, 0.2, 0.5};
  const auto phi = a.additionalThrustFraction(z);
  for (std::size_t i = 0; i < 4; ++i) {
    const double x = imageTerm(R, z[i]);
    EXPECT_NEAR(phi[i], (1.0 / (1.0 - x) - 1.0) * taper(z[i]), 1e-14) << "rotor " << i + 1;
  }
  // A single 7-inch rotor gains ≈ 3.6 % at 0.12 m (REALITY-GAP.md).
  EXPECT_NEAR(phi[1], 0.0357, 5e-4);
}

TEST(GroundEffectLaws, SanchezCuevasPerRotorIsItsClosedForm) {
  const TruthParams p = paperTruth();
  const RotorAerodynamics a = withLaw(GroundEffectLaw::kSanchezCuevas);
  const std::array<double, 4> z = {0.07, 0.12, 0.18, 0.4};
  const auto phi = a.additionalThrustFraction(z);
  for (std::size_t i = 0; i < 4; ++i) {
    const double x = sanchezCuevasTerms(a.geometry(), p.aero.body_coefficient, z[i]);
    EXPECT_NEAR(phi[i], (1.0 / (1.0 - x) - 1.0) * taper(z[i]), 1e-12) << "rotor " << i + 1;
  }
  // The neighbour and body terms dominate the rotor's own image (the multirotor's ≈ 23 % at
  // 0.12 m against a single rotor's 3.6 %, REALITY-GAP.md).
  EXPECT_GT(phi[1], 0.2);
  EXPECT_LT(phi[1], 0.35);
}

TEST(GroundEffectLaws, ClosedFormsAreHeldAtHalfARadius) {
  for (const auto law : {GroundEffectLaw::kCheesemanBennett, GroundEffectLaw::kSanchezCuevas}) {
    const RotorAerodynamics a = withLaw(law);
    const double z_hold = kClosedFormMinHeightOverRadius * a.geometry().radius_m;
    const auto at_hold = a.additionalThrustFraction({z_hold, z_hold, z_hold, z_hold});
    const auto below = a.additionalThrustFraction({0.02, 0.02, 0.02, 0.02});
    // Below R/2 only the (range) taper still changes: 1 − (z/3)⁴ ≈ 1 − 5e-8.
    EXPECT_NEAR(below[0], at_hold[0] / taper(z_hold) * taper(0.02), 1e-12) << toString(law);
    EXPECT_TRUE(std::isfinite(below[0]));
  }
  // 1/(1 − (R/4·(R/2))²) − 1 = 1/3, tapered at the distance (clamped to the 0.01 m minimum).
  const RotorAerodynamics cb = withLaw(GroundEffectLaw::kCheesemanBennett);
  EXPECT_NEAR(cb.additionalThrustFraction({0.001, 1, 1, 1})[0], (4.0 / 3.0 - 1.0) * taper(0.01),
              1e-12);
}

TEST(GroundEffectLaws, EachRotorsIncrementScalesWithItsOwnThrust) {
  const RotorAerodynamics a = withLaw(GroundEffectLaw::kSanchezCuevas);
  const std::array<double, 4> z = {0.1, 0.15, 0.2, 0.25};
  const std::array<double, 4> n = {9000.0, 10000.0, 11000.0, 12000.0};
  const auto phi = a.additionalThrustFraction(z);
  const RotorAeroOutput o = a.compute(n, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(),
                                      Eigen::Vector3d::Zero(), a.groundFactors(z));
  for (std::size_t i = 0; i < 4; ++i) {
    const double t_free = a.geometry().k_T_N_per_rpm2[i] * n[i] * n[i];
    EXPECT_NEAR(o.thrust_N[i], t_free * (1.0 + phi[i]), 1e-12) << "rotor " << i + 1;
  }
}

TEST(GroundEffectLaws, NoSurfaceMeansNoIncrementAndTheDragFactorsAreTheCalibrateds) {
  const RotorAerodynamics cb = withLaw(GroundEffectLaw::kCheesemanBennett);
  const RotorAerodynamics cal = withLaw(GroundEffectLaw::kCalibrated);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const std::array<double, 4> z = {0.1, kInf, std::nan(""), 5.0};
  const RotorGroundFactors f = cb.groundFactors(z);
  const RotorGroundFactors g = cal.groundFactors(z);
  EXPECT_GT(f.phi[0], 0.0);
  EXPECT_EQ(f.phi[1], 0.0);
  EXPECT_EQ(f.phi[2], 0.0);
  EXPECT_EQ(f.phi[3], 0.0);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(f.drag_scale_x[i], g.drag_scale_x[i], 1e-15);
    EXPECT_NEAR(f.drag_scale_y[i], g.drag_scale_y[i], 1e-15);
  }
}

TEST(GroundEffectLaws, TheInFlightScaleAppliesToClosedFormsToo) {
  TruthParams p = paperTruth();
  p.aero.law = GroundEffectLaw::kCheesemanBennett;
  p.aero.in_flight_cushion_scale = 0.5;
  const RotorAerodynamics a(p.rotorGeometry(), p.aero);
  const std::array<double, 4> z = {0.12, 0.12, 0.12, 0.12};
  EXPECT_NEAR(a.flightFactors(z).phi[0], 0.5 * a.groundFactors(z).phi[0], 1e-15);
}

}  // namespace
}  // namespace geaware::sim
