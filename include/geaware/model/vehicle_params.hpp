// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The controller-side description of a quadrotor: every number the models of the paper need,
// with its unit in the field name and comment. The vehicle file format (config/vehicles/*.yaml)
// mirrors this struct key for key; see docs/vehicle-file.md.

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geaware/model/field_error.hpp"

namespace geaware::model {

/// Rotor and mixer coefficients (paper eq. 2). Speeds are in rpm.
struct RotorParams {
  double k_T_N_per_rpm2 = 0.0;     ///< thrust coefficient, T_i = k_T·n_i² [N/rpm²]
  double k_TX_N_per_rpm2 = 0.0;    ///< roll torque-by-thrust coefficient [N/rpm²]
  double k_TY_N_per_rpm2 = 0.0;    ///< pitch torque-by-thrust coefficient [N/rpm²]
  double k_I_Nm_per_rpm2 = 0.0;    ///< reaction-torque coefficient, M_i = k_I·n_i² [N·m/rpm²]
  double J_R_kgm2 = 0.0;           ///< rotor (+ motor bell) inertia about its axis [kg·m²]
};

/// ESC throttle curve: n² = c2·t² + c1·t + c0 for throttle t ∈ [0, 1], n in rpm, at the
/// reference battery voltage V_ref; at a battery voltage V the speed is scaled by (V/V_ref)^p:
///   n(t, V) = √(c2·t² + c1·t + c0) · (V/V_ref)^p
/// (p = 1: an ESC's duty cycle times the battery voltage drives the motor, whose speed is
/// proportional to the applied voltage). V_ref = 0: the voltage dependence is not known and the
/// curve is used at any voltage, as the paper's (identified "after removing the battery-voltage
/// influence", at a voltage it does not publish).
/// (docs/paper-facts.md: the published curve is one of rpm²; its printed c0 has a factor-10 typo.)
struct ThrottleCurveParams {
  double c2_rpm2 = 0.0;  ///< quadratic coefficient [rpm²]
  double c1_rpm2 = 0.0;  ///< linear coefficient [rpm²]
  double c0_rpm2 = 0.0;  ///< value at zero throttle [rpm²]
  double reference_voltage_V = 0.0;  ///< V_ref, the battery voltage the curve holds at; 0: none [V]
  double voltage_exponent = 1.0;     ///< p, rotor speed ∝ (V/V_ref)^p at a fixed throttle [-]
};

/// A ground-effect curve given at measured heights instead of by the paper's formula,
/// interpolated by model::HeightTable (PCHIP between the knots, the first value held below
/// them, an inverse-square tail above them). Empty: the formula is used.
struct HeightTableParams {
  std::vector<double> heights_m;  ///< strictly increasing knot heights [m]
  std::vector<double> values;     ///< the curve at each knot [the curve's unit]
  [[nodiscard]] bool empty() const noexcept { return heights_m.empty() && values.empty(); }
};

/// Additional-thrust ratio F_G(h) = g2 / (h² + g1), h in m (paper eq. 5), or a table of F_G.
struct AdditionalThrustParams {
  double g1_m2 = 0.0;  ///< [m²]
  double g2_m2 = 0.0;  ///< [m²]; F_G is dimensionless
  /// When not empty, F_G(h) is this table (values dimensionless) and g1, g2 are not used.
  HeightTableParams table;
};

/// Leveling-torque coefficient M_G(h) = scale·h / (h² + g3·h + g4)² [m], i.e. newton-metres of
/// leveling torque per newton of thrust per unit sin δ (paper eq. 13–14), or a table of M_G.
struct LevelingTorqueParams {
  double g3_m = 0.0;       ///< [m]
  double g4_m2 = 0.0;      ///< [m²]
  double scale_m4 = 0.0;   ///< the paper's g5 role, calibrated to measured torques [m⁴]
  /// When not empty, M_G(h) is this table (values in m) and g3, g4, scale are not used.
  HeightTableParams table;
};

/// Rotor-drag coefficients measured per height (paper eq. 18), interpolated linearly in h and
/// held constant outside the table. The last row is the high-altitude reference.
struct DragTableParams {
  std::vector<double> heights_m;         ///< strictly increasing heights [m]
  std::vector<double> d_x_N_per_mps;     ///< body-x drag coefficient at each height [N/(m/s)]
  std::vector<double> d_y_N_per_mps;     ///< body-y drag coefficient at each height [N/(m/s)]
};

/// One rotor of the airframe, in the mixer's order (model/mixer.hpp: rotor 1 front right, 2 rear
/// left, 3 front left, 4 rear right), as a flight controller configures it.
struct RotorPlacement {
  double x_m = 0.0;        ///< rotor centre along body x (forward); x = y = 0: from the X layout [m]
  double y_m = 0.0;        ///< rotor centre along body y (left) [m]
  double spin = 1.0;       ///< +1 counter-clockwise seen from above (PX4: CA_ROTORn_KM > 0), −1 clockwise [-]
  double px4_motor = 1.0;  ///< PX4's motor number 1…12 (actuator_motors.control[n − 1]) [-]
};

/// Rotor positions, spin directions and motor numbers (issue 12 item 5). The defaults are the X
/// layout of geometry.diagonal_rotor_distance_m with PX4's "Quadrotor x" numbering, which is the
/// mixer's order: motor 1 front right (counter-clockwise), 2 rear left (counter-clockwise), 3
/// front left (clockwise), 4 rear right (clockwise) (PX4 airframe reference, "Quadrotor x").
struct RotorLayoutParams {
  std::array<RotorPlacement, 4> rotors{{{0.0, 0.0, 1.0, 1.0},
                                        {0.0, 0.0, 1.0, 2.0},
                                        {0.0, 0.0, -1.0, 3.0},
                                        {0.0, 0.0, -1.0, 4.0}}};
  /// False when every position is 0 (the file gave none: the X layout is meant).
  [[nodiscard]] bool positionsGiven() const noexcept {
    for (const auto& r : rotors) {
      if (r.x_m != 0.0 || r.y_m != 0.0) return true;
    }
    return false;
  }
};

/// Everything the controller-side model knows about one quadrotor (X configuration).
struct VehicleParams {
  std::string name;                          ///< free text, e.g. "paper_quad"
  double mass_kg = 0.0;                      ///< total flying mass [kg]
  Eigen::Vector3d inertia_kgm2 = Eigen::Vector3d::Zero();  ///< principal inertia Ixx, Iyy, Izz [kg·m²]
  double diagonal_rotor_distance_m = 0.0;    ///< b, distance between diagonal rotor axes [m]
  double propeller_radius_m = 0.0;           ///< propeller radius [m]
  double min_rotor_plane_height_m = 0.0;     ///< lowest physical rotor-plane height (landing gear) [m]
  RotorParams rotor;
  ThrottleCurveParams throttle;
  AdditionalThrustParams additional_thrust;
  LevelingTorqueParams leveling_torque;
  /// The ground effect's fade in forward flight (Cheeseman & Bennett 1955): F_G and M_G are
  /// scaled by v_i²/(v_i² + V²), V the speed in the rotor plane, v_i the rotor's induced velocity
  /// in hover (momentum theory, √(T/(2ρA)) per rotor) [m/s]. 0: no fade (the paper's model).
  double forward_fade_induced_velocity_mps = 0.0;
  DragTableParams drag;
  RotorLayoutParams rotor_layout;  ///< optional in the file: the X layout, PX4's numbering

  /// Every field that is not finite or not in its physical range, with the value and the
  /// expectation. Empty when the parameters are usable.
  [[nodiscard]] std::vector<FieldError> validate() const;
};

}  // namespace geaware::model
