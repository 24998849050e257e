// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/sim/truth_params.hpp"

#include "geaware/sim/similarity.hpp"

#include "geaware/sim/sampling.hpp"

#include <cmath>
#include <random>
#include <string>
#include <utility>

#include <Eigen/Eigenvalues>

#include "geaware/model/field_check.hpp"
#include "geaware/model/mixer.hpp"
#include "geaware/model/units.hpp"

namespace geaware::sim {

using model::formatValue;

Eigen::Vector3d tiltedAxis(const Eigen::Vector2d& tilt_rad) noexcept {
  if (tilt_rad.x() == 0.0 && tilt_rad.y() == 0.0) return Eigen::Vector3d::UnitZ();
  // R_y(θ_y)·R_x(θ_x)·z = (sin θ_y·cos θ_x, −sin θ_x, cos θ_y·cos θ_x).
  const double cx = std::cos(tilt_rad.x());
  return {std::sin(tilt_rad.y()) * cx, -std::sin(tilt_rad.x()), std::cos(tilt_rad.y()) * cx};
}

RotorGeometry TruthParams::rotorGeometry() const {
  RotorGeometry g;
  for (std::size_t i = 0; i < 4; ++i) {
    g.position_B[i] = rotor_position_B[i] - cog_offset_B;  // the aerodynamics work about the CoM
    g.spin[i] = yaw_sign[i];
    g.k_T_N_per_rpm2[i] = k_T_N_per_rpm2 * thrust_multiplier[i];
    g.k_I_Nm_per_rpm2[i] = k_I_Nm_per_rpm2 * torque_multiplier[i];
    g.thrust_axis_B[i] = tiltedAxis(thrust_axis_tilt_rad[i]);
  }
  g.radius_m = propeller_radius_m;
  return g;
}

namespace {
/// Largest thrust-axis tilt about either axis: ten degrees is a broken mount, not a tolerance.
constexpr double kMaxTilt_rad = 10.0 * model::kDegToRad;
}  // namespace

std::vector<model::FieldError> TruthParams::validate() const {
  std::vector<model::FieldError> errors;
  // Key paths in the shape of model::VehicleParams::validate.
  model::FieldChecker c(errors);
  using enum model::LowerBound;
  c.range("mass_kg", mass_kg, 0.0, 1000.0, kExclusive, "kg");

  // Inertia: finite, symmetric, positive definite, principal moments satisfying the triangle
  // inequalities (no rigid body has other moments).
  bool j_finite = true;
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      j_finite &= c.range("inertia_kgm2(" + std::to_string(r) + "," + std::to_string(k) + ")",
                          inertia_kgm2(r, k), -1000.0, 1000.0, kInclusive, "kg·m²");
    }
  }
  if (j_finite) {
    if (!inertia_kgm2.isApprox(inertia_kgm2.transpose(), 1e-12)) {
      c.fail("inertia_kgm2", "asymmetric", "a symmetric matrix");
    } else {
      const Eigen::Vector3d ev =
          Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia_kgm2).eigenvalues();
      if (!(ev.minCoeff() > 0.0)) {
        c.fail("inertia_kgm2", "smallest principal moment " + formatValue(ev.minCoeff()),
               "positive definite");
      } else if (ev[2] > (ev[0] + ev[1]) * (1.0 + 1e-9)) {
        c.fail("inertia_kgm2",
               "principal moments " + formatValue(ev[0]) + ", " + formatValue(ev[1]) + ", " +
                   formatValue(ev[2]),
               "the largest at most the sum of the other two");
      }
    }
  }

  c.componentsWithin("cog_offset_B", cog_offset_B, 1.0, "m");
  for (std::size_t i = 0; i < 4; ++i) {
    const std::string idx = "[" + std::to_string(i) + "]";
    c.componentsWithin("rotor_position_B" + idx, rotor_position_B[i], 10.0, "m");
    if (!(yaw_sign[i] == 1.0 || yaw_sign[i] == -1.0))
      c.fail("yaw_sign" + idx, formatValue(yaw_sign[i]), "+1 or -1");
    c.range("thrust_multiplier" + idx, thrust_multiplier[i], 0.5, 1.5, kInclusive,
            "(relative to k_T)");
    c.range("torque_multiplier" + idx, torque_multiplier[i], 0.5, 1.5, kInclusive,
            "(relative to k_I)");
    c.range("thrust_axis_tilt_rad" + idx + ".x", thrust_axis_tilt_rad[i].x(), -kMaxTilt_rad,
            kMaxTilt_rad, kInclusive, "rad");
    c.range("thrust_axis_tilt_rad" + idx + ".y", thrust_axis_tilt_rad[i].y(), -kMaxTilt_rad,
            kMaxTilt_rad, kInclusive, "rad");
  }
  c.range("propeller_radius_m", propeller_radius_m, 0.0, 5.0, kExclusive, "m");
  c.range("k_T_N_per_rpm2", k_T_N_per_rpm2, 0.0, 1.0, kExclusive, "N/rpm²");
  c.range("k_I_Nm_per_rpm2", k_I_Nm_per_rpm2, 0.0, 1.0, kInclusive, "N·m/rpm²");
  c.range("gravity_mps2", gravity_mps2, 0.0, 100.0, kInclusive, "m/s²");

  c.range("motor.time_constant_s", motor.time_constant_s, 0.0, 10.0, kExclusive, "s");
  c.range("motor.dead_time_s", motor.dead_time_s, 0.0, 1.0, kInclusive, "s");
  c.range("motor.J_R_kgm2", motor.J_R_kgm2, 0.0, 1.0, kInclusive, "kg·m²");
  const bool lo_ok =
      c.range("motor.min_speed_rpm", motor.min_speed_rpm, 0.0, 1e6, kInclusive, "rpm");
  const bool hi_ok =
      c.range("motor.max_speed_rpm", motor.max_speed_rpm, 0.0, 1e6, kExclusive, "rpm");
  if (lo_ok && hi_ok && !(motor.max_speed_rpm > motor.min_speed_rpm)) {
    c.fail("motor.max_speed_rpm", formatValue(motor.max_speed_rpm),
           "greater than motor.min_speed_rpm = " + formatValue(motor.min_speed_rpm));
  }
  const auto& t = motor.throttle;
  const bool c2_ok = c.range("motor.throttle.c2_rpm2", t.c2_rpm2, -1e12, 1e12, kInclusive, "rpm²");
  const bool c1_ok = c.range("motor.throttle.c1_rpm2", t.c1_rpm2, -1e12, 1e12, kInclusive, "rpm²");
  const bool c0_ok = c.range("motor.throttle.c0_rpm2", t.c0_rpm2, 0.0, 1e12, kInclusive, "rpm²");
  if (c2_ok && c1_ok && c0_ok && !(t.c1_rpm2 > 0.0 && t.c1_rpm2 + 2.0 * t.c2_rpm2 > 0.0)) {
    c.fail("motor.throttle", "c1=" + formatValue(t.c1_rpm2) + ", c2=" + formatValue(t.c2_rpm2),
           "n² strictly increasing on throttle [0, 1] (c1 > 0 and c1 + 2·c2 > 0)");
  }

  const auto& b = battery;
  const bool vf_ok =
      c.range("battery.full_voltage_V", b.full_voltage_V, 0.0, 1000.0, kExclusive, "V");
  const bool ve_ok =
      c.range("battery.empty_voltage_V", b.empty_voltage_V, 0.0, 1000.0, kExclusive, "V");
  if (vf_ok && ve_ok && !(b.empty_voltage_V < b.full_voltage_V)) {
    c.fail("battery.empty_voltage_V", formatValue(b.empty_voltage_V),
           "below battery.full_voltage_V = " + formatValue(b.full_voltage_V));
  }
  c.range("battery.nominal_voltage_V", b.nominal_voltage_V, 0.0, 1000.0, kExclusive, "V");
  c.range("battery.internal_resistance_ohm", b.internal_resistance_ohm, 0.0, 10.0, kInclusive, "Ω");
  const bool cap_ok = c.range("battery.capacity_Ah", b.capacity_Ah, 0.0, 1000.0, kExclusive, "A·h");
  if (cap_ok)
    c.range("battery.initial_charge_used_Ah", b.initial_charge_used_Ah, 0.0, b.capacity_Ah,
            kInclusive, "A·h");
  c.range("battery.efficiency", b.efficiency, 0.0, 1.0, kExclusive);
  c.range("battery.idle_current_A", b.idle_current_A, 0.0, 1000.0, kInclusive, "A");

  for (std::size_t i = 0; i < landing_feet_B.size(); ++i) {
    c.componentsWithin("landing_feet_B[" + std::to_string(i) + "]", landing_feet_B[i], 10.0, "m");
  }
  const LandingGearParams& g = landing_gear;
  c.range("landing_gear.stiffness_N_per_m", g.stiffness_N_per_m, 0.0, 1e8, kInclusive, "N/m");
  c.range("landing_gear.damping_ratio", g.damping_ratio, 0.0, 10.0, kInclusive);
  c.range("landing_gear.friction_coefficient", g.friction_coefficient, 0.0, 10.0, kInclusive);
  c.range("landing_gear.slip_speed_mps", g.slip_speed_mps, 0.0, 1.0, kExclusive, "m/s");
  c.range("landing_gear.max_compression_m", g.max_compression_m, 0.0, 1.0, kExclusive, "m");
  for (model::FieldError& e : aero.validate()) errors.push_back(std::move(e));  // "aero.…"
  return errors;
}

TruthParams fromNominal(const model::VehicleParams& nominal) {
  TruthParams p;
  p.mass_kg = nominal.mass_kg;
  p.inertia_kgm2 = nominal.inertia_kgm2.asDiagonal();
  p.rotor_position_B = model::Mixer::rotorPositions_B(nominal.diagonal_rotor_distance_m);
  const Eigen::Vector4d& yaw = model::Mixer::yawSigns();
  for (int i = 0; i < 4; ++i) p.yaw_sign[static_cast<std::size_t>(i)] = yaw[i];
  p.propeller_radius_m = nominal.propeller_radius_m;
  p.k_T_N_per_rpm2 = nominal.rotor.k_T_N_per_rpm2;
  p.k_I_Nm_per_rpm2 = nominal.rotor.k_I_Nm_per_rpm2;
  // The calibrated motor and aerodynamics, carried over to this vehicle by similarity (the
  // reference vehicle's own values for it, bit for bit).
  const SimilarityRatios similar = similarityToReference(nominal);
  p.motor = scaledMotor(MotorParams{}, similar);
  p.aero = scaledAero(RotorAeroParams{}, similar);
  p.motor.J_R_kgm2 = nominal.rotor.J_R_kgm2;
  p.motor.throttle = nominal.throttle;
  p.gravity_mps2 = model::kGravity;
  // Four feet under the arms, halfway out, at the lowest rotor-plane height: the landing gear
  // holds the rotor plane at min_rotor_plane_height_m above flat ground.
  for (const Eigen::Vector3d& r : p.rotor_position_B) {
    p.landing_feet_B.emplace_back(0.5 * r.x(), 0.5 * r.y(), -nominal.min_rotor_plane_height_m);
  }
  p.landing_gear.stiffness_N_per_m =
      nominal.mass_kg * model::kGravity /
      (static_cast<double>(p.landing_feet_B.size()) * kDefaultGearStaticDeflectionM);
  p.landing_gear.damping_ratio = kDefaultGearDampingRatio;
  p.landing_gear.friction_coefficient = kDefaultGearFrictionCoefficient;
  p.landing_gear.max_compression_m = kDefaultGearMaxCompressionM;
  return p;
}

TruthParams perturbed(const TruthParams& base, const MismatchSpec& spec, std::uint64_t seed) {
  // The engine and the mapping are specified bit for bit (sim/sampling.hpp), so the same seed
  // gives the same vehicle everywhere (std::uniform_real_distribution is not).
  NoiseSource rng = NoiseSource::fromEngineSeed(seed);
  const auto uniform = [&rng](double bound) { return bound * (2.0 * rng.uniformHalfOpen() - 1.0); };
  TruthParams p = base;
  p.mass_kg = base.mass_kg * (1.0 + uniform(spec.mass_rel));
  // Scale the principal moments in the inertia's own axes; clamp so that the triangle
  // inequality of a rigid body still holds.
  // The draws happen whatever the bounds, so that one seed gives the same mass whether or
  // not the inertia is perturbed too.
  Eigen::Vector3d factor;
  for (int k = 0; k < 3; ++k) factor[k] = 1.0 + uniform(spec.inertia_rel);
  if (spec.inertia_rel != 0.0) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(base.inertia_kgm2);
    Eigen::Vector3d ev = es.eigenvalues().cwiseProduct(factor);
    if (ev[2] > ev[0] + ev[1]) ev[2] = ev[0] + ev[1];
    if (ev[1] > ev[0] + ev[2]) ev[1] = ev[0] + ev[2];
    if (ev[0] > ev[1] + ev[2]) ev[0] = ev[1] + ev[2];
    const Eigen::Matrix3d J = es.eigenvectors() * ev.asDiagonal() * es.eigenvectors().transpose();
    p.inertia_kgm2 = 0.5 * (J + J.transpose());
  }
  p.cog_offset_B =
      base.cog_offset_B + Eigen::Vector3d(uniform(spec.cog_offset_m), uniform(spec.cog_offset_m),
                                          uniform(spec.cog_offset_z_m));
  for (std::size_t i = 0; i < 4; ++i) {
    const double f = 1.0 + uniform(spec.thrust_spread_rel);
    p.thrust_multiplier[i] *= f;
    p.torque_multiplier[i] *= f;
  }
  return p;
}

}  // namespace geaware::sim
