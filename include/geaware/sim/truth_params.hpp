// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The vehicle as it really is: the simulator's "truth", which may differ from the nominal
// vehicle the controller believes in (model::VehicleParams). Mass, inertia, centre of gravity,
// per-motor thrust spread, motors, ESC and battery. Only sim/ reads it.
//
// Frames: body frame x forward, y left, z up, origin at the GEOMETRIC centre of the vehicle
// (the centre of the rotor plane, where model::Mixer puts its rotor positions). The centre of
// mass sits at `cog_offset_B` from it.

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "geaware/model/vehicle_params.hpp"
#include "geaware/sim/ground_contact.hpp"
#include "geaware/sim/rotor_aerodynamics.hpp"

namespace geaware::sim {

/// Battery and its influence on the ESC. The ESC curve was identified "after removing the
/// battery-voltage influence" (docs/paper-facts.md, supplementary section 3), i.e. it holds at
/// the nominal voltage. An ESC drives the motor with a duty cycle; the motor's back-EMF speed is
/// proportional to the applied voltage, so the steady speed scales with V/V_nom and
///   n_ss² = (c2·t² + c1·t + c0) · (V/V_nom)².
/// The battery is a linear open-circuit voltage (V_full at full charge down to V_empty at the
/// rated capacity) behind an internal resistance:
///   V = V_oc(Q_used) − R_int·I,   I = I_idle + Σ_i P_mech,i / (η·V),   P_mech,i = k_I·n_i²·Ω_i.
/// I is evaluated once per step from the speeds at the start of the step (explicit; the
/// electrical time constants are far below 1 ms).
struct BatteryParams {
  bool enabled = true;              ///< false: V ≡ V_nom, the curve holds exactly
  double full_voltage_V = 16.8;     ///< open-circuit voltage when full (4S LiPo, 4.2 V/cell) [V]
  double empty_voltage_V = 14.0;    ///< open-circuit voltage at rated capacity (3.5 V/cell) [V]
  double nominal_voltage_V = 16.0;  ///< voltage at which the ESC curve holds [V]
  double internal_resistance_ohm = 0.025;  ///< pack + wiring resistance [Ω]
  double capacity_Ah = 3.0;                ///< rated capacity [A·h]
  double initial_charge_used_Ah = 0.0;     ///< charge already drawn at t = 0 [A·h]
  double efficiency = 0.75;     ///< motor + ESC efficiency, mechanical/electrical power [-]
  double idle_current_A = 0.5;  ///< flight controller, receiver, ranger… [A]
};

/// Motor/ESC truth. Rotor speed follows a first-order lag toward the ESC's steady speed.
struct MotorParams {
  /// ESC/link dead time: a throttle command reaches the motors this much later (companion
  /// computer → flight controller → DShot; docs/world.md). 0: at once (today) [s].
  double dead_time_s = 0.0;
  double time_constant_s = 0.03;  ///< first-order speed time constant τ [s] (7-inch, ~30 ms)
  double min_speed_rpm = 0.0;     ///< hard speed floor (0: motor may stop) [rpm]
  double max_speed_rpm =
      21000.0;            ///< hard speed ceiling (above the curve's 19,708 rpm at 16.8 V) [rpm]
  double J_R_kgm2 = 0.0;  ///< rotor + bell inertia about the spin axis [kg·m²]
  model::ThrottleCurveParams throttle;  ///< ESC curve n² = c2·t²+c1·t+c0 at nominal voltage [rpm²]
};

/// How far a perturbed truth vehicle may differ from its nominal one. Every quantity is drawn
/// uniformly in ±its bound (seeded), independently.
struct MismatchSpec {
  double mass_rel = 0.0;           ///< relative mass error bound, e.g. 0.05 = ±5 % [-]
  double inertia_rel = 0.0;        ///< relative error bound on each principal moment [-]
  double cog_offset_m = 0.0;       ///< bound on each of the CoG offset's x, y components [m]
  double cog_offset_z_m = 0.0;     ///< bound on the CoG offset's z component [m]
  double thrust_spread_rel = 0.0;  ///< bound on each motor's thrust multiplier − 1 [-]
};

struct TruthParams {
  double mass_kg = 0.0;  ///< flying mass [kg]
  Eigen::Matrix3d inertia_kgm2 =
      Eigen::Matrix3d::Zero();  ///< inertia about the CoM, body axes [kg·m²]
  Eigen::Vector3d cog_offset_B =
      Eigen::Vector3d::Zero();  ///< CoM relative to the geometric centre, body [m]
  std::array<Eigen::Vector3d, 4>
      rotor_position_B{};  ///< rotor-disc centres rel. geometric centre, body, mixer order [m]
  std::array<double, 4>
      yaw_sign{};                   ///< reaction-torque sign about z_B (model::Mixer::yawSigns) [-]
  double propeller_radius_m = 0.0;  ///< [m]
  double k_T_N_per_rpm2 = 0.0;      ///< nominal thrust coefficient, out of ground effect [N/rpm²]
  double k_I_Nm_per_rpm2 = 0.0;     ///< nominal aerodynamic torque coefficient [N·m/rpm²]
  std::array<double, 4> thrust_multiplier{1.0, 1.0, 1.0,
                                          1.0};  ///< per-motor k_T scale (spread) [-]
  std::array<double, 4> torque_multiplier{1.0, 1.0, 1.0,
                                          1.0};  ///< per-motor k_I scale (spread) [-]
  /// Each rotor's thrust-axis misalignment: the axis is z_B tilted about body x by [0], then
  /// about body y by [1] (motor mounts, arm flex). Thrust and reaction torque act along it [rad].
  std::array<Eigen::Vector2d, 4> thrust_axis_tilt_rad{Eigen::Vector2d::Zero(),
                                                      Eigen::Vector2d::Zero(),
                                                      Eigen::Vector2d::Zero(),
                                                      Eigen::Vector2d::Zero()};
  MotorParams motor;
  BatteryParams battery;
  std::vector<Eigen::Vector3d>
      landing_feet_B;          ///< foot contact points rel. geometric centre, body [m]
  /// The legs under those feet, used when the flight allows ground contact
  /// (PlantConfig::ground_contact); otherwise a foot under the surface is a strike.
  LandingGearParams landing_gear;
  RotorAeroParams aero;        ///< truth aerodynamics (defaults: calibrated)
  double gravity_mps2 = 9.81;  ///< [m/s²] (model::kGravity)

  /// The rotor geometry the aerodynamics needs: positions relative to the CoM, per-rotor
  /// coefficients with the k_T and k_I spreads applied, the tilted thrust axes.
  [[nodiscard]] RotorGeometry rotorGeometry() const;

  /// Every field that is not finite or not in its physical range, with its value and what was
  /// expected (key paths as in model::VehicleParams::validate). Empty when usable.
  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

/// The unit thrust axis of a rotor whose mount is tilted about body x by tilt.x(), then about
/// body y by tilt.y() [rad]: R_y·R_x·z_B (exactly z_B for no tilt).
[[nodiscard]] Eigen::Vector3d tiltedAxis(const Eigen::Vector2d& tilt_rad) noexcept;

/// The truth identical to the nominal vehicle: no CoG offset, no thrust spread, the nominal
/// curve and coefficients, battery at full charge, four landing feet under the rotor arms at
/// the vehicle's lowest rotor-plane height, and legs with the representative gear of
/// kDefaultGear* below. Requires validated nominal parameters.
/// The default landing gear (docs/truth-file.md, "Landing gear"): NOT measured on the paper's
/// vehicle, which never lands in the paper. Legs that sag this far under the vehicle's weight
/// (stiffness m·g/(N·δ_s)) [m], their damping ratio (a level drop then rebounds with
/// restitution 0.45) [-], rubber feet on a hard floor [-], and how far a leg can give before
/// it breaks or bottoms out [m].
inline constexpr double kDefaultGearStaticDeflectionM = 0.003;
inline constexpr double kDefaultGearDampingRatio = 0.3;
inline constexpr double kDefaultGearFrictionCoefficient = 0.6;
inline constexpr double kDefaultGearMaxCompressionM = 0.02;

[[nodiscard]] TruthParams fromNominal(const model::VehicleParams& nominal);

/// A seeded random variation of `base` within `spec` (mass, inertia, CoG, thrust spread; a
/// motor's k_I moves with its k_T by the same factor, as a different propeller's would).
/// The same seed always gives the same vehicle. Inertia stays a valid rigid-body inertia.
[[nodiscard]] TruthParams perturbed(const TruthParams& base, const MismatchSpec& spec,
                                    std::uint64_t seed);

}  // namespace geaware::sim
