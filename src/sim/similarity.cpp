// SPDX-License-Identifier: BSD-3-Clause
// Carrying the calibrated defaults over to another vehicle by similarity (sim/similarity.hpp).

#include "geaware/sim/similarity.hpp"

#include <cmath>

#include "geaware/model/motor.hpp"

namespace geaware::sim {

double SimilarityRatios::inducedVelocity() const noexcept { return std::sqrt(mass) / length; }

SimilarityRatios similarityToReference(const model::VehicleParams& v) noexcept {
  using Ref = ReferenceVehicle;
  model::ThrottleCurveParams ref_curve;
  ref_curve.c2_rpm2 = Ref::kThrottleC2Rpm2;
  ref_curve.c1_rpm2 = Ref::kThrottleC1Rpm2;
  ref_curve.c0_rpm2 = Ref::kThrottleC0Rpm2;
  SimilarityRatios r;
  r.length = v.propeller_radius_m / Ref::kPropellerRadiusM;
  r.mass = v.mass_kg / Ref::kMassKg;
  r.arm = v.diagonal_rotor_distance_m / Ref::kDiagonalRotorDistanceM;
  r.hover_speed = model::freeAirHoverSpeedRpm(v.mass_kg, v.rotor.k_T_N_per_rpm2) /
                  model::freeAirHoverSpeedRpm(Ref::kMassKg, Ref::kThrustCoefficientNPerRpm2);
  r.top_speed = model::ThrottleCurve(v.throttle).maxSpeedRpm() /
                model::ThrottleCurve(ref_curve).maxSpeedRpm();
  return r;
}

RotorAeroParams scaledAero(const RotorAeroParams& ref, const SimilarityRatios& r) noexcept {
  RotorAeroParams a = ref;
  const double L = r.length;
  a.impingement_slope_per_m = ref.impingement_slope_per_m / L;
  a.wake_merge_height_m = ref.wake_merge_height_m * L;
  a.wake_merge_softness_m = ref.wake_merge_softness_m * L;
  a.recirculation_height_m = ref.recirculation_height_m * L;
  a.redistribution_cap_per_m = ref.redistribution_cap_per_m / L;
  a.ground_effect_range_m = ref.ground_effect_range_m * L;
  a.induced_velocity_mps = ref.induced_velocity_mps * r.inducedVelocity();
  a.induced_velocity_ref_rpm = ref.induced_velocity_ref_rpm * r.hover_speed;
  const double cube = L * L * L;
  a.drag_x_N_per_mps_per_rpm = ref.drag_x_N_per_mps_per_rpm * cube;
  a.drag_y_N_per_mps_per_rpm = ref.drag_y_N_per_mps_per_rpm * cube;
  a.drag_ground_height_m = ref.drag_ground_height_m * L;
  return a;
}

GroundTurbulenceParams scaledGroundTurbulence(const GroundTurbulenceParams& ref,
                                              const SimilarityRatios& r) noexcept {
  GroundTurbulenceParams g = ref;
  g.force_std_N = ref.force_std_N * r.mass;
  g.torque_std_Nm = ref.torque_std_Nm * (r.mass * r.arm);
  g.scale_height_m = ref.scale_height_m * r.length;
  g.cutoff_height_m = ref.cutoff_height_m * r.length;
  g.correlation_time_s = ref.correlation_time_s * (r.length / r.inducedVelocity());
  return g;
}

MotorParams scaledMotor(const MotorParams& ref, const SimilarityRatios& r) noexcept {
  MotorParams m = ref;
  m.max_speed_rpm = ref.max_speed_rpm * r.top_speed;
  m.time_constant_s = ref.time_constant_s * std::sqrt(r.length);
  return m;
}

}  // namespace geaware::sim
