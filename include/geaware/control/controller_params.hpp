// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Parameters of the ground-effect-aware controller (paper section "Model-based Controller with
// Incremental Inversion"). Defaults: the paper's gains (docs/paper-facts.md).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "geaware/control/ground_effect_learner.hpp"
#include "geaware/control/leveling_learner.hpp"
#include "geaware/model/field_error.hpp"

namespace geaware::control {

/// Acceleration (force) compensation: what feeds the position loop besides PD feedback.
enum class AccelerationCompensation {
  kNone,    ///< flatness with high-altitude drag only (Faessler et al. 2018)
  kIndi,    ///< incremental inversion of the filtered measured acceleration (Tal & Karaman 2020)
  kNeural,  ///< learned residual force (Neural-Lander, Shi et al. 2019)
  kModel,   ///< the paper's feed-forward of D(h) and F_G(h)
};

/// Torque compensation: how the body torque command is formed.
enum class TorqueCompensation {
  kNone,       ///< τ = J·ω̇_des + ω_des × J·ω_des
  kModel,      ///< J'(h) in place of J
  kIndi,       ///< τ = τ̂_B + J·(ω̇_des − ω̇_f) (Tal & Karaman 2020)
  kModelIndi,  ///< τ = τ̂_B + J'(h)·(ω̇_des − ω̇_f) (the paper, eq. 33)
};

[[nodiscard]] const char* toString(AccelerationCompensation c) noexcept;
[[nodiscard]] const char* toString(TorqueCompensation c) noexcept;
/// Parses "none", "indi", "neural", "model"; false when unknown.
[[nodiscard]] bool parse(const std::string& text, AccelerationCompensation& out) noexcept;
/// Parses "none", "model", "indi", "model_indi"; false when unknown.
[[nodiscard]] bool parse(const std::string& text, TorqueCompensation& out) noexcept;

/// F_G learned in flight (control/ground_effect_learner.hpp, issue 13 item 3), starting from…
enum class GroundEffectLearning {
  kOff,          ///< the vehicle file's F_G, fixed (the paper)
  kFromVehicle,  ///< the vehicle file's F_G at the knots (configuration suffix "+learn")
  kFromNothing,  ///< no ground effect at all: a user without a force platform ("+learn0")
};

/// The height at which the ground-effect models (F_G, D(h), J'(h)) are evaluated.
enum class GroundEffectHeight {
  kReference,  ///< the reference's height above the ground the ranger sees (a feed-forward)
  kMeasured,   ///< the measured height (makes F_G's slope a height feedback)
};

struct ControllerParams {
  AccelerationCompensation acceleration = AccelerationCompensation::kModel;
  TorqueCompensation torque = TorqueCompensation::kModelIndi;

  Eigen::Vector3d k_p_per_s2 = {3.0, 3.0, 3.0};     ///< K^P, position gain [1/s²]
  Eigen::Vector3d k_v_per_s = {2.5, 2.5, 2.5};      ///< K^V, velocity gain [1/s]
  Eigen::Vector3d k_xi_per_s = {6.0, 6.0, 2.0};     ///< K^ξ, attitude gain [1/s]
  Eigen::Vector3d k_w_per_s = {15.0, 15.0, 16.0};   ///< K^ω, body-rate gain [1/s]

  double rate_hz = 200.0;             ///< controller update rate [Hz] (IMU rate in the paper)
  double filter_cutoff_hz = 30.0;     ///< shared low-pass of ω̇_f, τ̂_B, a_f and the INDI thrust [Hz]
  double max_tilt_rad = 0.7;          ///< limit on the commanded tilt [rad]
  double thrust_pi_kp = 0.01;         ///< K_P^T of the shared throttle correction [1/(m/s²)]
  double thrust_pi_ki = 0.05;         ///< K_I^T [1/(m/s²·s)]
  double thrust_pi_limit = 0.1;       ///< bound on the integral term and on t_E [throttle]
  int neural_iterations = 2;          ///< fixed-point iterations of the Neural-Lander thrust [-]
  /// Account for the rotor-inertia yaw torque J_R·ṅ (in τ̂_B and by lagging the yaw command).
  /// Off only to reproduce a controller that ignores it.
  bool compensate_rotor_inertia = true;
  /// Where the ground-effect models are evaluated; the paper predicts the force "under the
  /// desired state". kMeasured only to reproduce a controller that uses the ranger height.
  GroundEffectHeight ground_effect_height = GroundEffectHeight::kReference;

  // geaware's additions in translation (docs/controller.md). Each default switches it off, which
  // is the paper's controller exactly; recommendedControllerParams() switches them on.

  /// τ_d, time constant of the first-order low-pass on the disturbance observer's residual (its
  /// ã_ext minus the model's F_G and D(h) at the measured height), fed forward in the
  /// acceleration command; 0: off. Acceleration `model` or `none` only [s].
  double dob_time_constant_s = 0.0;
  double dob_limit_mps2 = 3.0;  ///< bound on each component of the fed-forward residual [m/s²]
  /// K^I, gain on the integral of the position error; 0: off. Below K^P·K^V per axis [1/s³].
  Eigen::Vector3d k_i_per_s3 = Eigen::Vector3d::Zero();
  /// Anti-windup: bound on each component of K^I·∫e_p; the integral is also held while a
  /// saturation (tilt, thrust, the clearance guard) acts in the direction it would grow [m/s²].
  double integral_limit_mps2 = 1.0;
  /// Clearance guard: the commanded height and vertical acceleration never take the rotor plane
  /// below the landing gear's height (VehicleParams::min_rotor_plane_height_m) plus the margin.
  bool clearance_guard = false;
  double guard_margin_m = 0.01;   ///< clearance kept above the landing gear's height [m]
  /// a_b, the upward acceleration the guard may use to stop a descent above the floor: the
  /// barrier is ψ = (h − h_min) − |ḣ|·t_r − ḣ²/(2·a_b) ≥ 0 while sinking [m/s²].
  double guard_brake_mps2 = 2.0;
  /// t_r, the reaction time of the thrust (motors, ESC dead time, filters) the barrier allows
  /// for before the braking acts [s].
  double guard_reaction_time_s = 0.05;
  /// γ, the rate at which ψ may approach zero (ψ̇ ≥ −γ·ψ): while sinking, the guard's lower bound
  /// on the commanded vertical acceleration is (|ḣ| − γ·ψ)/(t_r + |ḣ|/a_b), at most a_b [1/s].
  double guard_rate_per_s = 4.0;
  /// K_n, the per-rotor speed loop: each motor's throttle gains K_n·∫(n_des − n)/n_max dt, so an
  /// ESC that reaches less speed than the throttle curve promises (a sagging battery, a worn
  /// motor) is brought to its command; the paper's throttle is the curve's open-loop inverse
  /// plus one shared correction. An addition: 0 (off) in the paper's configurations, 15 in
  /// `recommended` [1/s].
  double rotor_speed_ki_per_s = 0.0;
  /// Bound on each motor's speed-loop correction [throttle].
  double rotor_speed_limit_throttle = 0.3;
  /// The speed loop compares each rotor's speed with its command passed through this first-order
  /// lag (the motor's time constant plus the ESC/link dead time), so that only a gain error —
  /// not the motors' ordinary lag behind a changing command — is integrated [s].
  double rotor_speed_lag_s = 0.04;
  /// F_G learned in flight from the disturbance observer's estimate (the controller's input
  /// external_accel_W); acceleration `model` only. Off in every configuration unless the
  /// configuration name says "+learn" or "+learn0".
  GroundEffectLearning learn_ground_effect = GroundEffectLearning::kOff;
  /// The learner's knots, forgetting, gates and bounds (with learning on).
  GroundEffectLearnerParams learner;
  /// The leveling torque's scale, learned with F_G (with learning on; from 1, the vehicle file's
  /// M_G, with "+learn", from 0 with "+learn0"): its forgetting, excitation gate and bounds.
  LevelingLearnerParams leveling_learner;
  /// Per-rotor ground effect from the ranger's view of the ground (issue 13 item 1,
  /// docs/controller.md "Per-rotor ground effect"): F_G at each rotor's own height, so the
  /// extra lift and the torque of partial ground effect (some rotors over a table, others over
  /// the void beyond its edge) are fed forward, and the leveling torque acts toward the measured
  /// ground normal instead of the vertical. Acceleration `model` (the force) and torque `model` /
  /// `model_indi` (the torque). Off unless the configuration name says "+rotors".
  bool per_rotor_ground_effect = false;
  /// Ceiling and wall effects from the single-beam rangers (issue 13 item 4, docs/controller.md
  /// "Ceilings and walls"): the image-method law (model/proximity_effect.hpp) at each rotor's
  /// distance to the surface each beam sees, taken square to the beam; the extra thrust and the
  /// pull toward a wall are fed forward (acceleration `model`, `none`, `neural`) and their torque
  /// (every torque). Nothing without a beam that sees a surface. On in `recommended`; elsewhere
  /// the configuration name says "+proximity".
  bool proximity_compensation = false;

  /// Whether any of geaware's additions is on.
  [[nodiscard]] bool hasAdditions() const noexcept;

  /// Every offending field with its value and expectation; empty when usable.
  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

/// geaware's recommended configuration (`--controller recommended`, docs/controller.md): the
/// best ACC:TORQUE pair, model:model_indi (F_G, D(h) and J'(h) fed forward, model + INDI
/// torque), with the disturbance observer's residual fed forward, integral action on position
/// with anti-windup and the clearance guard. Later work that improves the controller changes
/// this function, and the tables that use it are re-run.
[[nodiscard]] ControllerParams recommendedControllerParams();

/// The name of a configuration: "recommended" when `p` has recommendedControllerParams()'s
/// switches and additions; otherwise "ACC:TORQUE", followed by "+dob", "+integral", "+guard"
/// for each addition that is on and "+proximity" for the ceiling and wall feed-forward (except
/// in "recommended", which has it); then "+rotors" for per-rotor ground effect and "+learn" or
/// "+learn0" when F_G is learned in flight.
[[nodiscard]] std::string configurationName(const ControllerParams& p);

/// Parses "recommended" or "ACC:TORQUE[+proximity]", then "[+rotors][+learn|+learn0]", into `p`
/// (the switches and additions only; gains and rates keep their values); false when malformed.
[[nodiscard]] bool parseConfiguration(const std::string& text, ControllerParams& p);

}  // namespace geaware::control
