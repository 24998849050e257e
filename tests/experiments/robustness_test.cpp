// SPDX-License-Identifier: BSD-3-Clause
// The robustness suite (experiments/robustness.hpp) on a small scale: each cell changes exactly
// its truth field and nothing of the belief; the run is identical on 1 and 2 threads; a law
// family re-runs the calibration in its own world; the JSON parses with nulls where every flight
// struck; the paired-seed comparison and the checks on hand-made results.

#include "geaware/experiments/robustness.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "geaware/control/controller_params.hpp"
#include "geaware/experiments/table_one.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/vehicle_schema.hpp"

namespace geaware::experiments {
namespace {


/// Every number of the world a cell could touch (the truth, the sensors, the disturbances), by
/// name: a cell must change exactly its own.
std::map<std::string, double> worldFingerprint(const FlightScenario& s) {
  std::map<std::string, double> f;
  const sim::TruthParams& t = *s.truth;
#define GEAWARE_F(name, expr) f[name] = static_cast<double>(expr)
  GEAWARE_F("mass_kg", t.mass_kg);
  for (int i = 0; i < 9; ++i) GEAWARE_F("inertia" + std::to_string(i), t.inertia_kgm2(i));
  for (int i = 0; i < 3; ++i) GEAWARE_F("cog" + std::to_string(i), t.cog_offset_B[i]);
  for (std::size_t r = 0; r < 4; ++r) {
    const std::string k = std::to_string(r);
    for (int i = 0; i < 3; ++i) GEAWARE_F("rotor" + k + "." + std::to_string(i), t.rotor_position_B[r][i]);
    GEAWARE_F("yaw_sign" + k, t.yaw_sign[r]);
    GEAWARE_F("thrust_multiplier" + k, t.thrust_multiplier[r]);
    GEAWARE_F("torque_multiplier" + k, t.torque_multiplier[r]);
    GEAWARE_F("tilt" + k + ".x", t.thrust_axis_tilt_rad[r].x());
    GEAWARE_F("tilt" + k + ".y", t.thrust_axis_tilt_rad[r].y());
  }
  GEAWARE_F("radius", t.propeller_radius_m);
  GEAWARE_F("k_T", t.k_T_N_per_rpm2);
  GEAWARE_F("k_I", t.k_I_Nm_per_rpm2);
  GEAWARE_F("motor.dead_time", t.motor.dead_time_s);
  GEAWARE_F("motor.tau", t.motor.time_constant_s);
  GEAWARE_F("motor.max", t.motor.max_speed_rpm);
  GEAWARE_F("motor.J_R", t.motor.J_R_kgm2);
  GEAWARE_F("motor.c2", t.motor.throttle.c2_rpm2);
  GEAWARE_F("battery.R", t.battery.internal_resistance_ohm);
  GEAWARE_F("feet", t.landing_feet_B.size());
  GEAWARE_F("gravity", t.gravity_mps2);
  const sim::RotorAeroParams& a = t.aero;
  GEAWARE_F("aero.law", static_cast<int>(a.law));
  GEAWARE_F("aero.body_coefficient", a.body_coefficient);
  GEAWARE_F("aero.suckdown_gain", a.suckdown_gain);
  GEAWARE_F("aero.own_thrust_fraction", a.own_thrust_fraction);
  GEAWARE_F("aero.induced_velocity", a.induced_velocity_mps);
  GEAWARE_F("aero.cushion", a.in_flight_cushion_scale);
  GEAWARE_F("aero.lift", a.translational_lift_per_mps2);
  GEAWARE_F("aero.drag_area", a.airframe_drag_area_m2);
  GEAWARE_F("aero.drag_x", a.drag_x_N_per_mps_per_rpm);
  const sim::MocapParams& m = s.sensors.mocap;
  GEAWARE_F("mocap.latency", m.latency_s);
  GEAWARE_F("mocap.reported", m.reported_latency_s);
  GEAWARE_F("mocap.jitter", m.latency_jitter_std_s);
  GEAWARE_F("mocap.rate", m.rate_Hz);
  GEAWARE_F("imu.lowpass", s.sensors.imu.lowpass_cutoff_Hz);
  const DisturbanceSettings& d = s.disturbances;
  GEAWARE_F("turbulence", d.turbulence);
  GEAWARE_F("turbulence.sigma_z", d.turbulence_params.force_std_N.z());
  GEAWARE_F("wind", d.wind);
  for (int i = 0; i < 3; ++i) {
    GEAWARE_F("wind.mean" + std::to_string(i), d.wind_params.mean_W_mps[i]);
    GEAWARE_F("wind.gust" + std::to_string(i), d.wind_params.gust_std_mps[i]);
  }
  GEAWARE_F("wind.T", d.wind_params.gust_correlation_time_s);
  GEAWARE_F("unsteadiness", d.unsteadiness);
#undef GEAWARE_F
  return f;
}

std::set<std::string> changed(const std::map<std::string, double>& a,
                              const std::map<std::string, double>& b) {
  std::set<std::string> out;
  for (const auto& [k, v] : a) {
    if (b.at(k) != v) out.insert(k);
  }
  return out;
}

template <class V>
std::string asText(const V& v) {
  std::ostringstream s;
  s.precision(17);
  if constexpr (std::is_same_v<V, std::vector<double>>) {
    for (double x : v) s << x << ',';
  } else {
    s << v;
  }
  return s.str();
}

std::map<std::string, std::string> beliefFingerprint(const FlightScenario& s) {
  std::map<std::string, std::string> out;
  model::forEachParameter(s.vehicle, [&](std::string_view key, std::string_view, const auto& v) {
    out[std::string(key)] = asText(v);
  });
  out["controller"] = control::configurationName(s.controller);
  out["residual"] = s.residual ? "set" : "none";
  return out;
}

FlightScenario paperWorld() {
  FlightScenario s;
  s.vehicle = io::builtinVehicle();
  s.truth = sim::fromNominal(s.vehicle);
  s.controller = control::recommendedControllerParams();
  return s;
}

TEST(RobustnessCells, EachChangesExactlyItsTruthFieldAndNothingOfTheBelief) {
  const std::map<std::string, std::set<std::string>> expected = {
      {"none", {}},
      {"mass-10%", {"mass_kg"}},
      {"mass-5%", {"mass_kg"}},
      {"mass+5%", {"mass_kg"}},
      {"mass+10%", {"mass_kg"}},
      {"k_T-5%", {"k_T"}},
      {"k_T+5%", {"k_T"}},
      {"spread±5%",
       {"thrust_multiplier0", "thrust_multiplier1", "thrust_multiplier2", "thrust_multiplier3"}},
      {"cog+1cm", {"cog0"}},
      {"cushion×0.5", {"aero.cushion"}},
      {"cushion×0.8", {"aero.cushion"}},
      {"cushion×1.2", {"aero.cushion"}},
      {"latency+20ms", {"mocap.latency", "mocap.reported"}},
      {"gusts0.3", {"wind", "wind.gust0", "wind.gust1", "wind.gust2", "wind.T"}},
      {"law:cheeseman_bennett", {"aero.law"}},
      {"law:sanchez_cuevas", {"aero.law"}},
  };
  const FlightScenario base = paperWorld();
  const auto before = worldFingerprint(base);
  const auto belief = beliefFingerprint(base);
  const auto cells = robustnessCells();
  ASSERT_EQ(cells.size(), expected.size());
  EXPECT_EQ(cells.front().name, "none");
  for (const auto& p : cells) {
    FlightScenario s = base;
    applyPerturbation(p, s);
    EXPECT_EQ(changed(before, worldFingerprint(s)), expected.at(p.name)) << p.name;
    EXPECT_EQ(beliefFingerprint(s), belief) << p.name;
    EXPECT_EQ(p.recalibrates(), p.kind == PerturbationKind::kGroundEffectLaw) << p.name;
  }
}

TEST(RobustnessCells, MagnitudesAreTheIssues) {
  const FlightScenario base = paperWorld();
  const auto apply = [&](const std::string& name) {
    for (const auto& p : robustnessCells()) {
      if (p.name != name) continue;
      FlightScenario s = base;
      applyPerturbation(p, s);
      return s;
    }
    throw std::out_of_range(name);
  };
  EXPECT_DOUBLE_EQ(apply("mass+10%").truth->mass_kg, 1.10 * base.truth->mass_kg);
  EXPECT_DOUBLE_EQ(apply("k_T-5%").truth->k_T_N_per_rpm2, 0.95 * base.truth->k_T_N_per_rpm2);
  const auto spread = apply("spread±5%").truth->thrust_multiplier;
  EXPECT_DOUBLE_EQ(spread[0], 1.05);
  EXPECT_DOUBLE_EQ(spread[1], 0.95);
  EXPECT_DOUBLE_EQ(spread[2], 1.05);
  EXPECT_DOUBLE_EQ(spread[3], 0.95);
  EXPECT_DOUBLE_EQ(apply("cog+1cm").truth->cog_offset_B.x(), 0.01);
  EXPECT_DOUBLE_EQ(apply("cushion×0.8").truth->aero.in_flight_cushion_scale, 0.8);
  // The true latency grows by 20 ms; the driver keeps stamping the old one.
  const auto latency = apply("latency+20ms").sensors.mocap;
  EXPECT_DOUBLE_EQ(latency.latency_s, base.sensors.mocap.latency_s + 0.020);
  EXPECT_DOUBLE_EQ(latency.reported_latency_s, base.sensors.mocap.latency_s);
  const auto gusts = apply("gusts0.3").disturbances;
  EXPECT_TRUE(gusts.wind);
  EXPECT_EQ(gusts.wind_params.gust_std_mps, Eigen::Vector3d::Constant(0.3));
  EXPECT_TRUE(gusts.wind_params.mean_W_mps.isZero());
  EXPECT_TRUE(gusts.wind_params.validate().empty());
  // A world that already has room air keeps its own correlation time and mean.
  FlightScenario windy = base;
  windy.disturbances.wind = true;
  windy.disturbances.wind_params.gust_correlation_time_s = 2.0;
  windy.disturbances.wind_params.mean_W_mps = Eigen::Vector3d(0.1, 0, 0);
  applyPerturbation({"g", PerturbationKind::kGusts, 0.3, sim::GroundEffectLaw::kCalibrated}, windy);
  EXPECT_EQ(windy.disturbances.wind_params.gust_correlation_time_s, 2.0);
  EXPECT_EQ(windy.disturbances.wind_params.mean_W_mps.x(), 0.1);
  FlightScenario no_truth;
  EXPECT_THROW(applyPerturbation(robustnessCells()[1], no_truth), std::invalid_argument);
}

TEST(SuiteCondition, NamesTheTableIRowOfItsShapeAtAnyHeightAndSpeed) {
  // The text and the report call a height/speed by the Table I row whose lemniscate it flies.
  const SuiteCondition exp1 = suiteCondition(lemniscateFor(tableOneExperiment(1)), "lem-0.12m-1mps");
  EXPECT_EQ(exp1.experiment, 1);  // exps 1–5 share the shape: the first of them
  EXPECT_EQ(exp1.height_m(), 0.12);
  EXPECT_EQ(exp1.speed_mps(), 1.0);
  EXPECT_EQ(exp1.describe(), "exp 1's lemniscate");
  EXPECT_EQ(suiteCondition(lemniscateFor(tableOneExperiment(7))).experiment, 6);
  EXPECT_EQ(suiteCondition(lemniscateFor(tableOneExperiment(8))).experiment, 8);
  traj::LemniscateParams high = lemniscateFor(tableOneExperiment(1));
  high.height_m = 1.0;  // the fault campaign's second height: still exp 1's lemniscate
  high.peak_speed_mps = 2.0;
  EXPECT_EQ(suiteCondition(high).experiment, 1);
  EXPECT_EQ(suiteCondition(high).lemniscate.height_m, 1.0);
  // Any other part of the shape makes it no row's: named by the sweep file's scenario.
  for (auto change : {+[](traj::LemniscateParams& p) { p.half_extent_y_m = 0.9; },
                      +[](traj::LemniscateParams& p) { p.laps = 2; },
                      +[](traj::LemniscateParams& p) { p.ramp_time_s = 1.0; },
                      +[](traj::LemniscateParams& p) { p.height_swing_m = 0.1; },
                      +[](traj::LemniscateParams& p) { p.centre_xy_m.x() = 0.5; },
                      +[](traj::LemniscateParams& p) { p.yaw_rad = 0.3; }}) {
    traj::LemniscateParams other = lemniscateFor(tableOneExperiment(1));
    change(other);
    const SuiteCondition c = suiteCondition(other, "wide");
    EXPECT_EQ(c.experiment, 0);
    EXPECT_EQ(c.describe(), "lemniscate wide");
  }
}

/// A configuration by the name a sweep file gives it.
SuiteController controllerNamed(const std::string& name) {
  control::ControllerParams p;
  EXPECT_TRUE(control::parseConfiguration(name, p)) << name;
  return {control::configurationName(p), p};
}

RobustnessOptions small(int jobs) {
  RobustnessOptions o;
  o.vehicle = io::builtinVehicle();
  o.seeds = 1;
  o.jobs = jobs;
  const auto all = robustnessCells();
  o.cells = {all[0], all[4]};  // none, mass+10%
  o.conditions = {suiteCondition(lemniscateFor(tableOneExperiment(1)), "lem-0.12m-1mps")};
  o.controllers = {controllerNamed("model:model_indi"), controllerNamed("recommended")};
  return o;
}

TEST(RobustnessRun, IdenticalOnOneAndTwoThreads) {
  const RobustnessResult a = runRobustness(small(1));
  const RobustnessResult b = runRobustness(small(2));
  ASSERT_EQ(a.cells.size(), 4u);
  ASSERT_EQ(b.cells.size(), a.cells.size());
  EXPECT_EQ(a.flights, 4u);
  for (std::size_t i = 0; i < a.cells.size(); ++i) {
    const SuiteCell& x = a.cells[i];
    const SuiteCell& y = b.cells[i];
    EXPECT_EQ(x.case_name, y.case_name);
    EXPECT_EQ(x.controller, y.controller);
    ASSERT_EQ(x.flights.size(), 1u);
    ASSERT_EQ(y.flights.size(), 1u);
    EXPECT_EQ(x.flights[0].struck, y.flights[0].struck) << i;
    EXPECT_EQ(x.flights[0].rmse_all_cm, y.flights[0].rmse_all_cm) << i;  // bit for bit
    EXPECT_EQ(x.flights[0].max_cm, y.flights[0].max_cm) << i;
    EXPECT_EQ(x.flights[0].guard_active_s, y.flights[0].guard_active_s) << i;
  }
  // Cells in the documented order, recommended with a guard time, the paper's without.
  EXPECT_EQ(a.cells[0].case_name, "none");
  EXPECT_EQ(a.cells[0].controller, "model:model_indi");
  EXPECT_FALSE(a.cells[0].guardActiveS().has_value());
  EXPECT_EQ(a.cells[1].controller, "recommended");
  EXPECT_TRUE(a.cells[1].guardActiveS().has_value());
  EXPECT_EQ(a.cells[3].case_name, "mass+10%");
  EXPECT_EQ(a.recommended, "model:model_indi");
  ASSERT_EQ(a.calibrations.size(), 1u);  // no law cell: one calibration

  // The document parses and carries the shared suite schema.
  const io::Json doc = io::Json::parse(io::dumpJson(robustnessJson(a)));
  EXPECT_EQ(doc["suite"], "robustness");
  EXPECT_EQ(doc["recommended"], "model:model_indi");
  EXPECT_TRUE(doc.contains("geaware_version"));
  ASSERT_EQ(doc["cells"].size(), 4u);
  const io::Json& c = doc["cells"][1];
  EXPECT_EQ(c["case"], "none");
  EXPECT_EQ(c["controller"], "recommended");
  EXPECT_EQ(c["height_m"], 0.12);
  EXPECT_EQ(c["speed_mps"], 1.0);
  EXPECT_EQ(c["seeds"], io::Json::array({1}));
  EXPECT_EQ(c["flights"], 1);
  EXPECT_TRUE(c["guard_active_s"].is_number());
  EXPECT_TRUE(doc["cells"][0]["guard_active_s"].is_null());
  EXPECT_FALSE(formatRobustness(a).empty());
}

TEST(RobustnessRun, ALawFamilyRecalibratesInItsOwnWorld) {
  RobustnessOptions o = small(0);
  o.cells = {robustnessCells()[14]};  // law:cheeseman_bennett
  o.controllers = {controllerNamed("indi:none")};
  const RobustnessResult r = runRobustness(o);
  ASSERT_EQ(r.calibrations.size(), 2u);
  EXPECT_EQ(r.calibrations[1].world, "law:cheeseman_bennett");
  // A single rotor's cushion (3.6 % at 0.12 m) against the vehicle's ≈ 23 %: the identified
  // F_G must have shrunk with it.
  const auto f_g = [](const ControllerCalibration& c) {
    const auto& g = c.vehicle.additional_thrust;
    return g.g2_m2 / (0.12 * 0.12 + g.g1_m2);
  };
  EXPECT_LT(f_g(r.calibrations[1].calibration), 0.5 * f_g(r.calibrations[0].calibration));
  ASSERT_EQ(r.cells.size(), 1u);
  EXPECT_EQ(r.cells[0].case_name, "law:cheeseman_bennett");
}

// --- Hand-made results ---------------------------------------------------------------------

SuiteFlight flew(std::uint64_t seed, double rmse, std::optional<double> guard = std::nullopt) {
  SuiteFlight f;
  f.seed = seed;
  f.rmse_all_cm = rmse;
  f.guard_active_s = guard;
  return f;
}

SuiteFlight struck(std::uint64_t seed, std::optional<double> guard = std::nullopt) {
  SuiteFlight f = flew(seed, 50.0, guard);
  f.struck = true;
  f.strike_t_s = 2.0;
  return f;
}

SuiteCell cellOf(std::string case_name, std::string controller, std::vector<SuiteFlight> flights) {
  return {std::move(case_name), std::move(controller), 0.12, 1.0, std::move(flights)};
}

TEST(RobustnessCompare, UsesTheSeedsBothFinishedAndRanksAStrikeBelow) {
  const SuiteCell a = cellOf("x", "a", {flew(1, 1.0), flew(2, 2.0), struck(3), flew(4, 1.0)});
  const SuiteCell b = cellOf("x", "b", {flew(1, 2.0), struck(2), struck(3), flew(4, 3.0), flew(5, 0.1)});
  const PairedComparison p = comparePaired(a, b);
  EXPECT_EQ(p.seeds, 4);
  EXPECT_EQ(p.both_finished, 2);
  EXPECT_EQ(p.only_b_struck, 1);
  EXPECT_EQ(p.both_struck, 1);
  EXPECT_EQ(p.only_a_struck, 0);
  EXPECT_DOUBLE_EQ(p.a_rmse_all_cm, 1.0);  // seeds 1 and 4 only
  EXPECT_DOUBLE_EQ(p.b_rmse_all_cm, 2.5);
  EXPECT_TRUE(p.atMost(1.0));
  EXPECT_TRUE(p.atMost(0.4));
  EXPECT_FALSE(p.atMost(0.3));
  // The other way round: b finished nowhere a struck, but b is worse where both finished.
  const PairedComparison q = comparePaired(b, a);
  EXPECT_EQ(q.only_a_struck, 1);  // b struck on seed 2, where a finished
  EXPECT_FALSE(q.atMost(100.0));  // a strike ranks below every finished flight
  // Nothing to compare: vacuously at most.
  const PairedComparison none = comparePaired(cellOf("x", "a", {struck(1)}), cellOf("x", "b", {struck(1)}));
  EXPECT_EQ(none.both_struck, 1);
  EXPECT_TRUE(std::isnan(none.a_rmse_all_cm));
  EXPECT_TRUE(none.atMost());
}

TEST(RobustnessSummary, AllStruckCellsAreNullAndTheChecksReportWhatTheySee) {
  RobustnessResult r;
  r.cases = {robustnessCells()[0], robustnessCells()[4]};
  r.controllers = {"indi:none", "model:model_indi", "recommended"};
  r.conditions = {suiteCondition(lemniscateFor(tableOneExperiment(1)))};
  r.seeds = {1, 2};
  r.recommended = "model:model_indi";
  r.cells = {
      cellOf("none", "indi:none", {flew(1, 2.0), flew(2, 2.0)}),
      cellOf("none", "model:model_indi", {flew(1, 1.5), flew(2, 1.5)}),
      cellOf("none", "recommended", {flew(1, 0.9, 0.0), flew(2, 1.1, 0.0)}),
      cellOf("mass+10%", "indi:none", {flew(1, 2.0), flew(2, 2.0)}),
      cellOf("mass+10%", "model:model_indi", {struck(1), struck(2)}),
      cellOf("mass+10%", "recommended", {flew(1, 1.0, 0.2), struck(2, 0.5)}),
  };
  r.checks = robustnessChecks(r);
  const io::Json doc = io::Json::parse(io::dumpJson(robustnessJson(r)));
  const io::Json& all_struck = doc["cells"][4];
  EXPECT_EQ(all_struck["strikes"], 2);
  EXPECT_TRUE(all_struck["rmse_all_cm"].is_null());
  EXPECT_TRUE(all_struck["guard_active_s"].is_null());
  EXPECT_TRUE(all_struck["per_seed"][0]["struck"].get<bool>());
  EXPECT_DOUBLE_EQ(doc["cells"][5]["rmse_all_cm"].get<double>(), 1.0);  // the finished one
  EXPECT_DOUBLE_EQ(doc["cells"][5]["guard_active_s"].get<double>(), 0.35);

  std::map<std::string, bool> pass;
  for (const auto& c : r.checks) pass[c.name] = c.pass;
  EXPECT_FALSE(pass.at("recommended: no strike"));  // mass+10%, seed 2
  // ≤ indi:none: none yes; mass+10% no (a strike where indi:none finished): 1 of 2 < 90 %.
  EXPECT_FALSE(pass.at("recommended all-RMSE ≤ indi:none (exp 2's configuration)'s (paired seeds)"));
  // ≤ ½ indi:none in none: 1.0 ≤ 0.5·2.0.
  EXPECT_TRUE(pass.at("recommended all-RMSE ≤ ½ × indi:none (exp 2's configuration)'s in \"none\""));
  // model:model_indi finishes only in none, where recommended is better.
  EXPECT_TRUE(pass.at("recommended all-RMSE ≤ model:model_indi's (exp 5's configuration)"));
  EXPECT_TRUE(pass.at("recommended: guard never active in \"none\""));
  EXPECT_EQ(pass.count("recommended all-RMSE ≤ indi:indi's (paired seeds)"), 0u);  // not flown
  const std::string text = formatRobustness(r);
  EXPECT_NE(text.find("struck"), std::string::npos);
  EXPECT_NE(text.find("[FAIL] recommended: no strike"), std::string::npos);
  EXPECT_NO_THROW((void)robustnessPage(r, io::RunInfo{}));
}

}  // namespace
}  // namespace geaware::experiments
