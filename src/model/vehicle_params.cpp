#include "geaware/model/vehicle_params.hpp"

#include <cmath>
#include <string>

#include "geaware/model/field_check.hpp"

namespace geaware::model {
namespace {

/// A curve table under `key` (e.g. "ground_effect.additional_thrust.table") with the values
/// list named `values_key`: at least 2 knots, one value per height, heights strictly increasing
/// in (0, 100] m, values in the curve's range.
void checkHeightTable(FieldChecker& c, const std::string& key, const std::string& values_key,
                      const HeightTableParams& t, double lo, double hi, LowerBound lower,
                      std::string_view unit) {
  const std::size_t n = t.heights_m.size();
  if (n < 2) {
    c.fail(key + ".heights_m", std::to_string(n) + " heights", "at least 2 heights");
    return;
  }
  if (t.values.size() != n) {
    c.fail(key, "heights_m: " + std::to_string(n) + ", " + values_key + ": " +
                    std::to_string(t.values.size()) + " entries",
           "the same number of entries in heights_m and " + values_key);
    return;
  }
  using enum LowerBound;
  for (std::size_t i = 0; i < n; ++i) {
    const std::string idx = "[" + std::to_string(i) + "]";
    const bool h_ok = c.range(key + ".heights_m" + idx, t.heights_m[i], 0.0, 100.0, kExclusive, "m");
    c.range(key + "." + values_key + idx, t.values[i], lo, hi, lower, unit);
    if (h_ok && i > 0 && !(t.heights_m[i] > t.heights_m[i - 1])) {
      c.fail(key + ".heights_m" + idx, formatValue(t.heights_m[i]),
             "strictly greater than the previous height " + formatValue(t.heights_m[i - 1]) + " m");
    }
  }
}

}  // namespace

std::vector<FieldError> VehicleParams::validate() const {
  std::vector<FieldError> errors;
  // Every check names the key path as written in the vehicle file.
  FieldChecker c(errors);
  using enum LowerBound;

  // Generous physical ranges: a toy micro-drone to a heavy-lift octo-sized vehicle.
  c.range("mass_kg", mass_kg, 0.0, 1000.0, kExclusive, "kg");
  const char* axes[3] = {"inertia_kgm2.xx", "inertia_kgm2.yy", "inertia_kgm2.zz"};
  bool inertia_ok = true;
  for (int i = 0; i < 3; ++i)
    inertia_ok &= c.range(axes[i], inertia_kgm2[i], 0.0, 1000.0, kExclusive, "kg·m²");
  if (inertia_ok) {
    // Principal moments of a real body satisfy the triangle inequalities.
    for (int i = 0; i < 3; ++i) {
      const double others = inertia_kgm2[(i + 1) % 3] + inertia_kgm2[(i + 2) % 3];
      if (inertia_kgm2[i] > others * (1.0 + 1e-9)) {
        c.fail(axes[i], formatValue(inertia_kgm2[i]),
               "at most the sum of the other two principal moments (" + formatValue(others) +
                   " kg·m²): no rigid body has these moments");
      }
    }
  }
  const bool b_ok = c.range("geometry.diagonal_rotor_distance_m", diagonal_rotor_distance_m, 0.0,
                            10.0, kExclusive, "m");
  const bool r_ok =
      c.range("geometry.propeller_radius_m", propeller_radius_m, 0.0, 5.0, kExclusive, "m");
  if (b_ok && r_ok) {
    // Adjacent rotors of an X quadrotor are b/√2 apart; their discs must not overlap.
    const double adjacent = diagonal_rotor_distance_m / std::sqrt(2.0);
    if (2.0 * propeller_radius_m > adjacent) {
      c.fail("geometry.propeller_radius_m", formatValue(propeller_radius_m),
             "at most half the adjacent-rotor distance b/√2 = " + formatValue(adjacent) +
                 " m, or the propellers overlap");
    }
  }
  c.range("geometry.min_rotor_plane_height_m", min_rotor_plane_height_m, 0.0, 10.0, kInclusive,
          "m");

  c.range("rotor.k_T_N_per_rpm2", rotor.k_T_N_per_rpm2, 0.0, 1.0, kExclusive, "N/rpm²");
  c.range("rotor.k_TX_N_per_rpm2", rotor.k_TX_N_per_rpm2, 0.0, 1.0, kExclusive, "N/rpm²");
  c.range("rotor.k_TY_N_per_rpm2", rotor.k_TY_N_per_rpm2, 0.0, 1.0, kExclusive, "N/rpm²");
  c.range("rotor.k_I_Nm_per_rpm2", rotor.k_I_Nm_per_rpm2, 0.0, 1.0, kExclusive, "N·m/rpm²");
  c.range("rotor.J_R_kgm2", rotor.J_R_kgm2, 0.0, 1.0, kInclusive, "kg·m²");

  const auto& t = throttle;
  const bool c2_ok = c.range("throttle_curve.c2_rpm2", t.c2_rpm2, -1e12, 1e12, kInclusive, "rpm²");
  const bool c1_ok = c.range("throttle_curve.c1_rpm2", t.c1_rpm2, -1e12, 1e12, kInclusive, "rpm²");
  const bool c0_ok = c.range("throttle_curve.c0_rpm2", t.c0_rpm2, 0.0, 1e12, kInclusive,
                             "rpm² (n² at zero throttle)");
  if (c2_ok && c1_ok && c0_ok) {
    // n² must rise strictly over the whole throttle range so that the curve can be inverted:
    // its slope c1 + 2·c2·t is linear in t, so checking both ends suffices.
    if (!(t.c1_rpm2 > 0.0 && t.c1_rpm2 + 2.0 * t.c2_rpm2 > 0.0)) {
      c.fail("throttle_curve", "c1=" + formatValue(t.c1_rpm2) + ", c2=" + formatValue(t.c2_rpm2),
             "n² strictly increasing on throttle [0, 1] (c1 > 0 and c1 + 2·c2 > 0)");
    }
  }

  if (additional_thrust.table.empty()) {
    c.range("ground_effect.additional_thrust.g1_m2", additional_thrust.g1_m2, 0.0, 100.0,
            kExclusive, "m²");
    c.range("ground_effect.additional_thrust.g2_m2", additional_thrust.g2_m2, 0.0, 100.0,
            kInclusive, "m²");
  } else {
    // F_G > −1 keeps the thrust positive; 10 is ten times the strongest cushion on record.
    checkHeightTable(c, "ground_effect.additional_thrust.table", "F_G", additional_thrust.table,
                     -1.0, 10.0, kExclusive, "(dimensionless)");
  }
  const auto& l = leveling_torque;
  if (l.table.empty()) {
    const bool g3_ok =
        c.range("ground_effect.leveling_torque.g3_m", l.g3_m, -100.0, 100.0, kInclusive, "m");
    const bool g4_ok =
        c.range("ground_effect.leveling_torque.g4_m2", l.g4_m2, 0.0, 100.0, kExclusive, "m²");
    c.range("ground_effect.leveling_torque.scale_m4", l.scale_m4, 0.0, 100.0, kInclusive, "m⁴");
    if (g3_ok && g4_ok && l.g3_m < 0.0 && l.g3_m * l.g3_m >= 4.0 * l.g4_m2) {
      // h² + g3·h + g4 would vanish at some h > 0 and M_G would be infinite there.
      c.fail("ground_effect.leveling_torque",
             "g3=" + formatValue(l.g3_m) + ", g4=" + formatValue(l.g4_m2),
             "h² + g3·h + g4 > 0 for every h ≥ 0 (g3 ≥ 0 or g3² < 4·g4)");
    }
  } else {
    // |M_G| ≤ 1 m: a leveling torque of one thrust times one metre per unit sin δ is already
    // forty times the measured peak (0.023 m).
    checkHeightTable(c, "ground_effect.leveling_torque.table", "M_G_m", l.table, -1.0, 1.0,
                     kInclusive, "m");
  }

  const std::size_t n = drag.heights_m.size();
  if (n == 0) {
    c.fail("drag.heights_m", "[]", "at least one height");
  } else if (drag.d_x_N_per_mps.size() != n || drag.d_y_N_per_mps.size() != n) {
    c.fail("drag", "heights_m: " + std::to_string(n) + ", d_x_N_per_mps: " +
                        std::to_string(drag.d_x_N_per_mps.size()) + ", d_y_N_per_mps: " +
                        std::to_string(drag.d_y_N_per_mps.size()) + " entries",
           "the same number of entries in heights_m, d_x_N_per_mps and d_y_N_per_mps");
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      const std::string idx = "[" + std::to_string(i) + "]";
      c.range("drag.heights_m" + idx, drag.heights_m[i], 0.0, 1000.0, kInclusive, "m");
      c.range("drag.d_x_N_per_mps" + idx, drag.d_x_N_per_mps[i], 0.0, 100.0, kInclusive, "N/(m/s)");
      c.range("drag.d_y_N_per_mps" + idx, drag.d_y_N_per_mps[i], 0.0, 100.0, kInclusive, "N/(m/s)");
      if (i > 0 && !(drag.heights_m[i] > drag.heights_m[i - 1])) {
        c.fail("drag.heights_m" + idx, formatValue(drag.heights_m[i]),
               "strictly greater than the previous height " + formatValue(drag.heights_m[i - 1]) +
                   " m");
      }
    }
  }
  return errors;
}

}  // namespace geaware::model
