// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/model/vehicle_schema.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "geaware/model/mixer.hpp"
#include "geaware/model/motor.hpp"

namespace geaware::model {
namespace {

using P = VehicleParams;
using S = ParamSpec<P>;
using enum LowerBound;
using enum ParamForm;

/// Generous physical ranges: a toy micro-drone to a heavy-lift octo-sized vehicle.
constexpr ParamRange kMass{0.0, 1000.0, kExclusive};
constexpr ParamRange kInertia{0.0, 1000.0, kExclusive};
constexpr ParamRange kCoefficient{0.0, 1.0, kExclusive};
constexpr ParamRange kCurveCoefficient{-1e12, 1e12, kInclusive};
constexpr ParamRange kKnotHeight{0.0, 100.0, kExclusive};

S number(std::string_view key, std::string_view unit, ParamRange range, double& (*get)(P&),
         bool fitted = false) {
  S s;
  s.key = key;
  s.unit = unit;
  s.range = range;
  s.number = get;
  s.fitted = fitted;
  return s;
}

S fitted(std::string_view key, std::string_view unit, ParamRange range, double& (*get)(P&)) {
  return number(key, unit, range, get, true);
}

/// A formula key of `curve`.
S formula(std::string_view curve, std::string_view key, std::string_view unit, ParamRange range,
          double& (*get)(P&)) {
  S s = fitted(key, unit, range, get);
  s.form = kFormula;
  s.curve = curve;
  return s;
}

/// A column of `table`; the first column of a table is its heights, strictly increasing.
S column(std::string_view table, std::string_view key, std::string_view unit, ParamRange range,
         std::vector<double>& (*get)(P&), std::size_t min_rows = 1) {
  S s;
  s.key = key;
  s.unit = unit;
  s.kind = ParamKind::kList;
  s.range = range;
  s.list = get;
  s.table = table;
  s.min_rows = min_rows;
  return s;
}

/// A column of the table form of `curve` (its table is "<curve>.table").
S curveColumn(std::string_view curve, std::string_view table, std::string_view key,
              std::string_view unit, ParamRange range, std::vector<double>& (*get)(P&),
              std::size_t min_rows = 1) {
  S s = column(table, key, unit, range, get, min_rows);
  s.form = kTable;
  s.curve = curve;
  return s;
}

/// Name, mass, inertia, geometry, rotor and throttle curve.
std::vector<S> bodySpecs() {
  S name;
  name.key = "name";
  name.kind = ParamKind::kText;
  name.text = [](P& p) -> std::string& { return p.name; };

  S c0 = fitted("throttle_curve.c0_rpm2", "rpm²", {0.0, 1e12, kInclusive},
                [](P& p) -> double& { return p.throttle.c0_rpm2; });
  c0.note = "(n² at zero throttle)";
  // The throttle curve's battery-voltage dependence n ∝ (V/V_ref)^p (issue 11 item 4, issue 12
  // item 4): optional, a vehicle file without it has none (V_ref = 0).
  S v_ref = fitted("throttle_curve.reference_voltage_V", "V", {0.0, 1000.0, kInclusive},
                   [](P& p) -> double& { return p.throttle.reference_voltage_V; });
  v_ref.note = "(0: no voltage dependence)";
  v_ref.optional = true;
  S exponent = fitted("throttle_curve.voltage_exponent", "", {0.0, 4.0, kInclusive},
                      [](P& p) -> double& { return p.throttle.voltage_exponent; });
  exponent.optional = true;

  return {
      name,
      number("mass_kg", "kg", kMass, [](P& p) -> double& { return p.mass_kg; }),
      number("inertia_kgm2.xx", "kg·m²", kInertia, [](P& p) -> double& { return p.inertia_kgm2[0]; }),
      number("inertia_kgm2.yy", "kg·m²", kInertia, [](P& p) -> double& { return p.inertia_kgm2[1]; }),
      number("inertia_kgm2.zz", "kg·m²", kInertia, [](P& p) -> double& { return p.inertia_kgm2[2]; }),
      number("geometry.diagonal_rotor_distance_m", "m", {0.0, 10.0, kExclusive},
             [](P& p) -> double& { return p.diagonal_rotor_distance_m; }),
      number("geometry.propeller_radius_m", "m", {0.0, 5.0, kExclusive},
             [](P& p) -> double& { return p.propeller_radius_m; }),
      number("geometry.min_rotor_plane_height_m", "m", {0.0, 10.0, kInclusive},
             [](P& p) -> double& { return p.min_rotor_plane_height_m; }),
      fitted("rotor.k_T_N_per_rpm2", "N/rpm²", kCoefficient,
             [](P& p) -> double& { return p.rotor.k_T_N_per_rpm2; }),
      fitted("rotor.k_TX_N_per_rpm2", "N/rpm²", kCoefficient,
             [](P& p) -> double& { return p.rotor.k_TX_N_per_rpm2; }),
      fitted("rotor.k_TY_N_per_rpm2", "N/rpm²", kCoefficient,
             [](P& p) -> double& { return p.rotor.k_TY_N_per_rpm2; }),
      fitted("rotor.k_I_Nm_per_rpm2", "N·m/rpm²", kCoefficient,
             [](P& p) -> double& { return p.rotor.k_I_Nm_per_rpm2; }),
      fitted("rotor.J_R_kgm2", "kg·m²", {0.0, 1.0, kInclusive},
             [](P& p) -> double& { return p.rotor.J_R_kgm2; }),
      fitted("throttle_curve.c2_rpm2", "rpm²", kCurveCoefficient,
             [](P& p) -> double& { return p.throttle.c2_rpm2; }),
      fitted("throttle_curve.c1_rpm2", "rpm²", kCurveCoefficient,
             [](P& p) -> double& { return p.throttle.c1_rpm2; }),
      c0,
      v_ref,
      exponent,
  };
}

/// The ground-effect curves, each as a formula or a table.
std::vector<S> groundEffectSpecs() {
  constexpr std::string_view kThrust = "ground_effect.additional_thrust";
  constexpr std::string_view kThrustTable = "ground_effect.additional_thrust.table";
  constexpr std::string_view kLeveling = "ground_effect.leveling_torque";
  constexpr std::string_view kLevelingTable = "ground_effect.leveling_torque.table";
  // F_G > −1 keeps the thrust positive; 10 is ten times the strongest cushion on record.
  S F_G = curveColumn(kThrust, kThrustTable, "ground_effect.additional_thrust.table.F_G", "",
                      {-1.0, 10.0, kExclusive}, [](P& p) -> std::vector<double>& {
                        return p.additional_thrust.table.values;
                      });
  F_G.note = "(dimensionless)";
  // The ground effect's forward-flight fade (issue 13 item 2): optional, a file without it has
  // none (the paper's model).
  S fade = fitted("ground_effect.forward_fade.induced_velocity_mps", "m/s", {0.0, 100.0, kInclusive},
                  [](P& p) -> double& { return p.forward_fade_induced_velocity_mps; });
  fade.note = "(0: no fade)";
  fade.optional = true;

  return {
      formula(kThrust, "ground_effect.additional_thrust.g1_m2", "m²", {0.0, 100.0, kExclusive},
              [](P& p) -> double& { return p.additional_thrust.g1_m2; }),
      formula(kThrust, "ground_effect.additional_thrust.g2_m2", "m²", {0.0, 100.0, kInclusive},
              [](P& p) -> double& { return p.additional_thrust.g2_m2; }),
      curveColumn(kThrust, kThrustTable, "ground_effect.additional_thrust.table.heights_m", "m",
                  kKnotHeight,
                  [](P& p) -> std::vector<double>& { return p.additional_thrust.table.heights_m; },
                  2),
      F_G,
      formula(kLeveling, "ground_effect.leveling_torque.g3_m", "m", {-100.0, 100.0, kInclusive},
              [](P& p) -> double& { return p.leveling_torque.g3_m; }),
      formula(kLeveling, "ground_effect.leveling_torque.g4_m2", "m²", {0.0, 100.0, kExclusive},
              [](P& p) -> double& { return p.leveling_torque.g4_m2; }),
      formula(kLeveling, "ground_effect.leveling_torque.scale_m4", "m⁴", {0.0, 100.0, kInclusive},
              [](P& p) -> double& { return p.leveling_torque.scale_m4; }),
      curveColumn(kLeveling, kLevelingTable, "ground_effect.leveling_torque.table.heights_m", "m",
                  kKnotHeight,
                  [](P& p) -> std::vector<double>& { return p.leveling_torque.table.heights_m; },
                  2),
      // |M_G| ≤ 1 m: a leveling torque of one thrust times one metre per unit sin δ is already
      // forty times the measured peak (0.023 m).
      curveColumn(kLeveling, kLevelingTable, "ground_effect.leveling_torque.table.M_G_m", "m",
                  {-1.0, 1.0, kInclusive},
                  [](P& p) -> std::vector<double>& { return p.leveling_torque.table.values; }),
      fade,
  };
}

/// The drag table (identified from flights).
std::vector<S> dragSpecs() {
  std::vector<S> s = {
      column("drag", "drag.heights_m", "m", {0.0, 1000.0, kInclusive},
             [](P& p) -> std::vector<double>& { return p.drag.heights_m; }),
      column("drag", "drag.d_x_N_per_mps", "N/(m/s)", {0.0, 100.0, kInclusive},
             [](P& p) -> std::vector<double>& { return p.drag.d_x_N_per_mps; }),
      column("drag", "drag.d_y_N_per_mps", "N/(m/s)", {0.0, 100.0, kInclusive},
             [](P& p) -> std::vector<double>& { return p.drag.d_y_N_per_mps; }),
  };
  for (auto& spec : s) spec.fitted = true;
  return s;
}

template <std::size_t I>
double& rotorX(P& p) { return p.rotor_layout.rotors[I].x_m; }
template <std::size_t I>
double& rotorY(P& p) { return p.rotor_layout.rotors[I].y_m; }
template <std::size_t I>
double& rotorSpin(P& p) { return p.rotor_layout.rotors[I].spin; }
template <std::size_t I>
double& rotorMotor(P& p) { return p.rotor_layout.rotors[I].px4_motor; }

/// The four keys of rotor I (all optional: the defaults are the X layout, PX4's numbering).
template <std::size_t I>
void addRotor(std::vector<S>& out, std::string_view x, std::string_view y, std::string_view spin,
              std::string_view motor) {
  S sx = number(x, "m", {-10.0, 10.0, kInclusive}, &rotorX<I>);
  S sy = number(y, "m", {-10.0, 10.0, kInclusive}, &rotorY<I>);
  S ss = number(spin, "", {-1.0, 1.0, kInclusive}, &rotorSpin<I>);
  ss.note = "(+1 counter-clockwise seen from above, −1 clockwise)";
  S sm = number(motor, "", {1.0, 12.0, kInclusive}, &rotorMotor<I>);
  sm.note = "(PX4 motor number)";
  for (S* s : {&sx, &sy, &ss, &sm}) {
    s->optional = true;
    out.push_back(*s);
  }
}

/// The rotor layout (docs/vehicle-file.md, "Rotor layout").
std::vector<S> layoutSpecs() {
  std::vector<S> s;
  addRotor<0>(s, "rotor_layout.rotor1.x_m", "rotor_layout.rotor1.y_m", "rotor_layout.rotor1.spin",
              "rotor_layout.rotor1.px4_motor");
  addRotor<1>(s, "rotor_layout.rotor2.x_m", "rotor_layout.rotor2.y_m", "rotor_layout.rotor2.spin",
              "rotor_layout.rotor2.px4_motor");
  addRotor<2>(s, "rotor_layout.rotor3.x_m", "rotor_layout.rotor3.y_m", "rotor_layout.rotor3.spin",
              "rotor_layout.rotor3.px4_motor");
  addRotor<3>(s, "rotor_layout.rotor4.x_m", "rotor_layout.rotor4.y_m", "rotor_layout.rotor4.spin",
              "rotor_layout.rotor4.px4_motor");
  return s;
}

std::vector<S> specs() {
  std::vector<S> s = bodySpecs();
  for (auto* part : {&groundEffectSpecs, &dragSpecs, &layoutSpecs}) {
    for (auto& spec : part()) s.push_back(std::move(spec));
  }
  return s;
}

// ------------------------------------------------------------------- cross-parameter rules

/// Principal moments of a real body satisfy the triangle inequalities.
void inertiaTriangle(const P& p, FieldChecker& c) {
  const char* axes[3] = {"inertia_kgm2.xx", "inertia_kgm2.yy", "inertia_kgm2.zz"};
  const Eigen::Vector3d& I = p.inertia_kgm2;
  for (int i = 0; i < 3; ++i) {
    const double others = I[(i + 1) % 3] + I[(i + 2) % 3];
    if (I[i] > others * (1.0 + 1e-9)) {
      c.fail(axes[i], formatValue(I[i]),
             "at most the sum of the other two principal moments (" + formatValue(others) +
                 " kg·m²): no rigid body has these moments");
    }
  }
}

/// Adjacent rotors of an X quadrotor are b/√2 apart; their discs must not overlap.
void propellersApart(const P& p, FieldChecker& c) {
  const double adjacent = p.diagonal_rotor_distance_m / std::sqrt(2.0);
  if (2.0 * p.propeller_radius_m > adjacent) {
    c.fail("geometry.propeller_radius_m", formatValue(p.propeller_radius_m),
           "at most half the adjacent-rotor distance b/√2 = " + formatValue(adjacent) +
               " m, or the propellers overlap");
  }
}

/// n² must rise strictly over the whole throttle range so that the curve can be inverted: its
/// slope c1 + 2·c2·t is linear in t, so checking both ends suffices.
void throttleIncreasing(const P& p, FieldChecker& c) {
  const auto& t = p.throttle;
  if (!(t.c1_rpm2 > 0.0 && t.c1_rpm2 + 2.0 * t.c2_rpm2 > 0.0)) {
    c.fail("throttle_curve", "c1=" + formatValue(t.c1_rpm2) + ", c2=" + formatValue(t.c2_rpm2),
           "n² strictly increasing on throttle [0, 1] (c1 > 0 and c1 + 2·c2 > 0)");
  }
}

/// The rotors must carry the weight out of ground effect between idle and full throttle: the
/// hover speed √(m·g/(4·k_T)) strictly inside [√c0, √(c2 + c1 + c0)] (the curve rises, so these
/// are its ends). Catches a k_T in N/(rad/s)² (91× too large), a mass in grams, a curve that tops
/// out too low.
void hoversWithinTheCurve(const P& p, FieldChecker& c) {
  const double hover = freeAirHoverSpeedRpm(p.mass_kg, p.rotor.k_T_N_per_rpm2);
  const ThrottleCurve curve(p.throttle);
  const double idle = curve.minSpeedRpm();
  const double top = curve.maxSpeedRpm();
  const std::string given = "hover speed √(m·g/(4·k_T)) = " + formatValue(hover) + " rpm";
  if (!(hover < top)) {
    c.fail("rotor.k_T_N_per_rpm2", given,
           "below the throttle curve's full-throttle speed √(c2 + c1 + c0) = " + formatValue(top) +
               " rpm, or the vehicle cannot lift itself (check mass_kg, k_T in N/rpm² and the curve)");
  } else if (!(hover > idle)) {
    c.fail("rotor.k_T_N_per_rpm2", given,
           "above the throttle curve's idle speed √c0 = " + formatValue(idle) +
               " rpm, or the vehicle climbs at zero throttle (check k_T: N/rpm², not N/(rad/s)²)");
  }
}

/// A ground-effect table's heights within 100 propeller radii: the cushion is below 0.1 % beyond
/// a few (Cheeseman & Bennett: (R/4z)² is 6·10⁻⁶ at 100·R), so a table reaching further holds
/// heights in another unit (centimetres) or another vehicle's.
void tableHeightsWithinReach(const std::vector<double>& heights_m, const P& p, std::string_view key,
                             FieldChecker& c) {
  const double reach = 100.0 * p.propeller_radius_m;
  if (!heights_m.empty() && heights_m.back() > reach) {
    c.fail(std::string(key) + "[" + std::to_string(heights_m.size() - 1) + "]", formatValue(heights_m.back()),
           "a height in metres within 100 propeller radii (" + formatValue(reach) +
               " m): no surface acts on a rotor that far (heights in cm?)");
  }
}

void thrustTableWithinReach(const P& p, FieldChecker& c) {
  tableHeightsWithinReach(p.additional_thrust.table.heights_m, p,
                          "ground_effect.additional_thrust.table.heights_m", c);
}

void levelingTableWithinReach(const P& p, FieldChecker& c) {
  tableHeightsWithinReach(p.leveling_torque.table.heights_m, p,
                          "ground_effect.leveling_torque.table.heights_m", c);
}

/// h² + g3·h + g4 would vanish at some h > 0 and M_G would be infinite there.
void levelingDenominator(const P& p, FieldChecker& c) {
  const auto& l = p.leveling_torque;
  if (l.g3_m < 0.0 && l.g3_m * l.g3_m >= 4.0 * l.g4_m2) {
    c.fail("ground_effect.leveling_torque", "g3=" + formatValue(l.g3_m) + ", g4=" + formatValue(l.g4_m2),
           "h² + g3·h + g4 > 0 for every h ≥ 0 (g3 ≥ 0 or g3² < 4·g4)");
  }
}

/// The controller's mixer is the X layout with fixed spins (model/mixer.hpp): a layout the file
/// gives must be that one (positions within 2 % of the arm or 1 mm), spins ±1 as the mixer's, motor
/// numbers whole and distinct.
void rotorLayout(const P& p, FieldChecker& c) {
  static constexpr const char* kRotor[4] = {"rotor_layout.rotor1", "rotor_layout.rotor2",
                                            "rotor_layout.rotor3", "rotor_layout.rotor4"};
  static constexpr const char* kWhere[4] = {"front right", "rear left", "front left", "rear right"};
  const auto expected = Mixer::rotorPositions_B(p.diagonal_rotor_distance_m);
  const double tolerance = std::max(1e-3, 0.02 * mixerArm_m(p.diagonal_rotor_distance_m));
  const bool given = p.rotor_layout.positionsGiven();
  for (std::size_t i = 0; i < 4; ++i) {
    const RotorPlacement& r = p.rotor_layout.rotors[i];
    const std::string key = kRotor[i];
    const Eigen::Vector3d& e = expected[i];
    if (given && (std::abs(r.x_m - e.x()) > tolerance || std::abs(r.y_m - e.y()) > tolerance)) {
      c.fail(key + ".x_m", formatValue(r.x_m) + ", y_m " + formatValue(r.y_m),
             std::string("the ") + kWhere[i] + " rotor of the X layout of geometry.diagonal_rotor_distance_m: (" +
                 formatValue(e.x()) + ", " + formatValue(e.y()) + ") m within " + formatValue(tolerance) +
                 " m (the controller's mixer is that layout)");
    }
    const double spin = -Mixer::yawSigns()[static_cast<Eigen::Index>(i)];  // CCW: reaction torque −z
    if (r.spin != spin) {
      c.fail(key + ".spin", formatValue(r.spin),
             formatValue(spin) + std::string(spin > 0 ? " (counter-clockwise" : " (clockwise") +
                 " seen from above, as the controller's mixer turns the " + kWhere[i] + " rotor)");
    }
    if (r.px4_motor != std::round(r.px4_motor)) {
      c.fail(key + ".px4_motor", formatValue(r.px4_motor), "a whole motor number 1…12");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (p.rotor_layout.rotors[j].px4_motor == r.px4_motor) {
        c.fail(key + ".px4_motor", formatValue(r.px4_motor),
               std::string("a motor number of its own (") + kRotor[j] + " has it)");
      }
    }
  }
}

std::vector<ParamRule<P>> rules() {
  return {
      {"inertia_kgm2.zz", {"inertia_kgm2.xx", "inertia_kgm2.yy", "inertia_kgm2.zz"}, inertiaTriangle},
      {"geometry.propeller_radius_m",
       {"geometry.diagonal_rotor_distance_m", "geometry.propeller_radius_m"}, propellersApart},
      {"throttle_curve.c0_rpm2",
       {"throttle_curve.c2_rpm2", "throttle_curve.c1_rpm2", "throttle_curve.c0_rpm2"},
       throttleIncreasing},
      {"throttle_curve.c0_rpm2",
       {"mass_kg", "rotor.k_T_N_per_rpm2", "throttle_curve.c2_rpm2", "throttle_curve.c1_rpm2",
        "throttle_curve.c0_rpm2"},
       hoversWithinTheCurve},
      {"ground_effect.leveling_torque.scale_m4",
       {"ground_effect.leveling_torque.g3_m", "ground_effect.leveling_torque.g4_m2"},
       levelingDenominator},
      {"ground_effect.additional_thrust.table.F_G",
       {"geometry.propeller_radius_m", "ground_effect.additional_thrust.table.heights_m"},
       thrustTableWithinReach},
      {"ground_effect.leveling_torque.table.M_G_m",
       {"geometry.propeller_radius_m", "ground_effect.leveling_torque.table.heights_m"},
       levelingTableWithinReach},
      {"rotor_layout.rotor4.px4_motor",
       {"geometry.diagonal_rotor_distance_m", "rotor_layout.rotor1.x_m", "rotor_layout.rotor1.y_m",
        "rotor_layout.rotor1.spin", "rotor_layout.rotor1.px4_motor", "rotor_layout.rotor2.x_m",
        "rotor_layout.rotor2.y_m", "rotor_layout.rotor2.spin", "rotor_layout.rotor2.px4_motor",
        "rotor_layout.rotor3.x_m", "rotor_layout.rotor3.y_m", "rotor_layout.rotor3.spin",
        "rotor_layout.rotor3.px4_motor", "rotor_layout.rotor4.x_m", "rotor_layout.rotor4.y_m",
        "rotor_layout.rotor4.spin", "rotor_layout.rotor4.px4_motor"},
       rotorLayout},
  };
}

}  // namespace

const ParamSchema<VehicleParams>& vehicleSchema() {
  static const ParamSchema<VehicleParams> schema(specs(), rules());
  return schema;
}

VehicleParams mergeParameters(const VehicleParams& base, const VehicleParams& update,
                              const std::vector<std::string>& keys) {
  return model::mergeParameters(vehicleSchema(), base, update, keys);
}

}  // namespace geaware::model
