// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Truth-side per-rotor aerodynamics: thrust, reaction torque and rotor drag of each rotor with
// ground effect from that rotor's own distance to the surface below it. This is NOT the
// controller's model (model/ground_effect.hpp): the leveling torque here emerges from per-rotor
// thrust differences. Design, sources and calibration: docs/sim-aerodynamics.md.
//
// Per rotor i, at distance z_i to the surface below it (vertical, as the caller measures it):
//   φ_i   = max(0, C(z̄) + l̄ + sat_M((1 + μ)·(l_i − l̄)))  additional-thrust fraction
//   T_i   = k_T,i·n_i² + fade_i·φ_i·[β·k_T,i·n_i² + (1 − β)·mean_j k_T,j·n_j²]
//   Q_i   = spin_i·k_I,i·n_i²·(1 − κ_Q·fade_i·φ_i)
//   f_D,i = −diag(c_x·q_x(z_i), c_y·q_y(z_i))·n_i·v_inplane,i
// with C the collective (vehicle-scale) cushion of Sanchez-Cuevas et al. 2017 at the mean rotor
// distance z̄, l the rotor-resolved impingement law (Cheeseman–Bennett image + slipstream
// impingement below the wake-merge height, times a recirculation factor, held at its peak
// below z* ≈ 0.083 m so that the lower rotor's gain saturates),
// sat_M a bounded redistribution with M = m·z̄, fade_i = v_i²/(v_i² + |v_inplane,i|²)
// (Cheeseman–Bennett's forward-flight correction). Every symbol is a field below.
//
// As-built extensions (docs/world.md), each off by default: the plant uses s·φ_i
// (in_flight_cushion_scale, flightFactors(); the rigs use φ_i), the free-air term k_T,i·n_i²
// gains 1 + min(c·|v_inplane,i|², max) (translational lift), and a rotor whose thrust axis a_i
// is tilted (RotorGeometry::thrust_axis_B) puts T_i and Q_i along a_i instead of z_B.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <vector>

#include "geaware/model/field_error.hpp"
#include "geaware/sim/wrench.hpp"

namespace geaware::sim {

/// Which law gives each rotor's additional-thrust fraction φ_i (docs/sim-aerodynamics.md,
/// "Other law families"). Only kCalibrated reproduces the paper's platform measurements; the
/// others are textbook closed forms for the robustness campaign (docs/robustness.md).
enum class GroundEffectLaw {
  /// Collective cushion + rotor-resolved impingement + suck-down (the calibrated default).
  kCalibrated,
  /// Per rotor, Cheeseman & Bennett 1955: φ_i = 1/(1 − (R/4z_i)²) − 1 at z_i ≥ R/2.
  kCheesemanBennett,
  /// Per rotor, Sanchez-Cuevas, Heredia & Ollero 2017 (neighbour images and the body term
  /// K_b = body_coefficient), each rotor at its own distance z_i ≥ R/2.
  kSanchezCuevas,
};

/// "calibrated", "cheeseman_bennett", "sanchez_cuevas".
[[nodiscard]] const char* toString(GroundEffectLaw law) noexcept;

/// The closed-form laws are evaluated at max(z, kClosedFormMinHeightOverRadius·R): both have a
/// pole (Cheeseman–Bennett's at z = R/4) and are used above z/R = 0.5, where Cheeseman–Bennett
/// gives T_IGE/T_OGE = 4/3 [-].
inline constexpr double kClosedFormMinHeightOverRadius = 0.5;

/// Parameters of the truth aerodynamics (defaults: calibrated to the paper's measurements for
/// its quadrotor; `geaware rig calibrate` checks them, docs/sim-aerodynamics.md explains them).
struct RotorAeroParams {
  /// The law family of φ_i. With a closed form, φ_i comes from that law alone (the collective,
  /// rotor-resolved and suck-down fields below are not used) and each rotor's increment scales
  /// with its own thrust (β = 1); the fade, reaction torque, drag and in-flight fields apply
  /// as with the calibrated law.
  GroundEffectLaw law = GroundEffectLaw::kCalibrated;

  // --- Collective cushion (vehicle scale, no torque), Sanchez-Cuevas et al. 2017 -------------
  /// Body coefficient K_b of the Sanchez-Cuevas multirotor law (their fuselage term) [-].
  double body_coefficient = 2.177;

  // --- Rotor-resolved impingement (per rotor, makes the leveling torque) ----------------------
  /// Core radius of the regularised Cheeseman–Bennett image term (R/4)²/(z² + (c·R)²), as a
  /// fraction c of the propeller radius; keeps the law finite at z → 0 [-].
  double image_core_fraction = 0.25;
  /// Slope of the slipstream-impingement term below the wake-merge height [1/m].
  double impingement_slope_per_m = 0.2449;
  /// Height below which a rotor's own slipstream still reaches the surface as a separate jet
  /// (above it the four slipstreams have merged) [m].
  double wake_merge_height_m = 0.3053;
  /// Rounding of the impingement ramp at the merge height [m].
  double wake_merge_softness_m = 0.003;
  /// Recirculation height z_r: the rotor-resolved term carries the factor 1/(1 + (z_r/z)⁴) and
  /// is held at its maximum below the height z* where it peaks (the lower rotor's gain
  /// saturates instead of growing; z* ≈ 0.083 m with the defaults) [m].
  double recirculation_height_m = 0.06741;
  /// Suck-down amplification μ of the rotor-resolved differences (zero-sum over the rotors) [-].
  double suckdown_gain = 2.994;
  /// Bound on each rotor's redistributed share, M = m·z̄ (z̄ the mean rotor distance) [1/m].
  double redistribution_cap_per_m = 0.3432;

  // --- How the increment is applied ------------------------------------------------------------
  /// Fraction β of a rotor's ground-effect increment that scales with its own n²; the rest
  /// scales with the mean rotor thrust (the cushion is fed by all wakes) [-].
  double own_thrust_fraction = 0.2;
  /// Relative reduction κ_Q of the reaction torque per unit additional-thrust fraction [-].
  double reaction_torque_reduction = 0.1;
  /// Beyond this distance (and for non-finite distances) a rotor sees no surface; the thrust
  /// laws are tapered by 1 − (z/range)⁴ to reach zero there smoothly [m].
  double ground_effect_range_m = 3.0;
  /// Distances below this are clamped to it (a rotor touching the surface) [m].
  double min_ground_distance_m = 0.01;

  // --- Forward-flight fade -----------------------------------------------------------------------
  /// Induced velocity v_i at the reference rotor speed (docs/paper-facts.md: ≈ 4 m/s) [m/s].
  double induced_velocity_mps = 4.0;
  /// Rotor speed at which `induced_velocity_mps` holds; v_i scales with n (momentum theory) [rpm].
  double induced_velocity_ref_rpm = 10179.0;

  // --- In flight only (the plant; the virtual rigs never apply these) --------------------------
  /// Scale s of the additional-thrust fraction in flight, φ_i → s·φ_i, applied by
  /// flightFactors() (the plant) and never by groundFactors() (the rigs): a hovering vehicle's
  /// cushion is weaker than a clamped platform's (docs/world.md) [-].
  double in_flight_cushion_scale = 1.0;
  /// Translational lift c: each rotor's free-air thrust gains 1 + min(c·v_h², max), v_h its
  /// in-plane air speed (docs/world.md) [1/(m/s)²].
  double translational_lift_per_mps2 = 0.0;
  /// Upper bound of the translational-lift gain [-].
  double translational_lift_max = 0.05;
  /// Airframe drag area C_d·A: F = −½·ρ·C_dA·|v_air|·v_air at the CoM (the plant) [m²].
  double airframe_drag_area_m2 = 0.0;
  /// Air density ρ for the airframe drag [kg/m³].
  double air_density_kg_per_m3 = 1.225;

  // --- Rotor drag --------------------------------------------------------------------------------
  /// Per-rotor drag along body x per rpm, out of ground effect [N/(m/s)/rpm].
  double drag_x_N_per_mps_per_rpm = 9.8078e-6;
  /// Per-rotor drag along body y per rpm, out of ground effect [N/(m/s)/rpm].
  double drag_y_N_per_mps_per_rpm = 8.1490e-6;
  /// Near-ground drag reduction a_x in q_x(z) = 1 − a_x/(1 + (z/z_q)²) [-].
  double drag_ground_reduction_x = 0.37798;
  /// Near-ground drag reduction a_y in q_y(z) = 1 − a_y/(1 + (z/z_q)²) [-].
  double drag_ground_reduction_y = 0.34928;
  /// Range z_q of the near-ground drag reduction [m].
  double drag_ground_height_m = 0.25;

  /// Every field that is not finite or out of its physical range (key paths "aero.<field>").
  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

/// What each rotor sees of the surface below it, computed by the caller from the terrain.
struct RotorSurroundings {
  /// Rotor-disc centre to the surface below, along −z_W [m]; ∞ (or NaN): no surface.
  std::array<double, 4> ground_distance_m{};
  /// Unit upward normal of that surface (not used: the truth is calibrated on vertical
  /// distances, see docs/sim-aerodynamics.md).
  std::array<Eigen::Vector3d, 4> ground_normal_W{};
};

/// The rotors as built (truth side: may differ from the controller's nominal vehicle).
struct RotorGeometry {
  /// Rotor-disc centres relative to the CoM, body frame [m].
  std::array<Eigen::Vector3d, 4> position_B{};
  /// Reaction-torque sign about z_B (the mixer's yaw row).
  std::array<double, 4> spin{};
  /// Per-rotor thrust coefficient, out of ground effect [N/rpm²].
  std::array<double, 4> k_T_N_per_rpm2{};
  /// Per-rotor aerodynamic torque coefficient [N·m/rpm²].
  std::array<double, 4> k_I_Nm_per_rpm2{};
  /// Per-rotor unit thrust axis, body frame (thrust and reaction torque act along it; the rotor
  /// drag stays in the body x–y plane). Default z_B [-].
  std::array<Eigen::Vector3d, 4> thrust_axis_B{Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ(),
                                               Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()};
  /// Propeller radius [m].
  double radius_m = 0.0;
};

/// The distance-dependent factors of the four rotors at one instant: everything compute() takes
/// from the surroundings. They change only with the rotor heights (about a millimetre per step at
/// 1 kHz), so the plant evaluates them once per step and holds them over the RK4 stages
/// (docs/sim-aerodynamics.md, "Performance"); compute(…, surroundings) evaluates them every call.
struct RotorGroundFactors {
  std::array<double, 4> phi{};           ///< static additional-thrust fraction φ_i [-]
  std::array<double, 4> drag_scale_x{};  ///< near-ground drag factor q_x(z_i) ∈ (0, 1] [-]
  std::array<double, 4> drag_scale_y{};  ///< near-ground drag factor q_y(z_i) ∈ (0, 1] [-]
};

/// Per-rotor outputs, for logging and the rigs.
struct RotorAeroOutput {
  Wrench wrench;                     ///< sum over rotors, body frame, about the CoM
  std::array<double, 4> thrust_N{};  ///< each rotor's thrust including ground effect [N]
  std::array<double, 4> gain{};      ///< each rotor's thrust ratio T/T_free [-]
};

class RotorAerodynamics {
 public:
  /// Throws std::invalid_argument listing the offending fields when `params` fail validate()
  /// or the geometry is not usable (non-finite, radius ≤ 0, rotors on top of each other).
  RotorAerodynamics(const RotorGeometry& geometry, const RotorAeroParams& params);

  /// Aerodynamic wrench of the four rotors: thrust with per-rotor ground effect (faded by
  /// forward speed), aerodynamic reaction torque, rotor drag. `v_air_W` is the velocity of the
  /// CoM relative to the air (wind subtracted), `w_B` the body rates. No allocation.
  [[nodiscard]] RotorAeroOutput compute(const std::array<double, 4>& n_rpm,
                                        const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& v_air_W,
                                        const Eigen::Vector3d& w_B,
                                        const RotorSurroundings& surroundings) const noexcept;

  /// The same from factors evaluated earlier by groundFactors() (the plant holds them over a
  /// step). compute(…, s) is compute(…, groundFactors(s.ground_distance_m)). No allocation.
  [[nodiscard]] RotorAeroOutput compute(const std::array<double, 4>& n_rpm,
                                        const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& v_air_W,
                                        const Eigen::Vector3d& w_B,
                                        const RotorGroundFactors& factors) const noexcept;

  /// compute(…, factors).wrench without the per-rotor outputs (the plant's RK4 stages).
  [[nodiscard]] Wrench wrench(const std::array<double, 4>& n_rpm, const Eigen::Matrix3d& R_WB,
                              const Eigen::Vector3d& v_air_W, const Eigen::Vector3d& w_B,
                              const RotorGroundFactors& factors) const noexcept;

  /// Static additional-thrust fraction φ_i of each rotor (no forward-speed fade) for the given
  /// distances [-]: the rigs and the calibration read it; compute() uses the same function.
  [[nodiscard]] std::array<double, 4> additionalThrustFraction(
      const std::array<double, 4>& ground_distance_m) const noexcept;

  /// φ_i and the near-ground drag factors q_x, q_y of each rotor for the given distances (the
  /// rigs' cushion).
  [[nodiscard]] RotorGroundFactors groundFactors(
      const std::array<double, 4>& ground_distance_m) const noexcept;

  /// groundFactors() with φ_i scaled by in_flight_cushion_scale: the cushion in flight (the
  /// plant). Identical to groundFactors() for the default scale 1.
  [[nodiscard]] RotorGroundFactors flightFactors(
      const std::array<double, 4>& ground_distance_m) const noexcept {
    RotorGroundFactors f = groundFactors(ground_distance_m);
    if (params_.in_flight_cushion_scale != 1.0) {
      for (double& phi : f.phi) phi *= params_.in_flight_cushion_scale;
    }
    return f;
  }

  /// Translational-lift gain 1 + min(c·v_h², max) for an in-plane air speed v_h [-].
  [[nodiscard]] double translationalLiftGain(double v_inplane_mps) const noexcept {
    return 1.0 + std::min(params_.translational_lift_per_mps2 * v_inplane_mps * v_inplane_mps,
                          params_.translational_lift_max);
  }

  [[nodiscard]] const RotorGeometry& geometry() const noexcept { return geometry_; }
  /// Height below which each rotor's rotor-resolved gain is held at its maximum [m].
  [[nodiscard]] double saturationHeight() const noexcept { return z_star_; }
  [[nodiscard]] const RotorAeroParams& params() const noexcept { return params_; }

 private:
  /// compute() and wrench(): the per-rotor outputs go to *per_rotor when kPerRotor.
  template <bool kPerRotor>
  [[nodiscard]] Wrench evaluate(const std::array<double, 4>& n_rpm, const Eigen::Matrix3d& R_WB,
                                const Eigen::Vector3d& v_air_W, const Eigen::Vector3d& w_B,
                                const RotorGroundFactors& factors,
                                RotorAeroOutput* per_rotor) const noexcept;
  /// The wrench of rotors with tilted thrust axes (evaluate()'s last step when tilted_).
  [[nodiscard]] Wrench tiltedWrench(const Eigen::Array4d& thrust, const Eigen::Array4d& f_x,
                                    const Eigen::Array4d& f_y,
                                    const Eigen::Array4d& q) const noexcept;
  [[nodiscard]] double collective(double z_mean) const noexcept;
  /// groundFactors() for the closed-form law families (params_.law != kCalibrated).
  [[nodiscard]] RotorGroundFactors closedFormFactors(
      const std::array<double, 4>& ground_distance_m) const noexcept;
  /// φ of one rotor at distance z (already clamped) under a closed-form law [-].
  [[nodiscard]] double closedFormFraction(double z) const noexcept;
  /// The rotor-resolved law l(z) = num/den of four distances at once (one SIMD lane per rotor).
  void rotorResolvedTerms(const Eigen::Array4d& z, Eigen::Array4d& num,
                          Eigen::Array4d& den) const noexcept;
  [[nodiscard]] Eigen::Array4d rotorResolvedRaw(const Eigen::Array4d& z) const noexcept;
  [[nodiscard]] double rotorResolvedRaw(double z) const noexcept {
    return rotorResolvedRaw(Eigen::Array4d::Constant(z))[0];
  }

  RotorGeometry geometry_;
  RotorAeroParams params_;
  // The rotors in structure-of-arrays form, one lane per rotor (compute() runs on all four at
  // once): positions relative to the CoM, k_T and spin·k_I.
  Eigen::Array4d r_x_ = Eigen::Array4d::Zero();
  Eigen::Array4d r_y_ = Eigen::Array4d::Zero();
  Eigen::Array4d r_z_ = Eigen::Array4d::Zero();
  Eigen::Array4d k_T_ = Eigen::Array4d::Zero();
  Eigen::Array4d spin_k_I_ = Eigen::Array4d::Zero();
  // Thrust axes (used only when tilted_: some axis is not exactly z_B).
  Eigen::Array4d a_x_ = Eigen::Array4d::Zero();
  Eigen::Array4d a_y_ = Eigen::Array4d::Zero();
  Eigen::Array4d a_z_ = Eigen::Array4d::Ones();
  bool tilted_ = false;
  bool lift_ = false;  // translational lift on (c > 0)
  double beta_ = 0.0;  // share of the increment on the rotor's own n² (1 for closed forms)
  double inv_range_ = 0.0;  // 1/ground_effect_range_m
  // Precomputed from the geometry and the parameters.
  double image_num_ = 0.0;      // (R/4)²
  double image_core_sq_ = 0.0;  // (c·R)²
  double adjacent_sq_ = 0.0;    // d², adjacent rotor spacing squared
  double diagonal_sq_ = 0.0;    // 2·d²
  double arm_sq_ = 0.0;         // rotor-to-centre distance squared
  double radius_sq_ = 0.0;      // R²
  double merge_soft_sq_ = 0.0;
  double recirc_sq_ = 0.0;  // z_r²
  double inv_drag_height_sq_ = 0.0;
  double vi_per_rpm_ = 0.0;  // induced velocity per rpm [m/s/rpm]
  double z_star_ = 0.0;      // height below which the rotor-resolved term is held [m]
};

}  // namespace geaware::sim
