// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Differential flatness with ground effect (paper section "Differential Flatness with Ground
// Effect", SPEC §2): flat outputs (p, v, a, j, s; ψ, ψ̇, ψ̈) and the rotor-plane height h map to
// thrust, attitude, body rates, body angular acceleration, torque and rotor speeds of the model
//
//   a = −g·z_W + (1 + F_G(h))·(T/m)·z_B − R·(D(h)/m)·Rᵀ·v          (paper eq. 27)
//   J'(h)·ω̇ = −ω × J'(h)·ω + τ_B
//
// The attitude follows the drag-aware construction of Faessler et al. 2018 (x_B ⊥ α, y_B ⊥ β
// with α = a + g·z_W + d_x·v, β = a + g·z_W + d_y·v, x_B ⊥ y_C); ω and ω̇ come from
// differentiating that model once and twice with dD/dt = 0 (the paper's assumption near the
// ground). The derivation, step by step, is in docs/flatness.md. With every ground-effect term
// off the map is exactly the plain drag-aware map with the high-altitude drag.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geaware/model/vehicle_model.hpp"
#include "geaware/traj/flat_output.hpp"

namespace geaware::flatness {

/// Which ground-effect terms the map accounts for; each can be switched alone.
struct GroundEffectTerms {
  bool additional_thrust = true;  ///< T = m·z_Bᵀ(a + g·z_W)/(1 + F_G(h)) instead of without F_G
  bool height_drag = true;        ///< D(h) instead of the high-altitude D (table's last row)
  bool leveling_inertia = true;   ///< J'(h) instead of J in the torque

  [[nodiscard]] static constexpr GroundEffectTerms all() noexcept { return {true, true, true}; }
  [[nodiscard]] static constexpr GroundEffectTerms none() noexcept { return {false, false, false}; }
};

/// Why a flat state could not be computed (the outputs are then not meaningful).
enum class FlatMapStatus {
  kOk,
  kNonFiniteInput,  ///< a flat output or the height is NaN or infinite
  kNoThrust,        ///< collective acceleration ≤ 0 or the rate equations are singular
  kYawSingular,     ///< the yaw direction is parallel to α (body x undefined)
};

/// Human-readable name of a status.
[[nodiscard]] const char* toString(FlatMapStatus status) noexcept;

/// The reference state and inputs for one instant.
struct FlatState {
  FlatMapStatus status = FlatMapStatus::kOk;
  double thrust_N = 0.0;                                  ///< collective rotor thrust T [N]
  double collective_acc_mps2 = 0.0;                       ///< (1 + F_G)·T/m [m/s²]
  Eigen::Matrix3d R_WB = Eigen::Matrix3d::Identity();     ///< attitude, body → world
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();
  Eigen::Vector3d w_B = Eigen::Vector3d::Zero();          ///< body rates ω [rad/s]
  Eigen::Vector3d w_dot_B = Eigen::Vector3d::Zero();      ///< ω̇ [rad/s²]
  Eigen::Vector3d tau_B = Eigen::Vector3d::Zero();        ///< rotor torque τ_B [N·m]
  Eigen::Vector4d n_sq_rpm2 = Eigen::Vector4d::Zero();    ///< M⁻¹·[T; τ_B], unclamped [rpm²]
  Eigen::Vector4d rotor_speeds_rpm = Eigen::Vector4d::Zero();  ///< √max(n², 0) [rpm]
  bool rotor_speeds_feasible = true;  ///< every n² within the throttle curve's speed range

  [[nodiscard]] bool ok() const noexcept { return status == FlatMapStatus::kOk; }
};

class FlatMap {
 public:
  /// Copies what it needs from `model`; no reference to it is kept.
  explicit FlatMap(const model::VehicleModel& model,
                   GroundEffectTerms terms = GroundEffectTerms::all());

  /// Flat outputs and rotor-plane height [m] → reference state. No allocation, no exceptions.
  [[nodiscard]] FlatState evaluate(const traj::FlatOutput& ref, double height_m) const noexcept;

  /// The attitude, thrust, body rates and angular acceleration of evaluate() (the same values
  /// bit for bit), without the torque, the quaternion and the rotor speeds: what a controller's
  /// feed-forward reads. `cos_yaw`, `sin_yaw` are std::cos and std::sin of ref.yaw_rad, which
  /// the caller may have at hand. tau_B, q_WB, n_sq_rpm2, rotor_speeds_rpm keep their defaults.
  [[nodiscard]] FlatState evaluateRates(const traj::FlatOutput& ref, double height_m, double cos_yaw,
                                        double sin_yaw) const noexcept;

  /// The model's F_G table values replaced (same knots; see model::GroundEffectModel), for a
  /// curve learned in flight. No allocation.
  void setThrustTableValues(const double* values) noexcept { ground_effect_.setThrustTableValues(values); }
  /// A factor on the vehicle file's leveling torque M_G (the scale learned in flight).
  void setLevelingScale(double scale) noexcept { ground_effect_.setLevelingScale(scale); }

  [[nodiscard]] const GroundEffectTerms& terms() const noexcept { return terms_; }

 private:
  void rates(const traj::FlatOutput& ref, double height_m, double cos_yaw, double sin_yaw,
             FlatState& out) const noexcept;

  GroundEffectTerms terms_;
  double mass_kg_;
  model::GroundEffectModel ground_effect_;
  model::RotorDragModel drag_;
  model::Mixer mixer_;
  Eigen::Vector3d inertia_kgm2_;
  double n_sq_min_rpm2_;
  double n_sq_max_rpm2_;
};

}  // namespace geaware::flatness
