// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The simulator's default aerodynamics, motor ceiling, motor lag and near-ground turbulence were
// calibrated on one vehicle, the paper's quadrotor (config/vehicles/paper_quad.yaml). The ideal
// world of any other vehicle file carries them over by geometric similarity (docs/truth-file.md,
// "The ideal world of another vehicle"), as config/truths/quad5_as_built.yaml does by hand:
// lengths with the propeller radius R, slopes per metre against it, per-rotor drag per rpm with
// R³ (the H-force of similar blades ∝ ρ·n·R³), forces with the weight, torques with weight × arm,
// the induced velocity by momentum theory (∝ √(T/A)) at the hover speed, the motor time
// constant with √R (Froude scaling, docs/controller-params.md rule 4), the speed ceiling with
// the throttle curve's top speed. For the reference vehicle itself every ratio is exactly 1 and
// every value is the calibrated one, bit for bit.

#include "geaware/model/vehicle_params.hpp"
#include "geaware/sim/disturbances.hpp"
#include "geaware/sim/rotor_aerodynamics.hpp"
#include "geaware/sim/truth_params.hpp"

namespace geaware::sim {

/// The reference vehicle's values the ratios are taken against (config/vehicles/paper_quad.yaml;
/// a test checks that they are the built-in vehicle's).
struct ReferenceVehicle {
  static constexpr double kMassKg = 1.696;                         ///< [kg]
  static constexpr double kPropellerRadiusM = 0.089;               ///< [m]
  static constexpr double kDiagonalRotorDistanceM = 0.35;          ///< [m]
  static constexpr double kThrustCoefficientNPerRpm2 = 4.0083e-8;  ///< k_T [N/rpm²]
  static constexpr double kThrottleC2Rpm2 = -1.448471e8;           ///< [rpm²]
  static constexpr double kThrottleC1Rpm2 = 5.228928e8;            ///< [rpm²]
  static constexpr double kThrottleC0Rpm2 = 1.033111e7;            ///< [rpm²]
};

/// A vehicle against the reference vehicle: each ratio is the vehicle's value over the
/// reference's (1 for the reference itself, exactly).
struct SimilarityRatios {
  double length = 1.0;       ///< propeller radius R / R_ref [-]
  double mass = 1.0;         ///< m / m_ref [-]
  double arm = 1.0;          ///< diagonal rotor distance / the reference's [-]
  double hover_speed = 1.0;  ///< √(m·g/(4·k_T)) / the reference's [-]
  double top_speed = 1.0;    ///< the throttle curve's full-throttle speed / the reference's [-]
  /// The induced velocity in hover, √(T/(2ρA)) ∝ √m / R, over the reference's [-].
  [[nodiscard]] double inducedVelocity() const noexcept;
};

/// `vehicle` (validated) against the reference vehicle.
[[nodiscard]] SimilarityRatios similarityToReference(const model::VehicleParams& vehicle) noexcept;

/// The calibrated aerodynamics `reference` carried over to a vehicle with ratios `r`: lengths
/// × r.length, slopes per metre ÷ r.length, per-rotor drag per rpm × r.length³, the induced
/// velocity × r.inducedVelocity() at the reference speed × r.hover_speed; dimensionless
/// coefficients and the air unchanged.
[[nodiscard]] RotorAeroParams scaledAero(const RotorAeroParams& reference,
                                         const SimilarityRatios& r) noexcept;

/// The near-ground turbulence `reference` carried over: forces × r.mass (the weight), torques
/// × r.mass·r.arm, heights × r.length, the correlation time (≈ D/v_i) × r.length /
/// r.inducedVelocity(); the per-rotor law's relative κ and correlation unchanged.
[[nodiscard]] GroundTurbulenceParams scaledGroundTurbulence(const GroundTurbulenceParams& reference,
                                                            const SimilarityRatios& r) noexcept;

/// The motor `reference` carried over: the speed ceiling × r.top_speed, the time constant
/// × √r.length; the throttle curve and J_R are the vehicle's (set by fromNominal).
[[nodiscard]] MotorParams scaledMotor(const MotorParams& reference,
                                      const SimilarityRatios& r) noexcept;

}  // namespace geaware::sim
