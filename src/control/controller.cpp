// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/control/controller.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "controller_internal.hpp"
#include "geaware/control/allocation.hpp"
#include "geaware/model/finite.hpp"
#include "geaware/model/imu_limits.hpp"
#include "geaware/model/rotation.hpp"
#include "geaware/model/units.hpp"

namespace geaware::control {
namespace {

using model::kGravity;

/// A reference body rate beyond the gyro's full scale (model/imu_limits.hpp) can be neither
/// measured nor tracked: refused like a reference the flat map refuses.
constexpr double kMaxRateRadps = model::kImuMaxRateRadps;
/// A measured rotor speed above twice the speed at full throttle is no measurement: refused like
/// a NaN, as IMU values beyond the full scales of model/imu_limits.hpp.
constexpr double kMaxRotorSpeedFactor = 2.0;

const ControllerParams& validated(const ControllerParams& p) {
  auto errors = p.validate();
  if (!errors.empty()) throw model::InvalidParameters(std::move(errors));
  return p;
}

/// The learners' heights and torques, given for the paper's vehicle, carried over to `vehicle`:
/// heights × R/R_ref, torques × m·b/(m_ref·b_ref) (exactly the given values for the reference).
ControllerParams withLearnersFor(const model::VehicleModel& vehicle, ControllerParams p) {
  const model::VehicleParams& v = vehicle.params();
  GroundEffectLearnerParams& g = p.learner;
  if (g.reference_propeller_radius_m > 0.0) {
    const double s = v.propeller_radius_m / g.reference_propeller_radius_m;
    for (double& h : g.knots_m) h *= s;
    g.far_height_m *= s;
    g.reference_propeller_radius_m = v.propeller_radius_m;
  }
  LevelingLearnerParams& l = p.leveling_learner;
  if (l.reference_mass_kg > 0.0) {
    const double q = (v.mass_kg * v.diagonal_rotor_distance_m) / (l.reference_mass_kg * l.reference_diagonal_m);
    for (double* t : {&l.bias_walk_sigma_Nm, &l.sample_sigma_Nm, &l.bias_sigma_Nm, &l.min_regressor_Nm,
                      &l.max_abs_sample_Nm}) {
      *t *= q;
    }
    l.reference_mass_kg = v.mass_kg;
    l.reference_diagonal_m = v.diagonal_rotor_distance_m;
  }
  return p;
}

/// Which flat-map terms each configuration feeds forward.
flatness::GroundEffectTerms referenceTerms(const ControllerParams& p) {
  const bool acc = p.acceleration == AccelerationCompensation::kModel;
  const bool torque = detail::usesJPrime(p.torque);
  return {acc, acc, torque};
}


/// Rotation with body z along `z_des` and body x perpendicular to the heading's y axis, given
/// the heading's cosine and sine.
Eigen::Matrix3d attitudeFrom(const Eigen::Vector3d& z_des, double cos_yaw, double sin_yaw) {
  const Eigen::Vector3d y_C(-sin_yaw, cos_yaw, 0.0);
  Eigen::Vector3d x = y_C.cross(z_des);
  const double n = x.norm();
  // z_des ⟂ y_C is excluded by the tilt limit (< 90°), so n > 0.
  x /= n;
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = z_des.cross(x);
  R.col(2) = z_des;
  return R;
}

model::GroundEffectModel groundEffectFor(const model::VehicleModel& vehicle, const ControllerParams& p) {
  return detail::learning(p) ? detail::learningVehicle(vehicle, p).groundEffect() : vehicle.groundEffect();
}

flatness::FlatMap referenceMapFor(const model::VehicleModel& vehicle, const ControllerParams& p) {
  return detail::learning(p) ? flatness::FlatMap(detail::learningVehicle(vehicle, p), referenceTerms(p))
                     : flatness::FlatMap(vehicle, referenceTerms(p));
}

}  // namespace

Controller::Controller(const model::VehicleModel& vehicle, ControllerParams params,
                       std::shared_ptr<const ResidualForceModel> residual)
    : params_(withLearnersFor(vehicle, validated(params))),
      residual_(std::move(residual)),
      mass_kg_(vehicle.params().mass_kg),
      inertia_kgm2_(vehicle.params().inertia_kgm2),
      ground_effect_(groundEffectFor(vehicle, params_)),
      drag_(vehicle.drag()),
      mixer_(vehicle.mixer()),
      throttle_curve_(vehicle.throttleCurve()),
      k_T_N_per_rpm2_(vehicle.params().rotor.k_T_N_per_rpm2),
      k_I_Nm_per_rpm2_(vehicle.params().rotor.k_I_Nm_per_rpm2),
      J_R_kgm2_(vehicle.params().rotor.J_R_kgm2),
      reference_map_(referenceMapFor(vehicle, params_)),
      dt_s_(1.0 / params_.rate_hz),
      tan_max_tilt_(std::tan(params_.max_tilt_rad)),
      min_rotor_plane_height_m_(vehicle.params().min_rotor_plane_height_m),
      arm_m_(0.5 * vehicle.params().diagonal_rotor_distance_m),
      rotors_B_(model::Mixer::rotorPositions_B(vehicle.params().diagonal_rotor_distance_m)),
      propeller_radius_m_(vehicle.params().propeller_radius_m),
      mem_(params_.filter_cutoff_hz, params_.rate_hz, detail::kFarFromGroundM) {
  if (params_.acceleration == AccelerationCompensation::kNeural && !residual_) {
    throw std::invalid_argument("acceleration compensation 'neural' needs a residual-force model");
  }
  if (detail::learning(params_)) {
    GroundEffectLearnerParams lp = params_.learner;
    if (params_.learn_ground_effect == GroundEffectLearning::kFromNothing) lp.prior_sigma = lp.no_model_prior_sigma;
    learner_.emplace(lp, detail::learnerPrior(vehicle, params_));
    leveling_learner_.emplace(params_.leveling_learner, detail::levelingPrior(params_));
    ground_effect_.setLevelingScale(leveling_learner_->scale());
    reference_map_.setLevelingScale(leveling_learner_->scale());
  }
}

void Controller::reset() noexcept {
  mem_ = Memory(params_.filter_cutoff_hz, params_.rate_hz, detail::kFarFromGroundM);
  beam_mem_ = BeamMemory();
}

ControllerOutput Controller::fallback(std::uint32_t flags) const noexcept {
  ControllerOutput out;
  out.flags = flags;
  out.height_used_m = mem_.last_height_m_;
  out.thrust_des_N = mass_kg_ * kGravity / (1.0 + ground_effect_.thrustRatio(mem_.last_height_m_));
  const double n = std::sqrt(out.thrust_des_N / (4.0 * k_T_N_per_rpm2_));
  out.n_des_rpm.setConstant(n);
  out.throttle.fill(throttle_curve_.throttle(n));
  return out;
}

namespace {

/// Nothing non-finite may reach the motors, nor an IMU or rotor-speed value no sensor reports.
bool finiteInputs(const ControllerInput& in, double max_rotor_speed_rpm) noexcept {
  const double q_norm = in.estimate.q_WB.norm();
  return in.reference.allFinite() && model::allFinite(in.estimate.p_W) && model::allFinite(in.estimate.v_W) &&
         model::allFinite(in.estimate.q_WB.coeffs()) && q_norm > 0.5 &&
         model::plausibleImu(in.gyro_B, in.accel_B) && model::allFinite(in.rotor_speeds_rpm) &&
         in.rotor_speeds_rpm.cwiseAbs().maxCoeff() <= max_rotor_speed_rpm;
}

/// Whether every command and intermediate of an update is finite (the guard's −∞ excepted).
bool outputFinite(const ControllerOutput& out) noexcept {
  bool ok = std::isfinite(out.thrust_des_N) && std::isfinite(out.yaw_torque_allocated_Nm) &&
            std::isfinite(out.height_used_m) && std::isfinite(out.z_cmd_m) &&
            !std::isnan(out.guard_min_accel_z_mps2) && model::allFinite(out.a_des_W) &&
            model::allFinite(out.q_des_WB.coeffs()) && model::allFinite(out.attitude_error) &&
            model::allFinite(out.w_des_B) && model::allFinite(out.w_dot_des_B) && model::allFinite(out.tau_des_B) &&
            model::allFinite(out.tau_hat_B) && model::allFinite(out.n_des_rpm) && model::allFinite(out.a_dob_W) &&
            model::allFinite(out.a_int_W) && model::allFinite(out.a_ground_shape_W) &&
            model::allFinite(out.tau_ground_shape_B);
  for (double t : out.throttle) ok = ok && std::isfinite(t);
  return ok;
}

}  // namespace

double Controller::modelHeight(const ControllerInput& in, std::uint32_t& flags) noexcept {
  // A height that is missing, non-finite or negative keeps the last valid one, and with it the
  // ground elevation under the vehicle, z_g = ẑ − h (the surface the ranger sees).
  if (in.height_valid && std::isfinite(in.height_m) && in.height_m >= 0.0) {
    mem_.last_height_m_ = std::min(in.height_m, detail::kFarFromGroundM);
    mem_.ground_z_m_ = in.estimate.p_W.z() - in.height_m;
    mem_.have_ground_ = true;
  } else {
    flags |= kFlagHeightInvalid;
  }
  // The ground-effect models are evaluated at the height of the *desired* state above that
  // ground (the paper: "the predicted external force under the desired state"), so they stay a
  // feed-forward. At the measured height the slope of F_G(h) would act as height feedback that
  // cancels the position gain close to the ground (docs/controller.md).
  double h = mem_.last_height_m_;
  if (params_.ground_effect_height == GroundEffectHeight::kReference && mem_.have_ground_) {
    h = std::clamp(in.reference.p_W.z() - mem_.ground_z_m_, 0.0, detail::kFarFromGroundM);
  }
  return h;
}

Controller::Measured Controller::measure(const ControllerInput& in,
                                         const Eigen::Matrix3d& R) noexcept {
  Measured m;
  m.w_f = mem_.w_filter_.update(in.gyro_B);
  m.w_dot_f = mem_.have_last_w_ ? Eigen::Vector3d((m.w_f - mem_.last_w_f_) / dt_s_) : Eigen::Vector3d::Zero();
  mem_.last_w_f_ = m.w_f;
  mem_.last_w_dot_f_ = m.w_dot_f;
  mem_.have_last_w_ = true;
  m.n_sq_rpm2 = in.rotor_speeds_rpm.cwiseAbs2();
  const Eigen::Vector4d wrench_meas = mixer_.wrench(m.n_sq_rpm2);
  Eigen::Vector3d tau_meas = wrench_meas.tail<3>();
  if (params_.compensate_rotor_inertia && mem_.have_last_n_) {
    // Reaction torque of the accelerating rotors, J_R·ṅ (ṅ in rad/s²), with the mixer's spins.
    const Eigen::Vector4d n_dot = (in.rotor_speeds_rpm - mem_.last_n_meas_rpm_) / dt_s_;
    tau_meas.z() += J_R_kgm2_ * model::kRpmToRadPerSec * model::Mixer::yawSigns().dot(n_dot);
  }
  mem_.last_n_meas_rpm_ = in.rotor_speeds_rpm;
  mem_.have_last_n_ = true;
  m.tau_hat = mem_.tau_hat_filter_.update(tau_meas);
  const Eigen::Vector3d a_meas_W = R * in.accel_B - Eigen::Vector3d(0.0, 0.0, kGravity);
  m.a_f = mem_.accel_filter_.update(a_meas_W);
  m.f_f = mem_.thrust_vector_filter_.update(wrench_meas(0) / mass_kg_ * R.col(2));
  mem_.thrust_acc_f_mps2_ = m.f_f.norm();
  return m;
}

Controller::Additions Controller::additions(const ControllerInput& in, double thrust_ref_N,
                                            const Eigen::Matrix3d& R, const Eigen::Vector3d& a_shape_W,
                                            const Eigen::Vector3d& a_prox_W, std::uint32_t& flags) noexcept {
  Additions x;
  x.a_shape = a_shape_W;
  x.a_prox = a_prox_W;
  x.reference = in.reference;
  if (params_.clearance_guard && mem_.have_ground_) {
    // The floor: the landing gear's rotor-plane height plus the margin above the ground the
    // ranger sees. The reference is raised to it (no descent through it), and while sinking the
    // vertical command is bounded below by the braking barrier
    // ψ = (h − h_min) − |ḣ|·t_r − ḣ²/(2·a_b) ≥ 0 (after a reaction time t_r, braking at a_b
    // stops above the floor): ψ̇ ≥ −γ·ψ when a_z ≥ (|ḣ| − γ·ψ)/(t_r + |ḣ|/a_b), at most a_b
    // (docs/controller.md, "The clearance guard").
    // A tilt θ lowers a landing foot by up to arm·sin θ below the level gear height (every
    // point of the airframe lies within the rotor arm of the centre).
    const double sin_tilt = std::sqrt(std::max(0.0, 1.0 - R(2, 2) * R(2, 2)));
    const double h_min = min_rotor_plane_height_m_ + params_.guard_margin_m + arm_m_ * sin_tilt;
    const double z_floor = mem_.ground_z_m_ + h_min;
    if (x.reference.p_W.z() < z_floor) {
      x.reference.p_W.z() = z_floor;
      x.reference.v_W.z() = std::max(x.reference.v_W.z(), 0.0);
      x.reference.a_W.z() = std::max(x.reference.a_W.z(), 0.0);
      flags |= kFlagClearanceGuard;
    }
    const double v = in.estimate.v_W.z();
    if (v < 0.0) {
      const double a_b = params_.guard_brake_mps2;
      const double t_r = params_.guard_reaction_time_s;
      const double psi = (in.estimate.p_W.z() - mem_.ground_z_m_ - h_min) + v * t_r - v * v / (2.0 * a_b);
      x.a_z_min = std::min((-v - params_.guard_rate_per_s * psi) / (t_r - v / a_b), a_b);
    }
  }
  x.a_int = integralTerm(x.reference.p_W - in.estimate.p_W, flags);
  x.a_dob = disturbanceResidual(in, thrust_ref_N, R, a_shape_W, a_prox_W);
  return x;
}

Eigen::Vector3d Controller::thrustVectorCommand(const ControllerInput& in,
                                                const flatness::FlatState& ref, double h,
                                                const Measured& m, const Additions& x,
                                                Eigen::Vector3d& a_des,
                                                std::uint32_t& flags) const {
  const Eigen::Quaterniond q_est = in.estimate.q_WB.normalized();
  const Eigen::Matrix3d R = q_est.toRotationMatrix();
  const Eigen::Vector3d z_B = R.col(2);
  const traj::FlatOutput& r = x.reference;
  a_des = r.a_W + params_.k_p_per_s2.cwiseProduct(r.p_W - in.estimate.p_W) +
          params_.k_v_per_s.cwiseProduct(r.v_W - in.estimate.v_W);
  // geaware's additions, each only when switched on (the paper's rows stay bit-identical).
  if (params_.k_i_per_s3.any()) a_des += x.a_int;
  // The clearance guard bounds the acceleration the vehicle will get: the model's F_G is fed
  // forward at the reference's height, but acts at the measured one.
  const double a_gap = params_.acceleration == AccelerationCompensation::kModel
                           ? ref.thrust_N / mass_kg_ * z_B.z() *
                                 (mem_.fade_est_ * ground_effect_.thrustRatio(mem_.last_height_m_) -
                                  mem_.fade_ref_ * ground_effect_.thrustRatio(h))
                           : 0.0;
  if (a_des.z() + a_gap < x.a_z_min) {
    a_des.z() = x.a_z_min - a_gap;  // the clearance guard
    flags |= kFlagClearanceGuard;
  }
  if (params_.dob_time_constant_s > 0.0) a_des -= x.a_dob;
  // Desired specific thrust vector: the acceleration the rotors must give.
  Eigen::Vector3d f_cmd = Eigen::Vector3d::Zero();
  switch (params_.acceleration) {
    case AccelerationCompensation::kNone:
    case AccelerationCompensation::kModel:
    case AccelerationCompensation::kNeural: {
      const bool model = params_.acceleration == AccelerationCompensation::kModel;
      const Eigen::Vector2d d = model ? drag_.coefficients(h) : drag_.highAltitudeCoefficients();
      // a_D = −R·(D/m)·Rᵀ·v_ref: the drag to be overcome is added back.
      a_des -= model::RotorDragModel::force_W(R, r.v_W, d) / mass_kg_;
      if (model) a_des -= ref.thrust_N / mass_kg_ * mem_.fade_ref_ * ground_effect_.thrustRatio(h) * z_B;  // a_G
      if (params_.per_rotor_ground_effect) a_des -= x.a_shape;  // zero unless acceleration model
      if (params_.proximity_compensation) a_des -= x.a_prox;    // ceiling and wall effects
      f_cmd = a_des + Eigen::Vector3d(0.0, 0.0, kGravity);
      if (params_.acceleration == AccelerationCompensation::kNeural) {
        // Shi et al. 2019: the residual depends on the rotor speeds the command produces, so
        // the command is found by fixed-point iteration starting from the measured speeds.
        ResidualFeatures features{h, in.estimate.v_W, q_est, in.rotor_speeds_rpm};
        Eigen::Vector3d f_nn = Eigen::Vector3d::Zero();
        for (int it = 0; it < params_.neural_iterations; ++it) {
          f_nn = residual_->predict_W(features);
          if (!model::allFinite(f_nn)) f_nn.setZero();
          const double thrust = std::max(mass_kg_ * (f_cmd - f_nn / mass_kg_).dot(z_B), 0.0);
          features.rotor_speeds_rpm.setConstant(std::sqrt(thrust / (4.0 * k_T_N_per_rpm2_)));
        }
        a_des -= f_nn / mass_kg_;
        f_cmd -= f_nn / mass_kg_;
      }
      break;
    }
    case AccelerationCompensation::kIndi:
      // Tal & Karaman 2020: increment the filtered thrust vector by the acceleration still
      // missing; everything the rotors' thrust does not explain (drag, ground) is measured.
      f_cmd = m.f_f + (a_des - m.a_f);
      break;
  }
  // Tilt limit: keep the vertical component, shorten the horizontal one.
  if (f_cmd.z() < 1e-3) f_cmd.z() = 1e-3;
  const double horiz = f_cmd.head<2>().norm();
  const double max_horiz = f_cmd.z() * tan_max_tilt_;
  if (horiz > max_horiz) {
    f_cmd.head<2>() *= max_horiz / horiz;
    flags |= kFlagTiltLimited;
  }
  return f_cmd;
}

ControllerOutput Controller::update(const ControllerInput& in) noexcept {
  // 0. Guard the inputs. Finite inputs can still be so large (1e300 m, 1e200 rpm) that the
  //    arithmetic overflows: a tick whose commands are not all finite is undone (filters,
  //    integrators and the last height as before it) and gives the hover fallback.
  if (mem_.terminated_) {  // latched: the motors stay off
    ControllerOutput off;
    off.flags = kFlagMotorFailure | kFlagTerminated;
    off.height_used_m = mem_.last_height_m_;
    return off;
  }
  // A tick without a computed command is remembered as such (the rotor-speed loop's
  // conditional integration reads it).
  if (!finiteInputs(in, kMaxRotorSpeedFactor * throttle_curve_.maxSpeedRpm())) {
    mem_.last_flags_ = kFlagNonFiniteInput;
    return fallback(kFlagNonFiniteInput);
  }
  const Memory before = mem_;
  ControllerOutput out = step(in);
  if (!outputFinite(out)) {
    mem_ = before;
    mem_.last_flags_ = kFlagNonFiniteInput;
    return fallback(kFlagNonFiniteInput);
  }
  if ((out.flags & kFlagReferenceInvalid) != 0) mem_.last_flags_ = out.flags;
  monitorMotors(in, out);
  if (learner_) learnInFlight(in, out.tau_hat_B);
  return out;
}



ControllerOutput Controller::step(const ControllerInput& in) noexcept {
  // The height the models are evaluated at.
  std::uint32_t flags = kFlagNone;
  const double h = modelHeight(in, flags);
  mem_.fade_ref_ = ground_effect_.forwardFade(in.reference.v_W);
  mem_.fade_est_ = ground_effect_.forwardFade(in.estimate.v_W);

  // 1. Reference from the flat map at that height (the rates and thrust it feeds forward); the
  //    filtered measurements. The reference yaw's cosine and sine are cached: a reference's yaw
  //    seldom changes from one update to the next. Compared bit for bit: −0 is not +0 here
  //    (sin(−0) = −0).
  if (std::bit_cast<std::uint64_t>(in.reference.yaw_rad) != std::bit_cast<std::uint64_t>(yaw_cached_rad_)) {
    yaw_cached_rad_ = in.reference.yaw_rad;
    cos_yaw_ = std::cos(yaw_cached_rad_);
    sin_yaw_ = std::sin(yaw_cached_rad_);
  }
  const flatness::FlatState ref = reference_map_.evaluateRates(in.reference, h, cos_yaw_, sin_yaw_);
  if (!ref.ok() || !(ref.w_B.cwiseAbs().maxCoeff() <= kMaxRateRadps)) {
    return fallback(flags | kFlagReferenceInvalid);
  }
  const Eigen::Quaterniond q_est = in.estimate.q_WB.normalized();
  const Eigen::Matrix3d R = q_est.toRotationMatrix();
  const Measured m = measure(in, R);

  // 2. Acceleration command (paper eq. 31, with geaware's additions when switched on) and the
  //    specific thrust vector.
  const GroundShapeTerms shape = groundShapeTerms(in, h, ref.thrust_N, R);
  const GroundShapeTerms prox = proximityTerms(in, ref.thrust_N, R);
  const Additions x = additions(in, ref.thrust_N, R, shape.a_W, prox.a_W, flags);
  Eigen::Vector3d a_des;
  const Eigen::Vector3d f_cmd = thrustVectorCommand(in, ref, h, m, x, a_des, flags);

  // 3. Attitude, body-rate and body-acceleration commands (paper eq. 32).
  const Eigen::Vector3d z_des = f_cmd.normalized();
  const Eigen::Quaterniond q_des(attitudeFrom(z_des, cos_yaw_, sin_yaw_));
  // Attitude error ξ_e = ξ̂⁻¹∘ξ_des as an angle vector (paper eq. 32), the short way round.
  const Eigen::Vector3d xi_e = model::logMap(q_est.conjugate() * q_des);
  const Eigen::Vector3d w_des = params_.k_xi_per_s.cwiseProduct(xi_e) + ref.w_B;
  const Eigen::Vector3d w_dot_des = params_.k_w_per_s.cwiseProduct(w_des - m.w_f) + ref.w_dot_B;

  // 4. Thrust and torque (paper eq. 33, 34).
  const double thrust = std::max(mass_kg_ * f_cmd.dot(R.col(2)), 0.0);
  const Eigen::Vector3d J = detail::usesJPrime(params_.torque) ? ground_effect_.levelingInertiaDiagonal(h, mem_.fade_ref_)
                                                       : inertia_kgm2_;
  Eigen::Vector3d tau;
  if (detail::usesIncrementalTorque(params_.torque)) {
    tau = m.tau_hat + J.cwiseProduct(w_dot_des - m.w_dot_f);
  } else {
    tau = J.cwiseProduct(w_dot_des) + w_des.cross(J.cwiseProduct(w_des));
  }
  if (params_.per_rotor_ground_effect) {
    // The predicted ground torque is cancelled. Torque INDI's τ̂_B already holds the torque the
    // rotors make against it, through its filter: only the part the filtered measurement does
    // not hold yet (the prediction less its filtered self) is fed forward, so a steady torque
    // is not cancelled twice.
    const Eigen::Vector3d held = mem_.ground_torque_filter_.update(shape.tau_B);
    tau -= detail::usesIncrementalTorque(params_.torque) ? Eigen::Vector3d(shape.tau_B - held) : shape.tau_B;
  }
  if (params_.proximity_compensation) {
    // The ceiling and wall torque, likewise.
    const Eigen::Vector3d held = mem_.proximity_torque_filter_.update(prox.tau_B);
    tau -= detail::usesIncrementalTorque(params_.torque) ? Eigen::Vector3d(prox.tau_B - held) : prox.tau_B;
  }

  // 5. Rotor speeds and throttles: inverse throttle curve (at the measured battery voltage, when
  //    the vehicle's curve has a voltage dependence) plus the shared PI correction.
  Eigen::Vector3d tau_alloc = tau;
  tau_alloc.z() = allocatedYawTorque(in, tau.z());
  const double v_scale = throttle_curve_.voltageScale(in.battery_voltage_V);
  const RotorAllocation alloc =
      allocateRotorSpeeds(mixer_.inverse(), thrust, tau_alloc, throttle_curve_.minSpeedRpm() * v_scale,
                          throttle_curve_.maxSpeedRpm() * v_scale);
  if (alloc.thrust_saturated) flags |= kFlagThrustSaturated;
  if (alloc.roll_pitch_saturated) flags |= kFlagRollPitchSaturated;
  if (alloc.yaw_saturated) flags |= kFlagYawSaturated;
  const double t_e = thrustCorrection(alloc.n_sq_rpm2, m.n_sq_rpm2);

  ControllerOutput out;
  out.n_des_rpm = alloc.n_sq_rpm2.cwiseSqrt();
  const Eigen::Vector4d t_n = rotorSpeedCorrection(in);
  for (int i = 0; i < 4; ++i) {
    out.throttle[static_cast<std::size_t>(i)] =
        std::clamp(throttle_curve_.throttle(out.n_des_rpm(i) / v_scale) + t_e + t_n[i], 0.0, 1.0);
  }
  out.rotor_speed_correction = t_n;
  out.a_des_W = a_des;
  out.thrust_des_N = thrust;
  out.q_des_WB = q_des;
  out.attitude_error = xi_e;
  out.w_des_B = w_des;
  out.w_dot_des_B = w_dot_des;
  out.tau_des_B = tau;
  out.yaw_torque_allocated_Nm = tau_alloc.z();
  out.tau_hat_B = m.tau_hat;
  out.height_used_m = h;
  out.a_dob_W = x.a_dob;
  out.a_int_W = x.a_int;
  out.a_ground_shape_W = shape.a_W;
  out.tau_ground_shape_B = shape.tau_B;
  out.guard_min_accel_z_mps2 = x.a_z_min;
  out.z_cmd_m = x.reference.p_W.z();
  out.flags = flags;
  mem_.last_flags_ = flags;
  return out;
}

}  // namespace geaware::control
