// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Controller-side ground-effect model of the paper: additional thrust F_G(h) (eq. 5), leveling
// torque M_G(h) (eq. 13–14) and its "payload ball" equivalent inertia J'(h) (eq. 24–25).
//
// Height convention: h is the distance from the ground to the centre of the rotor plane [m].
// Heights below the vehicle's smallest physical rotor-plane height (its landing gear) cannot be
// flown and lie outside the range the curves were fitted on, so every function clamps h up to
// that minimum (its derivative is then 0). There is no upper limit: F_G and M_G decay to 0.
// A non-finite h gives a non-finite result; callers guard their inputs (see control/).
//
// Each curve is either the paper's closed form or a table of measured points
// (VehicleParams' `table`, interpolated by model::HeightTable); every function below says the
// closed form, and uses the table instead where the vehicle gives one.

#include <Eigen/Core>

#include "geaware/model/height_table.hpp"
#include "geaware/model/vehicle_params.hpp"

namespace geaware::model {

class GroundEffectModel {
 public:
  /// Requires validated parameters (VehicleParams::validate() empty).
  explicit GroundEffectModel(const VehicleParams& params);

  /// The height actually used by the model: max(h, min_rotor_plane_height) [m].
  [[nodiscard]] double effectiveHeight(double h_m) const noexcept {
    return h_m < min_height_m_ ? min_height_m_ : h_m;
  }

  /// Additional-thrust ratio F_G(h) = g2/(h²+g1): f_G = F_G·T·z_B [-].
  [[nodiscard]] double thrustRatio(double h_m) const noexcept;

  /// dF_G/dh [1/m]; zero below the minimum height where the model is clamped.
  [[nodiscard]] double thrustRatioSlope(double h_m) const noexcept;

  /// Leveling coefficient M_G(h) = scale·h/(h²+g3·h+g4)² [m]: leveling torque per newton of
  /// thrust per unit sin δ.
  [[nodiscard]] double levelingCoefficient(double h_m) const noexcept {
    return leveling_scale_ * levelingShape(h_m);
  }
  /// M_G(h) as the vehicle file gives it, without the scale learned in flight
  /// (setLevelingScale) [m].
  [[nodiscard]] double levelingShape(double h_m) const noexcept;
  /// A factor on the vehicle file's M_G everywhere it is used (the leveling scale learned in
  /// flight, control/leveling_learner.hpp); 1 as built, which changes nothing bit for bit.
  void setLevelingScale(double scale) noexcept { leveling_scale_ = scale; }
  [[nodiscard]] double levelingScale() const noexcept { return leveling_scale_; }

  /// Height of the maximum of M_G, (−g3 + √(g3² + 12·g4))/6 [m]; for a table, the knot with
  /// the largest value (PCHIP does not overshoot, so the maximum lies at a knot).
  [[nodiscard]] double levelingPeakHeight() const noexcept;

  /// Leveling torque in the body frame [N·m]: R·τ_G = M_G(h)·T·(z_B × z_W) (paper eq. 13).
  [[nodiscard]] Eigen::Vector3d levelingTorque_B(const Eigen::Matrix3d& R_WB, double h_m,
                                                 double thrust_N) const noexcept;

  /// Inertia increment q(h) = [M_G(h)·T]²/(m·g²) with the hover approximation
  /// M_G·T ≈ m·g·M_G/(1+F_G) (paper eq. 25–26), so q = m·M_G²/(1+F_G)² [kg·m²].
  [[nodiscard]] double levelingInertiaIncrement(double h_m) const noexcept;

  /// Same, with the actual thrust instead of the hover approximation [kg·m²].
  [[nodiscard]] double levelingInertiaIncrement(double h_m, double thrust_N) const noexcept;

  /// J'(h) = J + diag(q, q, 0), the payload-ball equivalent inertia (hover approximation).
  [[nodiscard]] Eigen::Matrix3d levelingInertia(double h_m) const noexcept;

  /// Diagonal of J'(h) [kg·m²].
  [[nodiscard]] Eigen::Vector3d levelingInertiaDiagonal(double h_m) const noexcept;
  /// Diagonal of J'(h) with the ground effect faded in forward flight: M_G and F_G scaled by
  /// `fade`, q = m·[fade·M_G/(1 + fade·F_G)]²; bit for bit levelingInertiaDiagonal(h) at fade 1
  /// [kg·m²].
  [[nodiscard]] Eigen::Vector3d levelingInertiaDiagonal(double h_m, double fade) const noexcept;

  /// The ground effect's forward-flight fade v_i²/(v_i² + V²) at world velocity v_W, V its
  /// horizontal speed (the speed in the rotor plane of a level vehicle), v_i the vehicle file's
  /// forward_fade_induced_velocity_mps (Cheeseman & Bennett 1955): F_G and M_G are scaled by
  /// it. Exactly 1 without a fade (v_i = 0) or at rest [-].
  [[nodiscard]] double forwardFade(const Eigen::Vector3d& v_W) const noexcept {
    if (!(induced_velocity_sq_ > 0.0)) return 1.0;
    const double V_sq = v_W.x() * v_W.x() + v_W.y() * v_W.y();
    return V_sq > 0.0 ? induced_velocity_sq_ / (induced_velocity_sq_ + V_sq) : 1.0;
  }
  /// Whether the model fades with speed (a forward-fade induced velocity is set).
  [[nodiscard]] bool fades() const noexcept { return induced_velocity_sq_ > 0.0; }

  /// Whether F_G is a table (vehicle file `ground_effect.additional_thrust.table`), and its knots.
  [[nodiscard]] bool thrustIsTable() const noexcept { return !thrust_table_.empty(); }
  [[nodiscard]] const HeightTable& thrustTable() const noexcept { return thrust_table_; }
  /// New F_G values at the table's knots (thrustTable().size() of them, finite). Only for a
  /// table; no allocation (the curve learned in flight, control/ground_effect_learner.hpp).
  void setThrustTableValues(const double* values) noexcept { thrust_table_.setValues(values); }

 private:
  double mass_kg_;
  Eigen::Vector3d inertia_kgm2_;
  double min_height_m_;
  double induced_velocity_sq_ = 0.0;  ///< v_i² of the forward fade; 0: none [m²/s²]
  double leveling_scale_ = 1.0;       ///< factor on the file's M_G (learned in flight) [-]
  AdditionalThrustParams thrust_;
  LevelingTorqueParams leveling_;
  HeightTable thrust_table_;    ///< empty: the closed form
  HeightTable leveling_table_;  ///< empty: the closed form
};

}  // namespace geaware::model
