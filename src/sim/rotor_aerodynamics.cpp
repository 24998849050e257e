// Truth-side per-rotor aerodynamics. The physical model, its sources and the calibration are in
// docs/sim-aerodynamics.md; the numbered steps of compute() follow its section "Per step".
// Nothing here reads the controller's ground-effect model (model/ground_effect.hpp).

#include "geaware/sim/rotor_aerodynamics.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "geaware/model/field_check.hpp"

namespace geaware::sim {

using model::formatValue;

std::vector<model::FieldError> RotorAeroParams::validate() const {
  std::vector<model::FieldError> e;
  model::FieldChecker c(e);
  using enum model::LowerBound;
  c.range("aero.body_coefficient", body_coefficient, 0.0, 20.0, kInclusive, "[-]");
  c.range("aero.image_core_fraction", image_core_fraction, 1e-3, 10.0, kInclusive, "[-]");
  c.range("aero.impingement_slope_per_m", impingement_slope_per_m, 0.0, 100.0, kInclusive, "1/m");
  c.range("aero.wake_merge_height_m", wake_merge_height_m, 0.0, 10.0, kInclusive, "m");
  c.range("aero.wake_merge_softness_m", wake_merge_softness_m, 1e-6, 1.0, kInclusive, "m");
  c.range("aero.recirculation_height_m", recirculation_height_m, 0.0, 1.0, kInclusive, "m");
  c.range("aero.suckdown_gain", suckdown_gain, 0.0, 100.0, kInclusive, "[-]");
  c.range("aero.redistribution_cap_per_m", redistribution_cap_per_m, 1e-6, 100.0, kInclusive,
          "1/m");
  c.range("aero.own_thrust_fraction", own_thrust_fraction, 0.0, 1.0, kInclusive, "[-]");
  c.range("aero.reaction_torque_reduction", reaction_torque_reduction, 0.0, 1.0, kInclusive, "[-]");
  c.range("aero.ground_effect_range_m", ground_effect_range_m, 0.1, 1000.0, kInclusive, "m");
  c.range("aero.min_ground_distance_m", min_ground_distance_m, 1e-4, 0.1, kInclusive, "m");
  c.range("aero.induced_velocity_mps", induced_velocity_mps, 0.1, 100.0, kInclusive, "m/s");
  c.range("aero.induced_velocity_ref_rpm", induced_velocity_ref_rpm, 1.0, 1e6, kInclusive, "rpm");
  c.range("aero.drag_x_N_per_mps_per_rpm", drag_x_N_per_mps_per_rpm, 0.0, 1e-2, kInclusive,
          "N/(m/s)/rpm");
  c.range("aero.drag_y_N_per_mps_per_rpm", drag_y_N_per_mps_per_rpm, 0.0, 1e-2, kInclusive,
          "N/(m/s)/rpm");
  c.range("aero.drag_ground_reduction_x", drag_ground_reduction_x, 0.0, 0.99, kInclusive, "[-]");
  c.range("aero.drag_ground_reduction_y", drag_ground_reduction_y, 0.0, 0.99, kInclusive, "[-]");
  c.range("aero.drag_ground_height_m", drag_ground_height_m, 1e-3, 10.0, kInclusive, "m");
  if (min_ground_distance_m >= ground_effect_range_m) {
    c.fail("aero.min_ground_distance_m", formatValue(min_ground_distance_m),
           "less than aero.ground_effect_range_m");
  }
  return e;
}

RotorAerodynamics::RotorAerodynamics(const RotorGeometry& geometry, const RotorAeroParams& params)
    : geometry_(geometry), params_(params) {
  std::vector<model::FieldError> errors = params.validate();
  if (!(std::isfinite(geometry.radius_m) && geometry.radius_m > 0.0)) {
    errors.push_back(
        {"geometry.radius_m", formatValue(geometry.radius_m), "a finite radius > 0 m"});
  }
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < 4; ++i) {
    const std::string idx = std::to_string(i + 1);
    if (!geometry.position_B[i].allFinite()) {
      errors.push_back(
          {"geometry.position_B[" + idx + "]", "non-finite", "finite coordinates [m]"});
    }
    if (!(std::isfinite(geometry.k_T_N_per_rpm2[i]) && geometry.k_T_N_per_rpm2[i] >= 0.0)) {
      errors.push_back({"geometry.k_T_N_per_rpm2[" + idx + "]",
                        formatValue(geometry.k_T_N_per_rpm2[i]), "finite, ≥ 0"});
    }
    if (!(std::isfinite(geometry.k_I_Nm_per_rpm2[i]) && geometry.k_I_Nm_per_rpm2[i] >= 0.0)) {
      errors.push_back({"geometry.k_I_Nm_per_rpm2[" + idx + "]",
                        formatValue(geometry.k_I_Nm_per_rpm2[i]), "finite, ≥ 0"});
    }
    if (!(geometry.spin[i] == 1.0 || geometry.spin[i] == -1.0)) {
      errors.push_back({"geometry.spin[" + idx + "]", formatValue(geometry.spin[i]), "+1 or −1"});
    }
    centre += geometry.position_B[i] / 4.0;
  }
  // Geometry of the interaction terms: the mean rotor-to-centre distance in the rotor plane
  // (arm) and, for the X layout, the adjacent spacing d = √2·arm, diagonal spacing √2·d.
  double arm = 0.0;
  for (std::size_t i = 0; i < 4; ++i)
    arm += (geometry.position_B[i] - centre).head<2>().norm() / 4.0;
  if (!(std::isfinite(arm) && arm > geometry.radius_m * 0.5)) {
    errors.push_back({"geometry.position_B", "mean arm " + formatValue(arm) + " m",
                      "rotors spread wider than half a propeller radius"});
  }
  if (!errors.empty()) {
    std::string msg = "RotorAerodynamics: invalid parameters:";
    for (const auto& f : errors)
      msg += "\n  " + f.field + " = " + f.value + " (expected " + f.expected + ")";
    throw std::invalid_argument(msg);
  }
  const double R = geometry.radius_m;
  radius_sq_ = R * R;
  image_num_ = radius_sq_ / 16.0;
  image_core_sq_ = (params.image_core_fraction * R) * (params.image_core_fraction * R);
  arm_sq_ = arm * arm;
  adjacent_sq_ = 2.0 * arm_sq_;
  diagonal_sq_ = 2.0 * adjacent_sq_;
  merge_soft_sq_ = params.wake_merge_softness_m * params.wake_merge_softness_m;
  recirc_sq_ = params.recirculation_height_m * params.recirculation_height_m;
  inv_drag_height_sq_ = 1.0 / (params.drag_ground_height_m * params.drag_ground_height_m);
  vi_per_rpm_ = params.induced_velocity_mps / params.induced_velocity_ref_rpm;
  // z*: the peak of the (unimodal) rotor-resolved term on [min distance, merge height], by
  // golden-section search (once, here).
  double lo = params.min_ground_distance_m;
  double hi = std::max(params.wake_merge_height_m, 2.0 * lo);
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int k = 0; k < 80; ++k) {
    const double m1 = hi - g * (hi - lo);
    const double m2 = lo + g * (hi - lo);
    if (rotorResolvedRaw(m1) > rotorResolvedRaw(m2)) {
      hi = m2;
    } else {
      lo = m1;
    }
  }
  z_star_ = 0.5 * (lo + hi);
}

double RotorAerodynamics::collective(double z) const noexcept {
  // Each term z/(c + 4z²)^{3/2} is the axial induced velocity of an image rotor at horizontal
  // distance √c and depth 2z, per unit R².
  // Sanchez-Cuevas, Heredia & Ollero 2017 (Int. J. Aerospace Eng., "Characterization of the
  // aerodynamic ground effect and its influence in multirotor control", eq. for T_IGE/T_OGE):
  // the images of the neighbouring rotors at d and √2·d and the body term 2·K_b at the arm b,
  // here evaluated at the MEAN rotor distance and applied to every rotor alike: it is the
  // vehicle-scale cushion under the merged wakes and the fuselage, which pushes the whole
  // vehicle and makes no torque. Linearised (the increment, not 1/(1 − x)) to stay finite.
  // The three terms z/t_k, t_k = (c_k + 4z²)^{3/2}, over one common denominator (one division).
  const double z4 = 4.0 * z * z;
  const double s1 = adjacent_sq_ + z4;
  const double s2 = diagonal_sq_ + z4;
  const double s3 = arm_sq_ + z4;
  const double t1 = s1 * std::sqrt(s1);
  const double t2 = s2 * std::sqrt(s2);
  const double t3 = s3 * std::sqrt(s3);
  return radius_sq_ * z * (t2 * t3 + 0.5 * t1 * t3 + 2.0 * params_.body_coefficient * t1 * t2) /
         (t1 * t2 * t3);
}

double RotorAerodynamics::rotorResolvedRaw(double z) const noexcept {
  // 1. Cheeseman & Bennett 1955: T_IGE/T_OGE = 1/(1 − (R/4z)²); its increment ≈ (R/4z)²,
  //    regularised with a core so that it stays finite as z → 0.
  // 2. Impingement of the rotor's own slipstream while it reaches the surface as a separate
  //    jet: a ramp A·(z_m − z), smoothly zero above the wake-merge height z_m.
  // 3. Recirculation very close to the surface: the outwash is trapped and re-ingested, the
  //    rotor-resolved gain stops growing, factor 1/(1 + (z_r/z)⁴) = z⁴/(z⁴ + z_r⁴); below its
  //    peak z* the caller holds it at the peak (rotorResolved), so a lower rotor never gets
  //    LESS than a higher one and the leveling torque fades at touchdown instead of reversing.
  // Steps 1–3 share one division: (num/(z²+c²) + ramp)·z⁴/(z⁴+z_r⁴).
  const double z2 = z * z;
  const double core = z2 + image_core_sq_;
  const double x = params_.wake_merge_height_m - z;
  const double ramp =
      params_.impingement_slope_per_m * 0.5 * (x + std::sqrt(x * x + merge_soft_sq_));
  const double z4 = z2 * z2;
  return (image_num_ + ramp * core) * z4 / (core * (z4 + recirc_sq_ * recirc_sq_));
}

std::array<double, 4> RotorAerodynamics::additionalThrustFraction(
    const std::array<double, 4>& ground_distance_m) const noexcept {
  const double range = params_.ground_effect_range_m;
  // Both laws are tapered by 1 − (z/range)⁴ so that they reach exactly zero at the range
  // without a jump (at 1 m the taper changes them by about 1 %).
  const auto taper = [range](double z) {
    const double s = z / range;
    const double s2 = s * s;
    return 1.0 - s2 * s2;
  };
  std::array<double, 4> l{};
  double z_mean = 0.0;
  double l_mean = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    const double d = ground_distance_m[i];
    // Non-finite or distant: no surface within range. NaN compares false and lands here too.
    const bool in_range = d < range;
    const double z = in_range ? std::max(d, params_.min_ground_distance_m) : range;
    l[i] = in_range ? rotorResolved(z) * taper(z) : 0.0;
    z_mean += 0.25 * z;
    l_mean += 0.25 * l[i];
  }
  std::array<double, 4> phi{};
  if (!(z_mean < range)) return phi;  // no rotor near a surface: free air
  const double c = collective(z_mean) * taper(z_mean);
  const double inv_cap = 1.0 / (params_.redistribution_cap_per_m * z_mean);
  const double gain = 1.0 + params_.suckdown_gain;
  for (std::size_t i = 0; i < 4; ++i) {
    // Suck-down: the flow under the vehicle escapes through the wide side of the gap, so the
    // rotor-resolved differences are amplified (zero-sum: the total stays l̄) and bounded by
    // M = m·z̄ (x/(1 + (x/M)⁴)^{1/4}): the measured saturation above ~10° of tilt.
    const double dx = gain * (l[i] - l_mean);
    const double r = dx * inv_cap;
    const double r2 = r * r;
    // Floor at zero: the redistribution never takes a rotor below its free-air thrust. Over a
    // plane this never binds (φ ≥ 0.006 for h ≤ 1 m, δ ≤ 25°); it does for partial ground
    // effect (a rotor over the void beside a table edge stays at free air).
    phi[i] = std::max(0.0, c + l_mean + dx / std::sqrt(std::sqrt(1.0 + r2 * r2)));
  }
  return phi;
}

RotorAeroOutput RotorAerodynamics::compute(const std::array<double, 4>& n_rpm,
                                           const Eigen::Matrix3d& R_WB,
                                           const Eigen::Vector3d& v_air_W,
                                           const Eigen::Vector3d& w_B,
                                           const RotorSurroundings& surroundings) const noexcept {
  RotorAeroOutput out;
  // 1. Static additional-thrust fraction of each rotor from the distances.
  const std::array<double, 4> phi = additionalThrustFraction(surroundings.ground_distance_m);
  const Eigen::Vector3d v_B = R_WB.transpose() * v_air_W;
  // 2. Free-air thrust of each rotor and their mean (the cushion is fed by all the wakes).
  std::array<double, 4> t_free{};
  double t_mean = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    t_free[i] = geometry_.k_T_N_per_rpm2[i] * n_rpm[i] * n_rpm[i];
    t_mean += 0.25 * t_free[i];
  }
  const double beta = params_.own_thrust_fraction;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3d& r = geometry_.position_B[i];
    // 3. Air velocity at the rotor hub, in the rotor plane (rotor axis = z_B).
    const Eigen::Vector3d v_rot = v_B + w_B.cross(r);
    const double v_inplane_sq = v_rot.x() * v_rot.x() + v_rot.y() * v_rot.y();
    // 4. Forward-flight fade, Cheeseman & Bennett 1955: the image's effect scales with
    //    1/(1 + (V/v_i)²), v_i ∝ n (momentum theory: v_i ∝ √T ∝ n).
    const double v_i = vi_per_rpm_ * std::abs(n_rpm[i]);
    const double v_i_sq = v_i * v_i;
    const double denom = v_i_sq + v_inplane_sq;
    const double fade = denom > 0.0 ? v_i_sq / denom : 1.0;
    const double dphi = fade * phi[i];
    // 5. Thrust: free-air plus the increment (β of it on the rotor's own n², the rest shared).
    const double thrust = t_free[i] + dphi * (beta * t_free[i] + (1.0 - beta) * t_mean);
    out.thrust_N[i] = thrust;
    out.gain[i] = t_free[i] > 0.0 ? thrust / t_free[i] : 1.0 + dphi;
    // 6. Rotor drag per rotor, proportional to n and the in-plane velocity, reduced near the
    //    surface by q(z) = 1 − a/(1 + (z/z_q)²) (paper: Conclusion 3, measured ratio ≈ 0.6).
    const double d = surroundings.ground_distance_m[i];
    // (No surface, d = ∞ or NaN: near = 0. Not cut at the ground-effect range: q(2 m) ≈ 0.994.)
    const double z_d = std::max(d, params_.min_ground_distance_m);
    const double near = std::isfinite(z_d) ? 1.0 / (1.0 + z_d * z_d * inv_drag_height_sq_) : 0.0;
    const double n_abs = std::abs(n_rpm[i]);
    const Eigen::Vector3d f(-params_.drag_x_N_per_mps_per_rpm *
                                (1.0 - params_.drag_ground_reduction_x * near) * n_abs * v_rot.x(),
                            -params_.drag_y_N_per_mps_per_rpm *
                                (1.0 - params_.drag_ground_reduction_y * near) * n_abs * v_rot.y(),
                            thrust);
    force += f;
    // 7. Torque about the CoM: r × F plus the aerodynamic reaction torque along the spin axis.
    const double q = geometry_.k_I_Nm_per_rpm2[i] * n_rpm[i] * n_rpm[i] *
                     (1.0 - params_.reaction_torque_reduction * dphi);
    torque += r.cross(f);
    torque.z() += geometry_.spin[i] * q;
  }
  out.wrench.force_B = force;
  out.wrench.torque_B = torque;
  return out;
}

}  // namespace geaware::sim
