// SPDX-License-Identifier: BSD-3-Clause
// Two of geaware's additions to the paper's controller (docs/controller.md): the disturbance
// observer's residual fed forward, and the position integral with conditional integration.
// Controller::additions (controller.cpp) combines them with the clearance guard.
#include <algorithm>
#include <cmath>

#include "controller_internal.hpp"
#include "geaware/control/controller.hpp"
#include "geaware/model/finite.hpp"

namespace geaware::control {

namespace {
/// Within this of the landing gear's rotor-plane height, the feet may carry the vehicle [m]
/// (the F_G learner's kLearnAboveGearM).
constexpr double kFeetMayCarryM = 0.01;
}  // namespace

Eigen::Vector3d Controller::disturbanceResidual(const ControllerInput& in, double thrust_ref_N,
                                                const Eigen::Matrix3d& R,
                                                const Eigen::Vector3d& a_shape_W,
                                                const Eigen::Vector3d& a_prox_W) noexcept {
  if (!(params_.dob_time_constant_s > 0.0)) return Eigen::Vector3d::Zero();
  // Standing on the gear before a take-off, the feet carry part of the weight: the observer
  // reads the ground's reaction as an upward disturbance, and feeding it forward would take
  // thrust away until the lift-off. Nothing is fed forward until a valid height more than a
  // centimetre above the gear's (the F_G learner's rule) says the vehicle is airborne; then the
  // filter starts afresh. A flight that starts in the air is airborne from its first reading;
  // without a valid height (out of range, no ranger) nothing withholds the feed-forward.
  if (in.height_valid) {
    const bool on_gear = in.height_m <= min_rotor_plane_height_m_ + kFeetMayCarryM;
    if (!on_gear) mem_.been_airborne_ = true;
    if (on_gear && !mem_.been_airborne_) return Eigen::Vector3d::Zero();
  }
  if (in.external_accel_valid && model::allFinite(in.external_accel_W)) {
    // What the model already accounts for in ã_ext: at the measured height, the extra thrust
    // F_G(h)·T_ref/m along z_B (with the feed-forward's thrust: a thrust or mass error times F_G
    // is a disturbance like any other) and the rotor drag at the estimated velocity. The rest is
    // fed forward. The model's own dependence on the state (F_G's slope in h, D·v) stays in the
    // loop as the physical spring and damping it is (docs/controller.md).
    const double h = mem_.last_height_m_;
    const bool model = params_.acceleration == AccelerationCompensation::kModel;
    const Eigen::Vector2d d = model ? drag_.coefficients(h) : drag_.highAltitudeCoefficients();
    Eigen::Vector3d explained = model::RotorDragModel::force_W(R, in.estimate.v_W, d) / mass_kg_;
    if (model) explained += mem_.fade_est_ * ground_effect_.thrustRatio(h) * thrust_ref_N / mass_kg_ * R.col(2);
    if (params_.per_rotor_ground_effect) explained += a_shape_W;  // partial ground effect
    if (params_.proximity_compensation) explained += a_prox_W;    // ceiling and walls
    const double lim = params_.dob_limit_mps2;
    const Eigen::Vector3d raw = (in.external_accel_W - explained).cwiseMax(-lim).cwiseMin(lim);
    // First-order low-pass, backward Euler: τ_d·ḋ = raw − d; like every filter of the
    // controller (model::LowPass2) it starts in steady state at its first input, so a mismatch
    // present from take-over on is cancelled at once instead of being flown into for τ_d.
    if (!mem_.have_dob_residual_) {
      mem_.dob_residual_mps2_ = raw;
      mem_.have_dob_residual_ = true;
    }
    mem_.dob_residual_mps2_ += dt_s_ / (params_.dob_time_constant_s + dt_s_) * (raw - mem_.dob_residual_mps2_);
  }
  return mem_.dob_residual_mps2_;
}

Eigen::Vector3d Controller::integralTerm(const Eigen::Vector3d& e_p, std::uint32_t& flags) noexcept {
  if (!params_.k_i_per_s3.any()) return Eigen::Vector3d::Zero();
  // Conditional integration: while last tick's command was cut (tilt or thrust; the guard for
  // z), the integral may shrink but not grow. And |K^I·∫e_p| ≤ integral_limit per axis.
  const bool cut_xy = (mem_.last_flags_ & (kFlagTiltLimited | kFlagThrustSaturated)) != 0;
  const bool cut_z = (mem_.last_flags_ & (kFlagThrustSaturated | kFlagClearanceGuard)) != 0;
  Eigen::Vector3d a_int = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    const double k_i = params_.k_i_per_s3[i];
    if (k_i <= 0.0) continue;
    double& I = mem_.position_integral_ms_[i];
    const double next = I + e_p[i] * dt_s_;
    if ((i < 2 ? cut_xy : cut_z) && std::abs(next) > std::abs(I)) {
      flags |= kFlagIntegralHeld;
    } else {
      const double bound = params_.integral_limit_mps2 / k_i;
      I = std::clamp(next, -bound, bound);
      if (I != next) flags |= kFlagIntegralHeld;
    }
    a_int[i] = k_i * I;
  }
  return a_int;
}

}  // namespace geaware::control
