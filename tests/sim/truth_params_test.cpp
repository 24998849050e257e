// SPDX-License-Identifier: BSD-3-Clause
// The truth's parameters: built from a nominal vehicle, perturbed from a seed, validated.
#include "geaware/sim/truth_params.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "geaware/model/units.hpp"
#include "geaware/sim/plant.hpp"
#include "geaware_test/eigen_matchers.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace geaware::sim {
namespace {

TruthParams paperTruth() { return fromNominal(geaware_test::paperParams()); }
// ---------------------------------------------------------------------------------------------
// Truth parameters
// ---------------------------------------------------------------------------------------------

TEST(TruthParams, FromNominalIsTheNominalVehicle) {
  const auto& nominal = geaware_test::paperParams();
  const TruthParams p = paperTruth();
  EXPECT_TRUE(p.validate().empty());
  EXPECT_EQ(p.mass_kg, nominal.mass_kg);
  EXPECT_MATRIX_NEAR(p.inertia_kgm2, Eigen::Matrix3d(nominal.inertia_kgm2.asDiagonal()), 0.0);
  EXPECT_MATRIX_NEAR(p.cog_offset_B, Eigen::Vector3d::Zero(), 0.0);
  EXPECT_EQ(p.k_T_N_per_rpm2, nominal.rotor.k_T_N_per_rpm2);
  EXPECT_EQ(p.motor.J_R_kgm2, nominal.rotor.J_R_kgm2);
  EXPECT_EQ(p.motor.throttle.c0_rpm2, nominal.throttle.c0_rpm2);
  ASSERT_EQ(p.landing_feet_B.size(), 4u);
  EXPECT_DOUBLE_EQ(p.landing_feet_B[0].z(), -nominal.min_rotor_plane_height_m);
  const RotorGeometry g = p.rotorGeometry();
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(g.position_B[i].head<2>().norm(), nominal.diagonal_rotor_distance_m / 2.0, 1e-15);
    EXPECT_EQ(g.k_T_N_per_rpm2[i], nominal.rotor.k_T_N_per_rpm2);
  }
}

TEST(TruthParams, PerturbedIsSeededAndBounded) {
  const TruthParams base = paperTruth();
  MismatchSpec spec;
  spec.mass_rel = 0.1;
  spec.inertia_rel = 0.2;
  spec.cog_offset_m = 0.01;
  spec.cog_offset_z_m = 0.005;
  spec.thrust_spread_rel = 0.03;
  const TruthParams a = perturbed(base, spec, 42);
  const TruthParams b = perturbed(base, spec, 42);
  const TruthParams c = perturbed(base, spec, 43);
  EXPECT_EQ(a.mass_kg, b.mass_kg);
  EXPECT_EQ(a.inertia_kgm2, b.inertia_kgm2);
  EXPECT_EQ(a.cog_offset_B, b.cog_offset_B);
  EXPECT_EQ(a.thrust_multiplier, b.thrust_multiplier);
  EXPECT_NE(a.mass_kg, c.mass_kg);
  for (const TruthParams* p : {&a, &c}) {
    EXPECT_TRUE(p->validate().empty());
    EXPECT_LE(std::abs(p->mass_kg / base.mass_kg - 1.0), 0.1);
    EXPECT_LE(std::abs(p->cog_offset_B.x()), 0.01);
    EXPECT_LE(std::abs(p->cog_offset_B.z()), 0.005);
    for (double m : p->thrust_multiplier) EXPECT_LE(std::abs(m - 1.0), 0.03);
  }
  // No mismatch: the very same vehicle.
  const TruthParams same = perturbed(base, MismatchSpec{}, 7);
  EXPECT_EQ(same.mass_kg, base.mass_kg);
  EXPECT_EQ(same.inertia_kgm2, base.inertia_kgm2);
}

TEST(TruthParams, ValidateNamesTheOffendingFields) {
  TruthParams p = paperTruth();
  p.mass_kg = -1.0;
  p.inertia_kgm2(0, 0) = std::numeric_limits<double>::quiet_NaN();
  p.motor.time_constant_s = 0.0;
  p.battery.empty_voltage_V = 20.0;
  p.yaw_sign[2] = 0.5;
  const auto errors = p.validate();
  const auto has = [&](const std::string& field) {
    for (const auto& e : errors) {
      if (e.field == field) return true;
    }
    return false;
  };
  EXPECT_TRUE(has("mass_kg"));
  EXPECT_TRUE(has("inertia_kgm2(0,0)"));
  EXPECT_TRUE(has("motor.time_constant_s"));
  EXPECT_TRUE(has("battery.empty_voltage_V"));
  EXPECT_TRUE(has("yaw_sign[2]"));
  EXPECT_THROW(Plant(p, nullptr), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Closed-form flights
// ---------------------------------------------------------------------------------------------

}  // namespace
}  // namespace geaware::sim
