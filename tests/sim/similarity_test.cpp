// SPDX-License-Identifier: BSD-3-Clause
// The ideal world of another vehicle: the calibrated defaults carried over by similarity
// (sim/similarity.hpp). The reference vehicle keeps them bit for bit; a geometrically similar
// vehicle sees the same ground effect at the same height over radius; the speed ceiling follows
// the vehicle's own throttle curve.
#include "geaware/sim/similarity.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "geaware/model/motor.hpp"
#include "geaware/sim/world.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace geaware::sim {
namespace {

/// The paper's vehicle with every length × s and the mass × s³ (same density); k_T so that it
/// hovers at the Froude speed (∝ s^−1/2), the throttle curve × that speed squared.
model::VehicleParams similarVehicle(double s) {
  model::VehicleParams v = geaware_test::paperParams();
  v.propeller_radius_m *= s;
  v.diagonal_rotor_distance_m *= s;
  v.min_rotor_plane_height_m *= s;
  v.mass_kg *= s * s * s;
  const double speed = 1.0 / std::sqrt(s);  // hover speed ratio
  v.rotor.k_T_N_per_rpm2 *= s * s * s / (speed * speed);
  v.throttle.c2_rpm2 *= speed * speed;
  v.throttle.c1_rpm2 *= speed * speed;
  v.throttle.c0_rpm2 *= speed * speed;
  return v;
}

TEST(Similarity, TheReferenceConstantsAreTheBuiltInVehicles) {
  const model::VehicleParams& p = geaware_test::paperParams();
  EXPECT_EQ(ReferenceVehicle::kMassKg, p.mass_kg);
  EXPECT_EQ(ReferenceVehicle::kPropellerRadiusM, p.propeller_radius_m);
  EXPECT_EQ(ReferenceVehicle::kDiagonalRotorDistanceM, p.diagonal_rotor_distance_m);
  EXPECT_EQ(ReferenceVehicle::kThrustCoefficientNPerRpm2, p.rotor.k_T_N_per_rpm2);
  EXPECT_EQ(ReferenceVehicle::kThrottleC2Rpm2, p.throttle.c2_rpm2);
  EXPECT_EQ(ReferenceVehicle::kThrottleC1Rpm2, p.throttle.c1_rpm2);
  EXPECT_EQ(ReferenceVehicle::kThrottleC0Rpm2, p.throttle.c0_rpm2);
}

TEST(Similarity, TheReferenceVehicleKeepsEveryCalibratedValueBitForBit) {
  const World w = idealWorld(geaware_test::paperParams());
  const RotorAeroParams a;
  const RotorAeroParams& b = w.truth.aero;
  for (const auto& [x, y] : std::array<std::array<double, 2>, 13>{
           {{a.impingement_slope_per_m, b.impingement_slope_per_m},
            {a.wake_merge_height_m, b.wake_merge_height_m},
            {a.wake_merge_softness_m, b.wake_merge_softness_m},
            {a.recirculation_height_m, b.recirculation_height_m},
            {a.redistribution_cap_per_m, b.redistribution_cap_per_m},
            {a.ground_effect_range_m, b.ground_effect_range_m},
            {a.induced_velocity_mps, b.induced_velocity_mps},
            {a.induced_velocity_ref_rpm, b.induced_velocity_ref_rpm},
            {a.drag_x_N_per_mps_per_rpm, b.drag_x_N_per_mps_per_rpm},
            {a.drag_y_N_per_mps_per_rpm, b.drag_y_N_per_mps_per_rpm},
            {a.drag_ground_height_m, b.drag_ground_height_m},
            {MotorParams{}.max_speed_rpm, w.truth.motor.max_speed_rpm},
            {MotorParams{}.time_constant_s, w.truth.motor.time_constant_s}}}) {
    EXPECT_EQ(x, y);
  }
  const GroundTurbulenceParams g;
  EXPECT_EQ(g.force_std_N, w.ground_turbulence_params.force_std_N);
  EXPECT_EQ(g.torque_std_Nm, w.ground_turbulence_params.torque_std_Nm);
  EXPECT_EQ(g.scale_height_m, w.ground_turbulence_params.scale_height_m);
  EXPECT_EQ(g.cutoff_height_m, w.ground_turbulence_params.cutoff_height_m);
  EXPECT_EQ(g.correlation_time_s, w.ground_turbulence_params.correlation_time_s);
}

TEST(Similarity, ASimilarVehicleSeesTheSameCushionAtTheSameHeightOverRadius) {
  const TruthParams ref = fromNominal(geaware_test::paperParams());
  const RotorAerodynamics paper(ref.rotorGeometry(), ref.aero);
  for (const double s : {0.43, 0.71, 1.6}) {
    const TruthParams t = fromNominal(similarVehicle(s));
    const RotorAerodynamics small(t.rotorGeometry(), t.aero);
    // A level vehicle and a tilted one (rotors at different heights), from below the
    // recirculation peak to beyond the wake merge.
    for (const std::array<double, 4> d : {std::array<double, 4>{0.05, 0.05, 0.05, 0.05},
                                          std::array<double, 4>{0.09, 0.09, 0.09, 0.09},
                                          std::array<double, 4>{0.12, 0.16, 0.20, 0.16},
                                          std::array<double, 4>{0.25, 0.30, 0.35, 0.30},
                                          std::array<double, 4>{0.6, 0.6, 0.6, 0.6}}) {
      std::array<double, 4> ds{};
      for (std::size_t i = 0; i < 4; ++i) ds[i] = d[i] * s;
      const auto phi = paper.additionalThrustFraction(d);
      const auto phi_s = small.additionalThrustFraction(ds);
      for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_NEAR(phi_s[i], phi[i], 1e-12 + 1e-9 * std::abs(phi[i]))
            << "s " << s << ", rotor " << i << " at " << d[i] << " m";
      }
      const auto q = paper.groundFactors(d);
      const auto q_s = small.groundFactors(ds);
      EXPECT_NEAR(q_s.drag_scale_x[0], q.drag_scale_x[0], 1e-12);
    }
  }
}

TEST(Similarity, TheMotorsCeilingFollowsTheVehiclesCurveAndItsLagTheFroudeRule) {
  // A 250 g 3-inch quadrotor (tests/fixtures/vehicles/micro3.yaml's numbers): its throttle curve
  // tops out at 44,000 rpm, twice the paper's; it hovers at 22,040 rpm, above the paper's
  // 21,000 rpm ceiling, which would pin it on the ground.
  model::VehicleParams v = geaware_test::paperParams();
  v.mass_kg = 0.250;
  v.propeller_radius_m = 0.0381;
  v.diagonal_rotor_distance_m = 0.13;
  v.rotor.k_T_N_per_rpm2 = 1.262e-9;
  v.throttle = {1.681e9, 2.46e8, 9.0e6};
  const TruthParams t = fromNominal(v);
  EXPECT_NEAR(model::ThrottleCurve(v.throttle).maxSpeedRpm(), 44000.0, 1e-9);
  EXPECT_NEAR(
      t.motor.max_speed_rpm,
      21000.0 * 44000.0 / model::ThrottleCurve(geaware_test::paperParams().throttle).maxSpeedRpm(),
      1e-9);
  EXPECT_GT(t.motor.max_speed_rpm, 44000.0);
  EXPECT_NEAR(t.motor.time_constant_s, 0.03 * std::sqrt(0.0381 / 0.089), 1e-15);
  // Per-rotor drag per rpm ∝ R³; the turbulence forces with the weight.
  EXPECT_NEAR(t.aero.drag_x_N_per_mps_per_rpm / RotorAeroParams{}.drag_x_N_per_mps_per_rpm,
              std::pow(0.0381 / 0.089, 3), 1e-12);
  const World w = idealWorld(v);
  EXPECT_NEAR(w.ground_turbulence_params.force_std_N.z() / GroundTurbulenceParams{}.force_std_N.z(),
              0.250 / 1.696, 1e-12);
  EXPECT_TRUE(t.validate().empty());
}

}  // namespace
}  // namespace geaware::sim
