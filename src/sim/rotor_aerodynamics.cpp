// SPDX-License-Identifier: BSD-3-Clause
// Truth-side per-rotor aerodynamics. The physical model, its sources and the calibration are in
// docs/sim-aerodynamics.md; the numbered steps of compute() follow its section "Per step".
// Nothing here reads the controller's ground-effect model (model/ground_effect.hpp).

#include "geaware/sim/rotor_aerodynamics.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "geaware/model/field_check.hpp"

namespace geaware::sim {

using model::formatValue;

namespace {
/// A thrust axis must lie within 15° of z_B (cos 15°): anything else is not a misalignment.
constexpr double kMinAxisZ = 0.9659258262890683;
}  // namespace

const char* toString(GroundEffectLaw law) noexcept {
  switch (law) {
    case GroundEffectLaw::kCalibrated:
      return "calibrated";
    case GroundEffectLaw::kCheesemanBennett:
      return "cheeseman_bennett";
    case GroundEffectLaw::kSanchezCuevas:
      return "sanchez_cuevas";
  }
  return "?";
}

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
  c.range("aero.in_flight_cushion_scale", in_flight_cushion_scale, 0.0, 2.0, kInclusive, "[-]");
  c.range("aero.translational_lift_per_mps2", translational_lift_per_mps2, 0.0, 1.0, kInclusive,
          "1/(m/s)²");
  c.range("aero.translational_lift_max", translational_lift_max, 0.0, 0.5, kInclusive, "[-]");
  c.range("aero.airframe_drag_area_m2", airframe_drag_area_m2, 0.0, 1.0, kInclusive, "m²");
  c.range("aero.air_density_kg_per_m3", air_density_kg_per_m3, 0.5, 1.5, kInclusive, "kg/m³");
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
    const Eigen::Vector3d& a = geometry.thrust_axis_B[i];
    if (!(a.allFinite() && std::abs(a.norm() - 1.0) < 1e-9 && a.z() > kMinAxisZ)) {
      errors.push_back({"geometry.thrust_axis_B[" + idx + "]",
                        a.allFinite() ? "norm " + formatValue(a.norm()) + ", z " + formatValue(a.z())
                                      : "non-finite",
                        "a unit vector within 15° of z_B"});
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
    throw std::invalid_argument(
        model::describeErrors("RotorAerodynamics: invalid parameters:", errors));
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
  inv_range_ = 1.0 / params.ground_effect_range_m;
  for (std::size_t i = 0; i < 4; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    r_x_[k] = geometry.position_B[i].x();
    r_y_[k] = geometry.position_B[i].y();
    r_z_[k] = geometry.position_B[i].z();
    k_T_[k] = geometry.k_T_N_per_rpm2[i];
    spin_k_I_[k] = geometry.spin[i] * geometry.k_I_Nm_per_rpm2[i];
    const Eigen::Vector3d& a = geometry.thrust_axis_B[i];
    a_x_[k] = a.x();
    a_y_[k] = a.y();
    a_z_[k] = a.z();
    tilted_ = tilted_ || a != Eigen::Vector3d::UnitZ();
  }
  lift_ = params.translational_lift_per_mps2 > 0.0 && params.translational_lift_max > 0.0;
  beta_ = params.law == GroundEffectLaw::kCalibrated ? params.own_thrust_fraction : 1.0;
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

void RotorAerodynamics::rotorResolvedTerms(const Eigen::Array4d& z, Eigen::Array4d& num,
                                           Eigen::Array4d& den) const noexcept {
  // 1. Cheeseman & Bennett 1955: T_IGE/T_OGE = 1/(1 − (R/4z)²); its increment ≈ (R/4z)²,
  //    regularised with a core so that it stays finite as z → 0.
  // 2. Impingement of the rotor's own slipstream while it reaches the surface as a separate
  //    jet: a ramp A·(z_m − z), smoothly zero above the wake-merge height z_m.
  // 3. Recirculation very close to the surface: the outwash is trapped and re-ingested, the
  //    rotor-resolved gain stops growing, factor 1/(1 + (z_r/z)⁴) = z⁴/(z⁴ + z_r⁴); below its
  //    peak z* the caller holds it at the peak (groundFactors), so a lower rotor never gets
  //    LESS than a higher one and the leveling torque fades at touchdown instead of reversing.
  // Steps 1–3 over one denominator: l = (num/(z²+c²) + ramp)·z⁴/(z⁴+z_r⁴) = num/den.
  const Eigen::Array4d z2 = z * z;
  const Eigen::Array4d core = z2 + image_core_sq_;
  const Eigen::Array4d x = params_.wake_merge_height_m - z;
  const Eigen::Array4d ramp =
      params_.impingement_slope_per_m * 0.5 * (x + (x * x + merge_soft_sq_).sqrt());
  const Eigen::Array4d z4 = z2 * z2;
  num = (image_num_ + ramp * core) * z4;
  den = core * (z4 + recirc_sq_ * recirc_sq_);
}

Eigen::Array4d RotorAerodynamics::rotorResolvedRaw(const Eigen::Array4d& z) const noexcept {
  Eigen::Array4d num;
  Eigen::Array4d den;
  rotorResolvedTerms(z, num, den);
  return num / den;
}

RotorGroundFactors RotorAerodynamics::groundFactors(
    const std::array<double, 4>& ground_distance_m) const noexcept {
  // The four rotors run in the lanes of Eigen::Array4d (SIMD pairs): the square roots and
  // divisions below are the cost of this function (docs/sim-aerodynamics.md, "Performance").
  if (params_.law != GroundEffectLaw::kCalibrated) return closedFormFactors(ground_distance_m);
  using A4 = Eigen::Array4d;
  RotorGroundFactors out;
  const double range = params_.ground_effect_range_m;
  const double z_min = params_.min_ground_distance_m;
  // Both laws are tapered by 1 − (z/range)⁴ so that they reach exactly zero at the range
  // without a jump (at 1 m the taper changes them by about 1 %).
  const auto taper = [this]<typename T>(T s) -> T {  // T: double or A4, evaluated
    s *= inv_range_;
    s *= s;
    return 1.0 - s * s;
  };
  std::array<bool, 4> in_range{};
  std::array<bool, 4> surface{};
  A4 z;
  A4 z_drag;
  for (std::size_t i = 0; i < 4; ++i) {
    const double d = ground_distance_m[i];
    const auto k = static_cast<Eigen::Index>(i);
    // Non-finite or distant: no surface within range. NaN compares false and lands here too.
    in_range[i] = d < range;
    z[k] = in_range[i] ? std::max(d, z_min) : range;
    // The drag factor is not cut at the ground-effect range (q(2 m) ≈ 0.994), only for no
    // surface at all (d = +∞ or NaN).
    surface[i] = !(std::isnan(d) || d == std::numeric_limits<double>::infinity());
    z_drag[k] = surface[i] ? std::max(d, z_min) : 0.0;
  }
  // The rotor-resolved law l = num/den, held at its peak below z* (rotorResolvedTerms, step 3),
  // and the rotor-drag reduction q(z) = 1 − a/(1 + (z/z_q)²) (paper: Conclusion 3, measured
  // ratio ≈ 0.6), near = 1/den_q, share one division: 1/(den·den_q).
  A4 num;
  A4 den;
  rotorResolvedTerms(z.max(z_star_), num, den);
  const A4 den_q = 1.0 + z_drag * z_drag * inv_drag_height_sq_;
  const A4 inv = 1.0 / (den * den_q);
  A4 near = den * inv;
  for (std::size_t i = 0; i < 4; ++i) {
    if (!surface[i]) near[static_cast<Eigen::Index>(i)] = 0.0;
  }
  Eigen::Map<A4>(out.drag_scale_x.data()) = 1.0 - params_.drag_ground_reduction_x * near;
  Eigen::Map<A4>(out.drag_scale_y.data()) = 1.0 - params_.drag_ground_reduction_y * near;
  A4 l = num * den_q * inv * taper(z);
  for (std::size_t i = 0; i < 4; ++i) {
    if (!in_range[i]) l[static_cast<Eigen::Index>(i)] = 0.0;
  }
  const double z_mean = 0.25 * z.sum();
  const double l_mean = 0.25 * l.sum();
  if (!(z_mean < range)) return out;  // no rotor near a surface: free air, φ = 0
  const double c = collective(z_mean) * taper(z_mean);
  const double inv_cap = 1.0 / (params_.redistribution_cap_per_m * z_mean);
  // Suck-down: the flow under the vehicle escapes through the wide side of the gap, so the
  // rotor-resolved differences are amplified (zero-sum: the total stays l̄) and bounded by
  // M = m·z̄ (x/(1 + (x/M)⁴)^{1/4}): the measured saturation above ~10° of tilt.
  const A4 dx = (1.0 + params_.suckdown_gain) * (l - l_mean);
  const A4 r = dx * inv_cap;
  const A4 r2 = r * r;
  // Floor at zero: the redistribution never takes a rotor below its free-air thrust. Over a
  // plane this never binds (φ ≥ 0.006 for h ≤ 1 m, δ ≤ 25°); it does for partial ground
  // effect (a rotor over the void beside a table edge stays at free air).
  Eigen::Map<A4>(out.phi.data()) = (c + l_mean + dx / (1.0 + r2 * r2).sqrt().sqrt()).max(0.0);
  return out;
}

double RotorAerodynamics::closedFormFraction(double z) const noexcept {
  // x is the sum of the terms under 1/(1 − x) of the law (docs/sim-aerodynamics.md, "Other
  // law families"); φ = 1/(1 − x) − 1 = x/(1 − x).
  // Cheeseman & Bennett 1955: x = (R/4z)², the rotor's own image.
  double x = image_num_ / (z * z);
  // Sanchez-Cuevas et al. 2017: plus the images of the neighbours at d and √2·d and the body
  // term 2·K_b at the rotor-to-centre distance, here at the rotor's OWN distance (collective()
  // is exactly that sum, evaluated there at the mean distance).
  if (params_.law == GroundEffectLaw::kSanchezCuevas) x += collective(z);
  // At z ≥ R/2 x stays below 0.5 for the paper's quadrotor; the bound only keeps an unusual
  // geometry finite.
  x = std::min(x, 0.9);
  return x / (1.0 - x);
}

RotorGroundFactors RotorAerodynamics::closedFormFactors(
    const std::array<double, 4>& ground_distance_m) const noexcept {
  // The same distances, taper and rotor-drag factors as groundFactors(); φ_i from the
  // closed-form law at each rotor's own distance, held at z ≥ R/2 (kClosedFormMinHeightOverRadius).
  RotorGroundFactors out;
  const double range = params_.ground_effect_range_m;
  const double z_min = params_.min_ground_distance_m;
  const double z_law = kClosedFormMinHeightOverRadius * geometry_.radius_m;
  for (std::size_t i = 0; i < 4; ++i) {
    const double d = ground_distance_m[i];
    const bool surface = !(std::isnan(d) || d == std::numeric_limits<double>::infinity());
    const double z_drag = surface ? std::max(d, z_min) : 0.0;
    const double near = surface ? 1.0 / (1.0 + z_drag * z_drag * inv_drag_height_sq_) : 0.0;
    out.drag_scale_x[i] = 1.0 - params_.drag_ground_reduction_x * near;
    out.drag_scale_y[i] = 1.0 - params_.drag_ground_reduction_y * near;
    if (!(d < range)) {
      out.phi[i] = 0.0;  // no surface within range (NaN lands here too)
      continue;
    }
    const double z = std::max(d, z_min);
    double s = z * inv_range_;
    s *= s;
    out.phi[i] = closedFormFraction(std::max(z, z_law)) * (1.0 - s * s);
  }
  return out;
}

std::array<double, 4> RotorAerodynamics::additionalThrustFraction(
    const std::array<double, 4>& ground_distance_m) const noexcept {
  return groundFactors(ground_distance_m).phi;
}

RotorAeroOutput RotorAerodynamics::compute(const std::array<double, 4>& n_rpm,
                                           const Eigen::Matrix3d& R_WB,
                                           const Eigen::Vector3d& v_air_W,
                                           const Eigen::Vector3d& w_B,
                                           const RotorSurroundings& surroundings) const noexcept {
  // 1. Static additional-thrust fraction and drag factors of each rotor from the distances.
  return compute(n_rpm, R_WB, v_air_W, w_B, groundFactors(surroundings.ground_distance_m));
}

template <bool kPerRotor>
Wrench RotorAerodynamics::evaluate(const std::array<double, 4>& n_rpm, const Eigen::Matrix3d& R_WB,
                                   const Eigen::Vector3d& v_air_W, const Eigen::Vector3d& w_B,
                                   const RotorGroundFactors& factors,
                                   RotorAeroOutput* per_rotor) const noexcept {
  // The steps of docs/sim-aerodynamics.md for the four rotors at once, one lane per rotor.
  using A4 = Eigen::Array4d;
  const Eigen::Map<const A4> n(n_rpm.data());
  const Eigen::Map<const A4> phi(factors.phi.data());
  const Eigen::Vector3d v_B = R_WB.transpose() * v_air_W;
  // 2. Free-air thrust of each rotor and their mean (the cushion is fed by all the wakes).
  const A4 t_free = k_T_ * n * n;
  const double t_mean = 0.25 * t_free.sum();
  // 3. Air velocity at each rotor hub, v_B + ω × r_i, in the rotor plane (rotor axis = z_B).
  const A4 v_x = v_B.x() + (w_B.y() * r_z_ - w_B.z() * r_y_);
  const A4 v_y = v_B.y() + (w_B.z() * r_x_ - w_B.x() * r_z_);
  // 4. Forward-flight fade, Cheeseman & Bennett 1955: the image's effect scales with
  //    1/(1 + (V/v_i)²), v_i ∝ n (momentum theory: v_i ∝ √T ∝ n). The smallest normal double
  //    on both sides makes the fade 1 when v_i and V both vanish (a stopped rotor at rest) and
  //    changes no other value (it is below the last bit of any v_i² the plant produces).
  const A4 n_abs = n.abs();
  const A4 v_i = vi_per_rpm_ * n_abs;
  const A4 v_i_sq = v_i * v_i;
  constexpr double kTiny = std::numeric_limits<double>::min();
  const A4 fade = (v_i_sq + kTiny) / (v_i_sq + (v_x * v_x + v_y * v_y) + kTiny);
  const A4 dphi = fade * phi;
  // 5. Thrust: free-air plus the increment (β of it on the rotor's own n², the rest shared).
  const double beta = beta_;
  A4 thrust = t_free + dphi * (beta * t_free + (1.0 - beta) * t_mean);
  if (lift_) {
    // 5a. Translational lift on the free-air part: 1 + min(c·v_h², max) (docs/world.md).
    const A4 lift = (params_.translational_lift_per_mps2 * (v_x * v_x + v_y * v_y))
                        .min(params_.translational_lift_max);
    thrust += lift * t_free;
  }
  if constexpr (kPerRotor) {
    const A4 ratio = thrust / t_free;  // a stopped rotor's lane (0/0) is replaced below
    for (std::size_t i = 0; i < 4; ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      per_rotor->thrust_N[i] = thrust[k];
      per_rotor->gain[i] = t_free[k] > 0.0 ? ratio[k] : 1.0 + dphi[k];
    }
  }
  // 6. Rotor drag per rotor, proportional to n and the in-plane velocity, reduced near the
  //    surface by the factors q(z) (groundFactors).
  const A4 f_x = -params_.drag_x_N_per_mps_per_rpm *
                 Eigen::Map<const A4>(factors.drag_scale_x.data()) * n_abs * v_x;
  const A4 f_y = -params_.drag_y_N_per_mps_per_rpm *
                 Eigen::Map<const A4>(factors.drag_scale_y.data()) * n_abs * v_y;
  // 7. Torque about the CoM: Σ r_i × F_i plus the aerodynamic reaction torques along z_B.
  const A4 q = spin_k_I_ * n * n * (1.0 - params_.reaction_torque_reduction * dphi);
  if (tilted_) return tiltedWrench(thrust, f_x, f_y, q);
  Wrench w;
  w.force_B = Eigen::Vector3d(f_x.sum(), f_y.sum(), thrust.sum());
  w.torque_B =
      Eigen::Vector3d((r_y_ * thrust - r_z_ * f_y).sum(), (r_z_ * f_x - r_x_ * thrust).sum(),
                      (r_x_ * f_y - r_y_ * f_x).sum() + q.sum());
  return w;
}

Wrench RotorAerodynamics::tiltedWrench(const Eigen::Array4d& thrust, const Eigen::Array4d& f_x,
                                       const Eigen::Array4d& f_y,
                                       const Eigen::Array4d& q) const noexcept {
  // 7'. Each rotor's thrust T_i·a_i and reaction torque Q_i·a_i along its own axis a_i; the
  //     rotor drag (f_x, f_y) stays in the body plane. Torque Σ r_i × F_i + Σ Q_i·a_i.
  using A4 = Eigen::Array4d;
  const A4 F_x = thrust * a_x_ + f_x;
  const A4 F_y = thrust * a_y_ + f_y;
  const A4 F_z = thrust * a_z_;
  Wrench w;
  w.force_B = Eigen::Vector3d(F_x.sum(), F_y.sum(), F_z.sum());
  w.torque_B = Eigen::Vector3d((r_y_ * F_z - r_z_ * F_y + q * a_x_).sum(),
                               (r_z_ * F_x - r_x_ * F_z + q * a_y_).sum(),
                               (r_x_ * F_y - r_y_ * F_x + q * a_z_).sum());
  return w;
}

RotorAeroOutput RotorAerodynamics::compute(const std::array<double, 4>& n_rpm,
                                           const Eigen::Matrix3d& R_WB,
                                           const Eigen::Vector3d& v_air_W,
                                           const Eigen::Vector3d& w_B,
                                           const RotorGroundFactors& factors) const noexcept {
  RotorAeroOutput out;
  out.wrench = evaluate<true>(n_rpm, R_WB, v_air_W, w_B, factors, &out);
  return out;
}

Wrench RotorAerodynamics::wrench(const std::array<double, 4>& n_rpm, const Eigen::Matrix3d& R_WB,
                                 const Eigen::Vector3d& v_air_W, const Eigen::Vector3d& w_B,
                                 const RotorGroundFactors& factors) const noexcept {
  return evaluate<false>(n_rpm, R_WB, v_air_W, w_B, factors, nullptr);
}

}  // namespace geaware::sim
