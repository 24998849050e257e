// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The ground-effect-aware controller of the paper ("Model-based Controller with Incremental
// Inversion", SPEC §3), with the acceleration and torque compensation of Table I as two
// independent switches, so every row of the table is a configuration, not a fork.
//
// One update (numbered as in the paper):
//   1. reference: flat map at the reference and the measured height (flatness/) → a_ref,
//      ω_ref, ω̇_ref, T_ref;
//   2. acceleration command a_des = a_ref + K^P·e_p + K^V·e_v − a_D − a_G (model), or the
//      INDI / Neural-Lander / drag-only variants (eq. 31);
//   3. desired attitude from a_des and ψ_ref, attitude error ξ_e = ξ̂⁻¹∘ξ_des as an angle
//      vector, ω_des = K^ξ·ξ_e + ω_ref, ω̇_des = K^ω·(ω_des − ω_f) + ω̇_ref (eq. 32);
//   4. thrust T_des = m·(a_des + g·z_W)ᵀ·ẑ_B, torque by the selected compensation (eq. 33);
//   5. rotor speeds N² = M⁻¹·[T; τ] with saturation that keeps thrust, then roll/pitch,
//      before yaw; throttles from the inverse throttle curve plus the shared PI correction on
//      the thrust-acceleration error (docs/paper-facts.md, supplementary section 3).
// Where it departs from the paper: the yaw torque of a rotor is k_I·n² + J_R·ṅ (the paper's
// own motor model), and with this vehicle's J_R the J_R·ṅ part dominates any fast yaw command
// (≈ 28× the k_I·n² effect above 0.2 Hz). The mixer's k_I·n² alone would make the yaw loop
// 28× too stiff and, with incremental inversion, unstable. So τ̂_B includes J_R·ṅ from the
// measured speeds, and the yaw command is passed through the lag 1/(1 + s·τ_R),
// τ_R = J_R·(2π/60)/(2·k_I·n̄), that cancels the lead (1 + s·τ_R) of the rotors' yaw response
// (the same effect Smeur et al. 2016 model with their G2 term). docs/controller.md.
// geaware's additions in translation, each off by default and on in `recommended`
// (recommendedControllerParams(), docs/controller.md): the disturbance observer's residual
// (ControllerInput::external_accel_W minus the model's F_G and D(h) at the measured height),
// low-passed and fed forward; integral action on position with anti-windup; and a clearance
// guard (the reference raised to the landing gear's height plus a margin, and a braking-barrier
// bound on the vertical command while sinking).
// No allocation and no exceptions in update(); invalid inputs are flagged and never reach the
// motors as NaN.

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geaware/control/controller_params.hpp"
#include "geaware/control/ground_effect_learner.hpp"
#include "geaware/control/residual_force.hpp"
#include "geaware/flatness/flat_map.hpp"
#include "geaware/model/low_pass.hpp"
#include "geaware/model/sensor_data.hpp"
#include "geaware/model/state_estimate.hpp"
#include "geaware/model/vehicle_model.hpp"
#include "geaware/traj/flat_output.hpp"

namespace geaware::control {

/// Everything the controller reads in one update.
struct ControllerInput {
  double t_s = 0.0;                       ///< time [s] (monotonic; used for logging only)
  traj::FlatOutput reference;             ///< flat outputs of the trajectory at t
  model::StateEstimate estimate;  ///< from estimation/, never the simulator's truth
  Eigen::Vector3d gyro_B = Eigen::Vector3d::Zero();   ///< bias-corrected body rates [rad/s]
  Eigen::Vector3d accel_B = Eigen::Vector3d::Zero();  ///< bias-corrected specific force [m/s²]
  double height_m = 0.0;                  ///< rotor-plane height from the ranger [m]
  bool height_valid = false;              ///< false: no reading this tick (missing or rejected)
  Eigen::Vector4d rotor_speeds_rpm = Eigen::Vector4d::Zero();  ///< measured (telemetry) [rpm]
  /// The disturbance observer's external acceleration ã_ext (estimation::DisturbanceObserver,
  /// paper eq. 6), world frame [m/s²]. Read only by the disturbance feed-forward
  /// (ControllerParams::dob_time_constant_s > 0); the paper's configurations ignore it.
  Eigen::Vector3d external_accel_W = Eigen::Vector3d::Zero();
  bool external_accel_valid = false;  ///< false: no estimate this tick (warming up, bad input)
  /// Measured battery voltage, for the throttle curve's voltage dependence (the vehicle's
  /// throttle_curve.reference_voltage_V and voltage_exponent): the rotor-speed command is turned
  /// into throttle at this voltage. NaN (the default): not measured, the curve at its reference
  /// voltage, as before the input existed [V].
  double battery_voltage_V = std::numeric_limits<double>::quiet_NaN();
  /// The ground's shape around the vehicle from the lattice ranger (estimation::LatticeHeight),
  /// read only with per-rotor ground effect on (ControllerParams::per_rotor_ground_effect):
  /// per rotor (mixer order), how much farther the surface beneath that rotor lies than the
  /// ground plane under the rotor-plane centre, extended (LatticeHeight::rotor_height_offset_m:
  /// 0 over one plane, +0.1 m for a rotor beyond a 10 cm table edge) [m], and the ground's
  /// upward unit normal, world frame. Invalid, non-finite or implausible values keep the last
  /// valid ones.
  std::array<double, 4> rotor_height_offset_m{};
  Eigen::Vector3d ground_normal_W = Eigen::Vector3d::UnitZ();
  bool ground_shape_valid = false;  ///< false: no reading this tick
  /// The single-beam rangers that look up and sideways (sim::BeamRanger), their latest
  /// readings; read only with ControllerParams::proximity_compensation. An invalid entry (no
  /// return, too old, or no such ranger) contributes nothing.
  static constexpr std::size_t kMaxBeams = 6;
  std::array<model::BeamReading, kMaxBeams> beams{};
};

/// Conditions met during an update (bit flags).
enum ControllerFlag : std::uint32_t {
  kFlagNone = 0,
  /// A NaN/∞ in the estimate, IMU or reference, an IMU or rotor-speed value beyond any sensor's
  /// range, or inputs so large that the commands overflowed: hover output, state unchanged.
  kFlagNonFiniteInput = 1u << 0,
  kFlagHeightInvalid = 1u << 1,      ///< height missing or implausible: last valid height used
  kFlagReferenceInvalid = 1u << 2,   ///< the flat map refused the reference
  kFlagTiltLimited = 1u << 3,        ///< commanded tilt clipped to max_tilt_rad
  kFlagYawSaturated = 1u << 4,       ///< yaw torque reduced to fit the rotor-speed range
  kFlagRollPitchSaturated = 1u << 5, ///< roll/pitch torque reduced to fit
  kFlagThrustSaturated = 1u << 6,    ///< thrust clipped to the rotor-speed range
  kFlagClearanceGuard = 1u << 7,     ///< the clearance guard raised the height or vertical command
  kFlagIntegralHeld = 1u << 8,       ///< anti-windup held or clipped the position integral
  /// A rotor has turned at less than half its command for 0.15 s (latched): the motor or its
  /// ESC failed (monitorMotors(); docs/reliability.md, "Fault campaign").
  kFlagMotorFailure = 1u << 9,
  /// Flight termination (latched): after a motor failure the vehicle tilted past 60°, so every
  /// throttle is 0 — PX4's failure detector does the same (FD_FAIL_R/P, 60° by default): a
  /// quadrotor that lost a motor cannot be held, and falling with stopped rotors harms less than
  /// flying away inverted at full power.
  kFlagTerminated = 1u << 10,
};

/// Commands of one update: the throttles and every intermediate for logging.
struct ControllerOutput {
  std::array<double, 4> throttle{};                              ///< per motor, [0, 1]
  Eigen::Vector3d a_des_W = Eigen::Vector3d::Zero();             ///< acceleration command [m/s²]
  double thrust_des_N = 0.0;                                     ///< T_des [N]
  Eigen::Quaterniond q_des_WB = Eigen::Quaterniond::Identity();  ///< desired attitude
  Eigen::Vector3d attitude_error = Eigen::Vector3d::Zero();      ///< ξ_e as angle vector [rad]
  Eigen::Vector3d w_des_B = Eigen::Vector3d::Zero();             ///< [rad/s]
  Eigen::Vector3d w_dot_des_B = Eigen::Vector3d::Zero();         ///< [rad/s²]
  Eigen::Vector3d tau_des_B = Eigen::Vector3d::Zero();           ///< torque command [N·m]
  double yaw_torque_allocated_Nm = 0.0;                          ///< τ_z after the rotor-inertia lag [N·m]
  Eigen::Vector3d tau_hat_B = Eigen::Vector3d::Zero();           ///< filtered τ̂_B from rotor speeds [N·m]
  Eigen::Vector4d n_des_rpm = Eigen::Vector4d::Zero();           ///< rotor-speed command [rpm]
  double height_used_m = 0.0;                                    ///< height the ground-effect models used [m]
  Eigen::Vector3d a_dob_W = Eigen::Vector3d::Zero();  ///< disturbance residual fed forward (subtracted) [m/s²]
  Eigen::Vector3d a_int_W = Eigen::Vector3d::Zero();  ///< integral term K^I·∫e_p (added) [m/s²]
  /// The rotor-speed loop's correction per motor, K_n·∫(n_des − n)/n_max dt (added) [throttle].
  Eigen::Vector4d rotor_speed_correction = Eigen::Vector4d::Zero();
  /// The clearance guard's lower bound on the commanded vertical acceleration
  /// (a_ref + K^P·e_p + K^V·e_v + K^I·∫e_p); −∞ when the guard is off, has no height or the
  /// vehicle is not sinking [m/s²].
  double guard_min_accel_z_mps2 = -std::numeric_limits<double>::infinity();
  /// The height the position loop aimed at: the reference's, raised to the guard's floor [m].
  double z_cmd_m = 0.0;
  /// Per-rotor ground effect (ControllerParams::per_rotor_ground_effect): the acceleration of
  /// partial ground effect fed forward (subtracted), world frame [m/s²], and the torque the
  /// model predicts from partial ground effect and the leveling toward a sloped ground's normal,
  /// body frame (compensated) [N·m]. Zero when off.
  Eigen::Vector3d a_ground_shape_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d tau_ground_shape_B = Eigen::Vector3d::Zero();
  std::uint32_t flags = kFlagNone;                               ///< ControllerFlag bits
};

class Controller {
 public:
  /// Validates params (throws model::InvalidParameters); `residual` is required for
  /// AccelerationCompensation::kNeural (throws std::invalid_argument otherwise).
  Controller(const model::VehicleModel& vehicle, ControllerParams params,
             std::shared_ptr<const ResidualForceModel> residual = nullptr);

  /// One control step at params().rate_hz. No allocation, no exceptions.
  [[nodiscard]] ControllerOutput update(const ControllerInput& in) noexcept;

  /// Clears filters and integrators (e.g. before a new flight). A curve learned in flight is
  /// kept.
  void reset() noexcept;

  [[nodiscard]] const ControllerParams& params() const noexcept { return params_; }
  /// The in-flight ground-effect learner (params().learn_ground_effect on), or null.
  [[nodiscard]] const GroundEffectLearner* learner() const noexcept {
    return learner_ ? &*learner_ : nullptr;
  }
  /// The in-flight leveling-scale learner (with learning on), or null.
  [[nodiscard]] const LevelingLearner* levelingLearner() const noexcept {
    return leveling_learner_ ? &*leveling_learner_ : nullptr;
  }

 private:
  /// Throttles that hold a level hover at the last valid height: the safe output for a tick
  /// whose inputs cannot be trusted.
  [[nodiscard]] ControllerOutput fallback(std::uint32_t flags) const noexcept;

  /// update() on finite inputs; its result may be non-finite when they are huge.
  [[nodiscard]] ControllerOutput step(const ControllerInput& in) noexcept;
  /// The motor monitor after a finite step: flags a failed motor, terminates when it tipped.
  void monitorMotors(const ControllerInput& in, ControllerOutput& out) noexcept;
  /// One sample for each in-flight learner (F_G and the leveling scale; learning on), after a
  /// finite step whose τ̂_B is `tau_hat_B`; the models take what changes.
  void learnInFlight(const ControllerInput& in, const Eigen::Vector3d& tau_hat_B) noexcept;
  /// The per-rotor speed loop's throttle corrections (zero when off).
  [[nodiscard]] Eigen::Vector4d rotorSpeedCorrection(const ControllerInput& in) noexcept;

  /// The filtered measurements of one tick (update(), step 1).
  struct Measured {
    Eigen::Vector3d w_f;        ///< filtered body rate [rad/s]
    Eigen::Vector3d w_dot_f;    ///< its difference quotient [rad/s²]
    Eigen::Vector4d n_sq_rpm2;  ///< measured rotor speeds squared [rpm²]
    Eigen::Vector3d tau_hat;    ///< filtered torque from the measured speeds [N·m]
    Eigen::Vector3d a_f;        ///< filtered measured acceleration, world frame [m/s²]
    Eigen::Vector3d f_f;        ///< filtered specific thrust vector from the speeds [m/s²]
  };
  /// The height the models are evaluated at; updates the last valid height and the ground.
  [[nodiscard]] double modelHeight(const ControllerInput& in, std::uint32_t& flags) noexcept;
  /// Advances every filter by one tick (they stay in step whatever the configuration).
  [[nodiscard]] Measured measure(const ControllerInput& in, const Eigen::Matrix3d& R) noexcept;
  /// geaware's additions in translation for one tick (all zero/inactive when switched off).
  struct Additions {
    traj::FlatOutput reference;  ///< the position loop's reference (raised to the guard's floor)
    Eigen::Vector3d a_int = Eigen::Vector3d::Zero();  ///< K^I·∫e_p [m/s²]
    Eigen::Vector3d a_dob = Eigen::Vector3d::Zero();  ///< low-passed DOB residual [m/s²]
    double a_z_min = -std::numeric_limits<double>::infinity();  ///< guard's bound [m/s²]
    Eigen::Vector3d a_shape = Eigen::Vector3d::Zero();  ///< partial ground effect [m/s²]
    Eigen::Vector3d a_prox = Eigen::Vector3d::Zero();   ///< ceiling and wall effects [m/s²]
  };
  /// The guarded reference, the position integral (with anti-windup) and the disturbance
  /// residual of this tick; advances their states.
  [[nodiscard]] Additions additions(const ControllerInput& in, double thrust_ref_N,
                                    const Eigen::Matrix3d& R, const Eigen::Vector3d& a_shape_W,
                                    const Eigen::Vector3d& a_prox_W, std::uint32_t& flags) noexcept;
  /// The low-passed residual of the disturbance observer against the model's terms (F_G at the
  /// measured height with the reference thrust `thrust_ref_N`, drag at the estimated velocity).
  /// The partial ground effect `a_shape_W` is part of the model (per-rotor ground effect on).
  [[nodiscard]] Eigen::Vector3d disturbanceResidual(const ControllerInput& in, double thrust_ref_N,
                                                    const Eigen::Matrix3d& R,
                                                    const Eigen::Vector3d& a_shape_W,
                                                    const Eigen::Vector3d& a_prox_W) noexcept;
  /// K^I·∫e_p after this tick's integration, held against the saturations of the last tick.
  [[nodiscard]] Eigen::Vector3d integralTerm(const Eigen::Vector3d& e_p,
                                             std::uint32_t& flags) noexcept;
  /// The desired specific thrust vector f_cmd (paper eq. 31 with the configured compensation
  /// and the additions); `a_des` gets the acceleration command. Tilt-limited, flagged in `flags`.
  [[nodiscard]] Eigen::Vector3d thrustVectorCommand(const ControllerInput& in,
                                                    const flatness::FlatState& ref, double h,
                                                    const Measured& m, const Additions& x,
                                                    Eigen::Vector3d& a_des,
                                                    std::uint32_t& flags) const;
  /// Per-rotor ground effect's terms at model height `h` with thrust `thrust_N` (zero when off):
  /// the specific force of partial ground effect along z_B [m/s²] and the predicted external
  /// torque, body frame [N·m]. Updates the held ground shape.
  struct GroundShapeTerms {
    Eigen::Vector3d a_W = Eigen::Vector3d::Zero();
    Eigen::Vector3d tau_B = Eigen::Vector3d::Zero();
  };
  [[nodiscard]] GroundShapeTerms groundShapeTerms(const ControllerInput& in, double h,
                                                  double thrust_N,
                                                  const Eigen::Matrix3d& R) noexcept;
  /// The ceiling and wall effects predicted from the beam rangers (zero when
  /// proximity_compensation is off or no beam sees a surface): the specific force, world frame
  /// [m/s²], and the torque, body frame [N·m], at thrust `thrust_N` (controller_proximity.cpp).
  /// Updates the beams' consistency check.
  [[nodiscard]] GroundShapeTerms proximityTerms(const ControllerInput& in, double thrust_N,
                                                const Eigen::Matrix3d& R) noexcept;
  /// The yaw torque to allocate: `tau_z` lagged against the rotors' J_R·ṅ lead.
  [[nodiscard]] double allocatedYawTorque(const ControllerInput& in, double tau_z) noexcept;
  /// The shared throttle PI correction T_E on the thrust-acceleration error.
  [[nodiscard]] double thrustCorrection(const Eigen::Vector4d& n_sq_des,
                                        const Eigen::Vector4d& n_sq_meas) noexcept;

  ControllerParams params_;
  std::shared_ptr<const ResidualForceModel> residual_;
  double mass_kg_;
  Eigen::Vector3d inertia_kgm2_;
  model::GroundEffectModel ground_effect_;
  model::RotorDragModel drag_;
  model::Mixer mixer_;
  model::ThrottleCurve throttle_curve_;
  double k_T_N_per_rpm2_;
  double k_I_Nm_per_rpm2_;
  double J_R_kgm2_;
  flatness::FlatMap reference_map_;
  double dt_s_;
  /// tan(params_.max_tilt_rad), the tilt limit's ratio of horizontal to vertical thrust [-].
  double tan_max_tilt_;
  /// The reference yaw of the last update and its cosine and sine (a reference's yaw seldom
  /// changes from one update to the next; the same values either way) [rad], [-].
  double yaw_cached_rad_ = 0.0;
  double cos_yaw_ = 1.0;
  double sin_yaw_ = 0.0;

  /// The landing gear's rotor-plane height [m].
  double min_rotor_plane_height_m_;
  /// Half the diagonal rotor distance: how far a landing foot can be from the centre [m].
  double arm_m_;
  /// Rotor centres in the body frame, mixer order (model::Mixer::rotorPositions_B) [m].
  std::array<Eigen::Vector3d, 4> rotors_B_;
  /// Propeller radius, for the ceiling and wall laws [m].
  double propeller_radius_m_;
  /// F_G learned in flight (with learning on; ground_effect_ and reference_map_ then hold F_G
  /// as a table on the learner's knots).
  std::optional<GroundEffectLearner> learner_;
  /// The leveling torque's scale learned in flight (with learning on; ground_effect_ and
  /// reference_map_ then scale M_G by it).
  std::optional<LevelingLearner> leveling_learner_;

  /// Everything update() changes from tick to tick (fixed size, no allocation). A tick whose
  /// commands come out non-finite (inputs finite but so large that the arithmetic overflows)
  /// restores it, so garbage never stays in a filter or integrator.
  struct Memory {
    Memory(double cutoff_hz, double rate_hz, double height_m) noexcept
        : w_filter_(cutoff_hz, rate_hz), tau_hat_filter_(cutoff_hz, rate_hz),
          accel_filter_(cutoff_hz, rate_hz), thrust_vector_filter_(cutoff_hz, rate_hz),
          ground_torque_filter_(cutoff_hz, rate_hz), proximity_torque_filter_(cutoff_hz, rate_hz),
          last_height_m_(height_m) {}
    // Filters in step (one type, one cut-off): ω (differentiated for ω̇_f) with τ̂_B, and the
    // measured acceleration with the rotor-speed thrust vector for translational INDI.
    model::LowPass2<3> w_filter_;
    model::LowPass2<3> tau_hat_filter_;
    model::LowPass2<3> accel_filter_;
    model::LowPass2<3> thrust_vector_filter_;
    // Per-rotor ground effect: the predicted ground torque through τ̂_B's filter (torque INDI
    // feeds forward only what the filtered measurement does not hold yet), and the last valid
    // ground shape.
    model::LowPass2<3> ground_torque_filter_;
    model::LowPass2<3> proximity_torque_filter_;  // the same for the ceiling and wall torque
    // Whether a beam saw a surface this tick (the F_G learner then takes no sample: the
    // observer's estimate holds the ceiling's pull too).
    bool proximity_active_ = false;
    Eigen::Vector4d rotor_height_offset_m_ = Eigen::Vector4d::Zero();
    Eigen::Vector3d ground_normal_W_ = Eigen::Vector3d::UnitZ();
    double thrust_acc_f_mps2_ = 0.0;  // |filtered thrust vector|, T_f/m [m/s²]
    Eigen::Vector3d last_w_f_ = Eigen::Vector3d::Zero();
    Eigen::Vector3d last_w_dot_f_ = Eigen::Vector3d::Zero();  // ω̇_f of the last tick [rad/s²]
    bool have_last_w_ = false;
    double thrust_pi_integral_ = 0.0;
    double last_height_m_;
    // The ground effect's forward-flight fade this tick (model::GroundEffectModel::forwardFade):
    // at the reference's velocity (the feed-forward) and at the estimate's (what the DOB
    // explains); exactly 1 without a fade in the vehicle file.
    double fade_ref_ = 1.0;
    double fade_est_ = 1.0;
    double ground_z_m_ = 0.0;  // ground elevation under the vehicle from the last valid height [m]
    bool have_ground_ = false;
    // Rotor-inertia yaw torque J_R·ṅ: the previous measured speeds (for ṅ) and the lag that
    // cancels its lead in the yaw command (see update(), step 5).
    Eigen::Vector4d last_n_meas_rpm_ = Eigen::Vector4d::Zero();
    bool have_last_n_ = false;
    double yaw_torque_lagged_Nm_ = 0.0;
    bool have_yaw_lag_ = false;
    // geaware's additions: the low-passed DOB residual, the position integral and the previous
    // tick's flags (anti-windup).
    Eigen::Vector3d dob_residual_mps2_ = Eigen::Vector3d::Zero();
    bool have_dob_residual_ = false;
    /// A valid height has been read more than a centimetre above the gear's height since the
    /// last reset: the feet no longer carry the vehicle (a take-off has lifted off).
    bool been_airborne_ = false;
    Eigen::Vector3d position_integral_ms_ = Eigen::Vector3d::Zero();  // ∫e_p dt [m·s]
    std::uint32_t last_flags_ = kFlagNone;
    // The motor monitor: the last rotor-speed command, how long each rotor has lagged it by
    // half, and the latched failure and termination.
    Eigen::Vector4d last_n_des_rpm_ = Eigen::Vector4d::Zero();
    std::array<double, 4> motor_short_s_{};
    bool motor_failed_ = false;
    Eigen::Vector4d rotor_speed_integral_ = Eigen::Vector4d::Zero();  // [throttle]
    Eigen::Vector4d rotor_speed_model_rpm_ = Eigen::Vector4d::Zero();  // the command through the motor lag
    bool have_rotor_speed_model_ = false;
    bool terminated_ = false;
  };
  Memory mem_;
  /// The beams' last new reading (time, range) and whether it agreed with the one before it (a
  /// lone outlier is not fed forward). Outside Memory: derived from the inputs' validity checks
  /// alone, it needs no undoing, and update() copies Memory on every tick.
  struct BeamMemory {
    BeamMemory() noexcept {
      last_t_s.fill(std::numeric_limits<double>::quiet_NaN());
      last_range_m.fill(std::numeric_limits<double>::quiet_NaN());
    }
    std::array<double, ControllerInput::kMaxBeams> last_t_s{};
    std::array<double, ControllerInput::kMaxBeams> last_range_m{};
    std::array<bool, ControllerInput::kMaxBeams> consistent{};
  };
  BeamMemory beam_mem_;
};

}  // namespace geaware::control
