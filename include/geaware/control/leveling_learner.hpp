// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The leveling torque's scale learned in flight (issue 13 item 3): s in
//     τ_G,B = s·M̂_G(h)·T·Rᵀ·(z_B × z_W)        (paper eq. 13, M̂_G the vehicle file's shape)
// from the torque the rotors do not explain, the torque-INDI quantities the controller already
// filters: y = J·ω̇_f + ω_f × J·ω_f − τ̂_B (τ̂_B from the measured rotor speeds).
//
// Per sample, the two horizontal body axes a ∈ {x, y} give y_a = s·x_a + b_a + noise, with the
// regressor x = M̂_G(h)·T_f·Rᵀ·(z_B × z_W) [N·m] and b a constant body torque that is not the
// ground's (the centre of mass off the thrust centre, unequal rotors: an as-built vehicle has
// one at every height, and it changes with the thrust and with a battery that shifts). θ =
// (s, b_x, b_y) is estimated by a Kalman filter whose states walk at random (the forgetting of
// recursive least squares, per state): before each used sample P ← P + diag(q_s, q_b, q_b), then
// one row φ = (x_a, e_a) at a time the standard update. The biases walk faster than the scale
// (a vehicle's leveling does not change in flight; its stray torques do), so a change of
// torque at one tilt goes to the biases. Only used samples advance the walk: a flight that
// gives no sample changes nothing.
//
// Excitation: a sample is used only when |x| ≥ min_regressor_Nm (tilted near the ground); a
// level hover or a flight far from the ground gives no sample and changes nothing. A constant
// tilt informs b + s·x only, which the biases can explain: the scale is told from the bias by
// the spread of x alone. The scale in use (published) is the estimate once its posterior
// standard deviation √P_ss is at most learned_sigma, bounded to [min_scale, max_scale];
// until then it is the prior (the vehicle file's M_G, or none). No allocation; every update is
// O(1).

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "geaware/control/ground_effect_learner.hpp"  // LearnerSample
#include "geaware/model/field_error.hpp"

namespace geaware::control {

struct LevelingLearnerParams {
  /// Random walk of the scale per used sample (its forgetting), σ [-].
  double scale_walk_sigma = 1e-4;
  /// Random walk of each bias per used sample, σ [N·m].
  double bias_walk_sigma_Nm = 2e-5;
  double sample_sigma_Nm = 0.02;   ///< σ of one torque sample on one axis [N·m]
  double prior_sigma = 0.3;        ///< σ₀ of the scale around the vehicle file's (1) [-]
  /// σ₀ around 0 when there is no model to start from: a regulariser only [-].
  double no_model_prior_sigma = 10.0;
  double bias_sigma_Nm = 0.1;      ///< σ of the bias torque's prior (0) [N·m]
  double min_scale = 0.0;          ///< lower bound on the published scale [-]
  double max_scale = 5.0;          ///< upper bound on the published scale [-]
  /// A sample's regressor |x| must reach this: the excitation gate [N·m].
  double min_regressor_Nm = 0.004;
  /// The scale is used once its posterior standard deviation is at most this [-].
  double learned_sigma = 0.05;
  double max_abs_sample_Nm = 0.5;  ///< |y| above this on either axis is an outlier, not used [N·m]
  double max_tilt_rad = 0.35;      ///< samples at a larger tilt are not used [rad]
  double max_speed_mps = 1.5;      ///< nor at a larger horizontal speed (the fade) [m/s]
  double max_climb_mps = 0.5;      ///< nor at a larger vertical speed [m/s]
  /// The vehicle the torques above ([N·m]) are for, the paper's: the controller multiplies them
  /// by m·b/(reference_mass_kg·reference_diagonal_m) for its own vehicle (torques scale with
  /// weight × arm); a mass of 0: the torques as given [kg], [m].
  double reference_mass_kg = 1.696;
  double reference_diagonal_m = 0.35;

  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

class LevelingLearner {
 public:
  /// prior_scale: θ₀'s scale (1: the vehicle file's M_G; 0: none). Throws
  /// model::InvalidParameters for invalid params or a non-finite prior.
  LevelingLearner(const LevelingLearnerParams& params, double prior_scale);

  /// One sample: the regressor x_B and the unexplained torque y_B (horizontal body axes) [N·m],
  /// with the tilt, horizontal and vertical speeds that gate it. No allocation.
  LearnerSample update(const Eigen::Vector2d& x_B_Nm, const Eigen::Vector2d& y_B_Nm, double tilt_rad,
                       double speed_mps, double climb_mps) noexcept;

  /// The scale in use: the prior until excited, then the bounded estimate, held while the
  /// excitation is short [-].
  [[nodiscard]] double scale() const noexcept { return published_; }
  /// The current unbounded least-squares estimate of the scale [-].
  [[nodiscard]] double estimate() const noexcept { return theta_(0); }
  /// The estimated bias torque, body x and y [N·m].
  [[nodiscard]] Eigen::Vector2d bias_Nm() const noexcept { return theta_.tail<2>(); }
  /// The scale's posterior standard deviation √P_ss [-].
  [[nodiscard]] double scaleSigma() const noexcept;
  /// Whether the scale in use was learned (its posterior σ has reached learned_sigma once).
  [[nodiscard]] bool learned() const noexcept { return learned_; }
  [[nodiscard]] std::uint64_t used() const noexcept { return used_; }

 private:
  void addRow(const Eigen::Vector3d& phi, double y) noexcept;

  LevelingLearnerParams p_;
  double r_;  ///< σ² of a row [(N·m)²]
  Eigen::Matrix3d P_ = Eigen::Matrix3d::Zero();  ///< θ's covariance
  Eigen::Vector3d theta_ = Eigen::Vector3d::Zero();
  double published_;
  bool learned_ = false;
  std::uint64_t used_ = 0;
};

}  // namespace geaware::control
