// `geaware identify`: rig and flight logs → parameters with standard errors, a merged vehicle
// file (--out), one JSON object (--json) and an HTML report (--report). Thin: parse, call the
// ident library, print.

#include "identify_command.hpp"

#include "geaware/io/json.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <functional>
#include <optional>

#include "geaware/ident/fits.hpp"
#include "geaware/ident/vehicle_update.hpp"
#include "geaware/io/range.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/height_table.hpp"
#include "geaware/model/ground_effect.hpp"
#include "geaware/model/units.hpp"
#include "geaware/report/page.hpp"

namespace geaware::cli {
namespace {

using io::jsonString;

struct IdentifyOptions {
  std::string kind;                  ///< rotor, platform, flight, correlations
  std::string log;
  std::string vehicle;               ///< base vehicle file (default: built-in)
  std::string out;                   ///< merged vehicle file
  std::string json;                  ///< JSON output ('-': stdout)
  std::string report;                ///< report directory
  std::vector<std::string> columns;  ///< DEFAULT=ACTUAL renames
  std::string loss = "huber";
  double tilt_limit_deg = 10.0;
  int height_bands = 6;
  bool hover = false;
  std::string ground_effect = "paper";  ///< paper: the closed forms; table: values at knots
  double table_top_m = 0.5;             ///< automatic F_G knots up to this height [m]
  std::string table_heights;            ///< explicit knots FROM:TO:STEP (empty: automatic)
};

/// One row of the parameter table: the vehicle-file key (or a descriptive name), the estimate
/// and its unit.
struct Param {
  std::string name;
  ident::Estimate e;
  std::string unit;
};

struct Fit {
  std::string name;
  ident::FitStats stats;
  std::string unit;
};

struct Outcome {
  std::vector<Param> params;
  std::vector<Fit> fits;
  std::vector<std::string> warnings;
  io::VehicleUpdate update;
  std::string json_extra;  ///< additional JSON members (",\"key\":value…")
};

std::string jsonNumber(double v) { return std::isfinite(v) ? fmt::format("{:.9g}", v) : "null"; }

std::string rename(const std::map<std::string, std::string>& m, const std::string& name) {
  const auto it = m.find(name);
  return it == m.end() ? name : it->second;
}

std::map<std::string, std::string> parseColumns(const std::vector<std::string>& specs) {
  std::map<std::string, std::string> m;
  for (const auto& s : specs) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == s.size()) {
      throw std::invalid_argument("--column '" + s + "': expected DEFAULT=ACTUAL, e.g. fz_N=Fz");
    }
    m[s.substr(0, eq)] = s.substr(eq + 1);
  }
  return m;
}

ident::RobustOptions robustOptions(const std::string& loss) {
  ident::RobustOptions r;
  if (loss == "cauchy") {
    r.loss = ident::RobustLoss::kCauchy;
    r.loss_scale = 2.385;
  } else if (loss == "none") {
    r.loss = ident::RobustLoss::kNone;
  }
  return r;
}

void addStatsTable(const Outcome& o, report::Page& page) {
  report::Table params{"Parameters", {"parameter", "value", "std. error", "unit"}, {}};
  for (const auto& p : o.params) {
    params.rows.push_back({p.name, fmt::format("{:.6g}", p.e.value), fmt::format("{:.3g}", p.e.std_error), p.unit});
  }
  page.addTable(params);
  report::Table fits{"Residuals", {"fit", "residual RMS", "unit", "samples", "outliers"}, {}};
  for (const auto& f : o.fits) {
    fits.rows.push_back({f.name, fmt::format("{:.4g}", f.stats.residual_rms), f.unit,
                         std::to_string(f.stats.count), std::to_string(f.stats.outliers)});
  }
  page.addTable(fits);
}

report::Series series(std::string name, std::string mode, std::string dash) {
  report::Series s;
  s.name = std::move(name);
  s.mode = std::move(mode);
  s.dash = std::move(dash);
  return s;
}

/// `f` sampled at 401 heights over [from, to] m, as a line.
report::Series curve(std::string name, const std::function<double(double)>& f, double from,
                     double to, std::string dash = "") {
  report::Series c = series(std::move(name), "lines", std::move(dash));
  for (int k = 0; k <= 400; ++k) {
    const double h = from + (to - from) * k / 400.0;
    c.x.push_back(h);
    c.y.push_back(f(h));
  }
  return c;
}

/// Every k-th index so that at most `max_points` are plotted.
std::size_t plotStride(std::size_t n, std::size_t max_points = 4000) {
  return std::max<std::size_t>(1, n / max_points);
}

std::vector<double> values(const ident::TableCurve& c) {
  std::vector<double> v;
  for (const auto& e : c.values) v.push_back(e.value);
  return v;
}

/// {"heights_m": [...], "<values_key>": [...], "std_error": [...], "samples": [...]}
std::string tableJson(const ident::TableCurve& c, const std::string& values_key) {
  std::string h;
  std::string v;
  std::string e;
  std::string n;
  for (std::size_t j = 0; j < c.values.size(); ++j) {
    const char* sep = j ? "," : "";
    h += sep + jsonNumber(c.heights_m[j]);
    v += sep + jsonNumber(c.values[j].value);
    e += sep + jsonNumber(c.values[j].std_error);
    n += fmt::format("{}{}", sep, c.samples[j]);
  }
  return fmt::format("{{\"heights_m\":[{}],{}:[{}],\"std_error\":[{}],\"samples\":[{}]}}", h,
                     jsonString(values_key), v, e, n);
}

/// How one curve's table is named: "F_G" with unit "-" in section ground_effect.additional_thrust
/// (values key "F_G"), or "M_G", "m", leveling_torque, "M_G_m".
struct TableNames {
  std::string curve;
  std::string unit;
  std::string section;     ///< below ground_effect
  std::string values_key;  ///< in the vehicle file
};

/// A fitted table into the outcome: one parameter row per knot ("F_G(h = 0.07 m)"), the
/// vehicle-file update with the standard errors, its JSON member appended to `json`. Returns the
/// curve as the model interpolates it (PCHIP), for the plots.
std::function<double(double)> takeTable(Outcome& o, const TableNames& n, const ident::TableCurve& c,
                                        std::string& json) {
  std::vector<double> errors;
  for (std::size_t j = 0; j < c.values.size(); ++j) {
    o.params.push_back({fmt::format("{}(h = {:.4g} m)", n.curve, c.heights_m[j]), c.values[j], n.unit});
    errors.push_back(c.values[j].std_error);
  }
  o.update.setTable("ground_effect." + n.section, c.heights_m, values(c), errors);
  json += (json.empty() ? "" : ",") + jsonString(n.section) + ":" + tableJson(c, n.values_key);
  return [curve = model::HeightTable(c.heights_m, values(c))](double h) { return curve.value(h); };
}

// ------------------------------------------------------------------------------- the kinds

Outcome identifyRotor(const IdentifyOptions& opt, const std::map<std::string, std::string>& cols,
                      report::Page& page) {
  ident::RotorStandColumns c;
  for (auto* s : {&c.t, &c.throttle, &c.rpm, &c.thrust, &c.torque}) *s = rename(cols, *s);
  const auto log = ident::readRotorStandLog(opt.log, c);
  ident::RotorFitOptions fo;
  fo.robust = robustOptions(opt.loss);
  const auto fit = ident::fitRotorStand(log, fo);
  Outcome o;
  o.params = {{"rotor.k_T_N_per_rpm2", fit.k_T_N_per_rpm2, "N/rpm²"},
              {"rotor.k_I_Nm_per_rpm2", fit.k_I_Nm_per_rpm2, "N·m/rpm²"}};
  if (fit.J_R_kgm2) o.params.push_back({"rotor.J_R_kgm2", *fit.J_R_kgm2, "kg·m²"});
  o.params.push_back({"throttle_curve.c2_rpm2", fit.c2_rpm2, "rpm²"});
  o.params.push_back({"throttle_curve.c1_rpm2", fit.c1_rpm2, "rpm²"});
  o.params.push_back({"throttle_curve.c0_rpm2", fit.c0_rpm2, "rpm²"});
  o.fits = {{"thrust", fit.thrust, "N"}, {"torque", fit.torque, "N·m"},
            {"throttle curve (n²/n)", fit.throttle, "rpm"}};
  o.warnings = fit.warnings;
  ident::addRotorFit(o.update, fit);

  report::Plot thrust{"Thrust vs rpm² (single-rotor stand)", "n² [rpm²]", "thrust [N]", {}};
  report::Plot throttle{"Throttle curve", "throttle [-]", "n [rpm]", {}};
  report::Series meas = series("measured", "markers", "");
  report::Series tmeas = series("measured", "markers", "");
  for (std::size_t i = 0; i < log.size(); i += plotStride(log.size())) {
    meas.x.push_back(log.rpm[i] * log.rpm[i]);
    meas.y.push_back(log.thrust_N[i]);
    tmeas.x.push_back(log.throttle[i]);
    tmeas.y.push_back(log.rpm[i]);
  }
  report::Series line = series("k_T·n²", "lines", "");
  report::Series curve = series("√(c2·t² + c1·t + c0)", "lines", "");
  const double n_max = *std::max_element(log.rpm.begin(), log.rpm.end());
  for (int k = 0; k <= 50; ++k) {
    const double n2 = n_max * n_max * k / 50.0;
    line.x.push_back(n2);
    line.y.push_back(fit.k_T_N_per_rpm2.value * n2);
    const double t = k / 50.0;
    curve.x.push_back(t);
    curve.y.push_back(std::sqrt(std::max(0.0, (fit.c2_rpm2.value * t + fit.c1_rpm2.value) * t + fit.c0_rpm2.value)));
  }
  thrust.series = {meas, line};
  throttle.series = {tmeas, curve};
  addStatsTable(o, page);
  page.addPlot(thrust);
  page.addPlot(throttle);
  return o;
}

ident::PlatformColumns platformColumns(const std::map<std::string, std::string>& cols) {
  ident::PlatformColumns c;
  for (auto* s : {&c.t, &c.h, &c.tilt}) *s = rename(cols, *s);
  for (auto& s : c.n) s = rename(cols, s);
  for (auto& s : c.f) s = rename(cols, s);
  for (auto& s : c.tau) s = rename(cols, s);
  return c;
}

Outcome identifyPlatform(const IdentifyOptions& opt, const std::map<std::string, std::string>& cols,
                         report::Page& page,
                         const model::VehicleParams& base) {
  const auto log = ident::readPlatformLog(opt.log, platformColumns(cols));
  ident::PlatformFitOptions po;
  po.robust = robustOptions(opt.loss);
  po.height_bands = opt.height_bands;
  const bool table = opt.ground_effect == "table";
  if (table) {
    po.thrust_table.top_m = opt.table_top_m;
    if (!opt.table_heights.empty()) {
      po.thrust_table.heights_m = io::parseRange(opt.table_heights, "--table-heights", 1000).values();
    }
  }
  Outcome o;
  const auto mixing = ident::fitMixing(log, base.diagonal_rotor_distance_m, po);
  // F_G in the chosen form: k_T, the curve for the plots, and the update.
  ident::Estimate k_T;
  std::function<double(double)> fitted_F;
  double h_min = 0.0;
  double h_max = 0.0;
  std::string tables_json;
  if (table) {
    const auto fit = ident::fitAdditionalThrustTable(log, po);
    k_T = fit.k_T_N_per_rpm2;
    o.params.push_back({"rotor.k_T_N_per_rpm2", k_T, "N/rpm²"});
    o.fits = {{"f_z = k_T·Σn²·(1 + F_G(h))", fit.stats, "N"}};
    o.warnings = fit.warnings;
    ident::setEstimate(o.update, "rotor.k_T_N_per_rpm2", k_T);
    fitted_F = takeTable(o, {"F_G", "-", "additional_thrust", "F_G"}, fit.F_G, tables_json);
    h_min = fit.h_min_m;
    h_max = fit.h_max_m;
  } else {
    const auto fit = ident::fitAdditionalThrust(log, po);
    k_T = fit.k_T_N_per_rpm2;
    o.params = {{"rotor.k_T_N_per_rpm2", k_T, "N/rpm²"},
                {"ground_effect.additional_thrust.g1_m2", fit.g1_m2, "m²"},
                {"ground_effect.additional_thrust.g2_m2", fit.g2_m2, "m²"}};
    o.fits = {{"f_z = k_T·Σn²·(1 + F_G(h))", fit.stats, "N"}};
    o.warnings = fit.warnings;
    ident::addAdditionalThrust(o.update, fit);
    fitted_F = [g1 = fit.g1_m2.value, g2 = fit.g2_m2.value](double h) { return g2 / (h * h + g1); };
    h_min = fit.h_min_m;
    h_max = fit.h_max_m;
  }
  o.params.push_back({"k_T of the top height band (paper's method)", mixing.k_T_top_N_per_rpm2, "N/rpm²"});
  if (mixing.k_TX_N_per_rpm2) o.params.push_back({"rotor.k_TX_N_per_rpm2", *mixing.k_TX_N_per_rpm2, "N/rpm²"});
  if (mixing.k_TY_N_per_rpm2) o.params.push_back({"rotor.k_TY_N_per_rpm2", *mixing.k_TY_N_per_rpm2, "N/rpm²"});
  if (mixing.k_I_Nm_per_rpm2) o.params.push_back({"rotor.k_I_Nm_per_rpm2", *mixing.k_I_Nm_per_rpm2, "N·m/rpm²"});
  o.fits.push_back({"roll torque", mixing.roll, "N·m"});
  o.fits.push_back({"pitch torque", mixing.pitch, "N·m"});
  o.fits.push_back({"yaw torque", mixing.yaw, "N·m"});
  o.warnings.insert(o.warnings.end(), mixing.warnings.begin(), mixing.warnings.end());
  ident::addMixing(o.update, mixing);

  // The leveling torque, when the log has tilted-board samples.
  std::function<double(double)> fitted_M;
  double lev_h_min = 0.0;
  double lev_h_max = 0.0;
  const bool tilted = std::any_of(log.tilt_deg.begin(), log.tilt_deg.end(),
                                  [&](double d) { return std::abs(d) > po.level_tilt_deg; });
  if (tilted) {
    ident::LevelingFitOptions lo;
    lo.robust = po.robust;
    lo.max_tilt_deg = opt.tilt_limit_deg;
    const double k_TY = mixing.k_TY_N_per_rpm2 ? mixing.k_TY_N_per_rpm2->value : base.rotor.k_TY_N_per_rpm2;
    const ident::LevelingInputs in{k_T.value, k_TY, base.diagonal_rotor_distance_m};
    if (table) {
      if (!opt.table_heights.empty()) lo.table.heights_m = po.thrust_table.heights_m;
      const auto fit = ident::fitLevelingTable(log, in, lo);
      o.fits.push_back({"leveling torque", fit.stats, "N·m"});
      o.warnings.insert(o.warnings.end(), fit.warnings.begin(), fit.warnings.end());
      fitted_M = takeTable(o, {"M_G", "m", "leveling_torque", "M_G_m"}, fit.M_G, tables_json);
      lev_h_min = fit.h_min_m;
      lev_h_max = fit.h_max_m;
    } else {
      const auto fit = ident::fitLeveling(log, in, lo);
      o.params.push_back({"ground_effect.leveling_torque.g3_m", fit.g3_m, "m"});
      o.params.push_back({"ground_effect.leveling_torque.g4_m2", fit.g4_m2, "m²"});
      o.params.push_back({"ground_effect.leveling_torque.scale_m4", fit.scale_m4, "m⁴"});
      o.fits.push_back({"leveling torque", fit.stats, "N·m"});
      o.warnings.insert(o.warnings.end(), fit.warnings.begin(), fit.warnings.end());
      ident::addLeveling(o.update, fit);
      fitted_M = [f = fit](double h) {
        return ident::levelingCoefficient(f.g3_m.value, f.g4_m2.value, f.scale_m4.value, h);
      };
      lev_h_min = fit.h_min_m;
      lev_h_max = fit.h_max_m;
    }
  } else {
    o.warnings.push_back("no tilted-board samples: the leveling torque is not identified");
  }

  // JSON and report extras: the height bands.
  std::string bands = ",\"height_bands\":[";
  report::Table band_table{"Coefficients per height band (k_T is k_T·(1 + F_G(h)))",
                           {"h [m]", "samples", "k_T", "k_TX", "k_TY", "k_I"}, {}};
  auto cell = [](const std::optional<ident::Estimate>& e) {
    return e ? fmt::format("{:.5g} ± {:.2g}", e->value, e->std_error) : std::string("–");
  };
  auto js = [](const std::optional<ident::Estimate>& e) {
    return e ? fmt::format("{{\"value\":{},\"std_error\":{}}}", jsonNumber(e->value), jsonNumber(e->std_error))
             : std::string("null");
  };
  for (std::size_t b = 0; b < mixing.bands.size(); ++b) {
    const auto& hb = mixing.bands[b];
    band_table.rows.push_back({fmt::format("{:.3g}–{:.3g}", hb.h_min_m, hb.h_max_m), std::to_string(hb.count),
                               cell(hb.k_T_N_per_rpm2), cell(hb.k_TX_N_per_rpm2), cell(hb.k_TY_N_per_rpm2),
                               cell(hb.k_I_Nm_per_rpm2)});
    bands += fmt::format("{}{{\"h_min_m\":{},\"h_max_m\":{},\"h_mean_m\":{},\"count\":{},\"k_T\":{},\"k_TX\":{},"
                         "\"k_TY\":{},\"k_I\":{}}}",
                         b ? "," : "", jsonNumber(hb.h_min_m), jsonNumber(hb.h_max_m), jsonNumber(hb.h_mean_m),
                         hb.count, js(hb.k_T_N_per_rpm2), js(hb.k_TX_N_per_rpm2), js(hb.k_TY_N_per_rpm2),
                         js(hb.k_I_Nm_per_rpm2));
  }
  o.json_extra = bands + "]";
  if (table) o.json_extra += ",\"tables\":{" + tables_json + "}";
  addStatsTable(o, page);
  page.addTable(band_table);

  // F_G: the paper's per-sample F̃_G (eq. 9) with the fitted k_T, the fit and the base curve.
  const model::GroundEffectModel base_ge(base);
  const auto F = ident::measuredAdditionalThrust(log, k_T.value);
  report::Plot fg{"Additional thrust F_G(h) (level board)", "h [m]", "F_G [-]", {}};
  report::Series pts = series("F̃_G = f̃_z/T̃ − 1 (eq. 9)", "markers", "");
  for (std::size_t i = 0; i < log.size(); i += plotStride(log.size())) {
    if (std::abs(log.tilt_deg[i]) > po.level_tilt_deg) continue;
    pts.x.push_back(log.h_m[i]);
    pts.y.push_back(F[i]);
  }
  fg.series = {pts, curve(table ? "fit, table (PCHIP)" : "fit g2/(h² + g1)", fitted_F, h_min, h_max),
               curve("base vehicle", [&](double h) { return base_ge.thrustRatio(h); }, h_min, h_max,
                     "dash")};
  page.addPlot(fg);
  if (fitted_M) {
    report::Plot mg{"Leveling coefficient M_G(h) (tilted board)", "h [m]", "M_G [m]", {}};
    report::Series mp = series("−τ_G,y/(T·sin δ)", "markers", "");
    const double arm = std::sqrt(2.0) * base.diagonal_rotor_distance_m / 4.0;
    const double k_TY = mixing.k_TY_N_per_rpm2 ? mixing.k_TY_N_per_rpm2->value : base.rotor.k_TY_N_per_rpm2;
    for (std::size_t i = 0; i < log.size(); i += plotStride(log.size())) {
      const double tilt = std::abs(log.tilt_deg[i]);
      if (tilt <= po.level_tilt_deg || tilt > opt.tilt_limit_deg) continue;
      std::array<double, 4> n2{};
      for (std::size_t k = 0; k < 4; ++k) n2[k] = log.n_rpm[k][i] * log.n_rpm[k][i];
      const double T = k_T.value * (n2[0] + n2[1] + n2[2] + n2[3]);
      const double tau_G = log.tau_Nm[1][i] - arm * k_TY * (-n2[0] + n2[1] - n2[2] + n2[3]);
      mp.x.push_back(log.h_m[i]);
      mp.y.push_back(-tau_G / (T * std::sin(log.tilt_deg[i] * model::kDegToRad)));
    }
    mg.series = {mp, curve(table ? "fit, table (PCHIP)" : "fit", fitted_M, lev_h_min, lev_h_max),
                 curve("base vehicle", [&](double h) { return base_ge.levelingCoefficient(h); },
                       lev_h_min, lev_h_max, "dash")};
    page.addPlot(mg);
  }
  return o;
}

Outcome identifyFlight(const IdentifyOptions& opt, const std::map<std::string, std::string>& cols,
                         report::Page& page,
                       const model::VehicleParams& base) {
  ident::FlightColumns c;
  for (auto* s : {&c.t, &c.h}) *s = rename(cols, *s);
  for (auto& s : c.v) s = rename(cols, s);
  for (auto& s : c.q) s = rename(cols, s);
  for (auto& s : c.a_ext) s = rename(cols, s);
  for (auto& s : c.n) s = rename(cols, s);
  Outcome o;
  if (opt.hover) {
    const auto log = ident::readHoverLog(opt.log, c);
    const auto fit = ident::fitHoverAdditionalThrust(log, base.mass_kg, base.rotor.k_T_N_per_rpm2,
                                                     robustOptions(opt.loss));
    o.params = {{"rotor.k_T_N_per_rpm2", fit.k_T_N_per_rpm2, "N/rpm²"},
                {"ground_effect.additional_thrust.g1_m2", fit.g1_m2, "m²"},
                {"ground_effect.additional_thrust.g2_m2", fit.g2_m2, "m²"}};
    o.fits = {{"m·a_ext,z + k_T·Σn² = k_T'·Σn²·(1 + F_G(h))", fit.stats, "N"}};
    o.warnings = fit.warnings;
    ident::addAdditionalThrust(o.update, fit);  // k_T in hover goes with its g1, g2
    addStatsTable(o, page);
    report::Plot fg{"F_G from the hover descent (eq. 10)", "h [m]", "F_G [-]", {}};
    report::Series pts = series("m·a_ext,z/T̃", "markers", "");
    report::Series fitted = series("fit", "lines", "");
    for (std::size_t i = 0; i < log.size(); i += plotStride(log.size())) {
      double S = 0.0;
      for (const auto& n : log.n_rpm) S += n[i] * n[i];
      pts.x.push_back(log.h_m[i]);
      // F̃_G with the hover's own k_T: (m·a_ext,z + k_T·S)/(k_T'·S) − 1.
      pts.y.push_back((base.mass_kg * log.a_ext_W[2][i] + base.rotor.k_T_N_per_rpm2 * S) /
                          (fit.k_T_N_per_rpm2.value * S) - 1.0);
      fitted.x.push_back(log.h_m[i]);
      fitted.y.push_back(fit.g2_m2.value / (log.h_m[i] * log.h_m[i] + fit.g1_m2.value));
    }
    fg.series = {pts, fitted};
    page.addPlot(fg);
    return o;
  }
  const auto log = ident::readFlightLog(opt.log, c);
  ident::DragFitOptions dopt;
  dopt.robust = robustOptions(opt.loss);
  dopt.height_bands = opt.height_bands;
  const auto fit = ident::fitDrag(log, base.mass_kg, dopt);
  std::string table = ",\"drag_table\":[";
  report::Plot dp{"Drag coefficients per height (eq. 20)", "h [m]", "d [N/(m/s)]", {}};
  report::Series dx = series("d_x", "lines+markers", "");
  report::Series dy = series("d_y", "lines+markers", "");
  for (std::size_t b = 0; b < fit.bands.size(); ++b) {
    const auto& band = fit.bands[b];
    const std::string h = fmt::format("{:.3g}", band.h_mean_m);
    o.params.push_back({"d_x at h = " + h + " m", band.d_x_N_per_mps, "N/(m/s)"});
    o.params.push_back({"d_y at h = " + h + " m", band.d_y_N_per_mps, "N/(m/s)"});
    o.fits.push_back({"drag x, h = " + h + " m", band.x, "N"});
    o.fits.push_back({"drag y, h = " + h + " m", band.y, "N"});
    table += fmt::format("{}{{\"h_m\":{},\"d_x_N_per_mps\":{},\"d_x_std_error\":{},\"d_y_N_per_mps\":{},"
                         "\"d_y_std_error\":{}}}",
                         b ? "," : "", jsonNumber(band.h_mean_m), jsonNumber(band.d_x_N_per_mps.value),
                         jsonNumber(band.d_x_N_per_mps.std_error), jsonNumber(band.d_y_N_per_mps.value),
                         jsonNumber(band.d_y_N_per_mps.std_error));
    dx.x.push_back(band.h_mean_m);
    dx.y.push_back(band.d_x_N_per_mps.value);
    dy.x.push_back(band.h_mean_m);
    dy.y.push_back(band.d_y_N_per_mps.value);
  }
  o.json_extra = table + "]";
  o.warnings = fit.warnings;
  ident::addDrag(o.update, fit);
  addStatsTable(o, page);
  dp.series = {dx, dy};
  page.addPlot(dp);
  return o;
}

Outcome identifyCorrelations(const IdentifyOptions& opt, const std::map<std::string, std::string>& cols,
                         report::Page& page,
                             const model::VehicleParams& base) {
  const auto log = ident::readPlatformLog(opt.log, platformColumns(cols));
  const auto t = ident::platformCorrelations(log, base);
  Outcome o;
  report::Table table{"Spearman rank correlations (ties: average ranks)", {""}, {}};
  for (const auto& c : t.column_names) table.header.push_back(c);
  std::string json = ",\"correlations\":{\"rows\":[";
  for (std::size_t r = 0; r < t.row_names.size(); ++r) json += (r ? "," : "") + jsonString(t.row_names[r]);
  json += "],\"columns\":[";
  for (std::size_t c = 0; c < t.column_names.size(); ++c) json += (c ? "," : "") + jsonString(t.column_names[c]);
  json += "],\"r\":[";
  fmt::print("{:>10}", "");
  for (const auto& c : t.column_names) fmt::print(" {:>21}", c);
  fmt::print("\n");
  for (Eigen::Index r = 0; r < t.r.rows(); ++r) {
    std::vector<std::string> row{t.row_names[static_cast<std::size_t>(r)]};
    fmt::print("{:>10}", row.front());
    json += r ? ",[" : "[";
    for (Eigen::Index c = 0; c < t.r.cols(); ++c) {
      row.push_back(fmt::format("{:+.4f}", t.r(r, c)));
      fmt::print(" {:>21}", row.back());
      json += (c ? "," : "") + jsonNumber(t.r(r, c));
    }
    json += "]";
    fmt::print("\n");
    table.rows.push_back(row);
  }
  json += "],\"samples\":[";
  for (std::size_t c = 0; c < t.samples.size(); ++c) json += fmt::format("{}{}", c ? "," : "", t.samples[c]);
  o.json_extra = json + "]}";
  page.addTable(table);
  return o;
}

// ------------------------------------------------------------------------------- the runner

int runIdentify(const IdentifyOptions& opt) {
  const auto cols = parseColumns(opt.columns);
  const model::VehicleParams base = opt.vehicle.empty() ? io::builtinVehicle() : io::loadVehicleFile(opt.vehicle);
  // The report page: the command first, then what the identification adds.
  report::Page page("geaware identify " + opt.kind + ": " +
                    std::filesystem::path(opt.log).filename().string());
  std::string cmd = "geaware identify " + opt.kind + " " + opt.log;
  if (!opt.vehicle.empty()) cmd += " --vehicle " + opt.vehicle;
  if (opt.kind == "platform") cmd += fmt::format(" --tilt-limit {}", opt.tilt_limit_deg);
  if (opt.kind == "platform") {
    cmd += " --ground-effect " + opt.ground_effect;
    if (opt.ground_effect == "table") {
      cmd += opt.table_heights.empty() ? fmt::format(" --table-top {}", opt.table_top_m)
                                       : " --table-heights " + opt.table_heights;
    }
  }
  if (opt.kind == "platform" || opt.kind == "flight") cmd += fmt::format(" --height-bands {}", opt.height_bands);
  if (opt.hover) cmd += " --hover";
  for (const auto& c : opt.columns) cmd += " --column " + c;
  page.addText("Command: " + cmd + " --loss " + opt.loss);
  Outcome o;
  if (opt.kind == "rotor") {
    o = identifyRotor(opt, cols, page);
  } else if (opt.kind == "platform") {
    o = identifyPlatform(opt, cols, page, base);
  } else if (opt.kind == "flight") {
    o = identifyFlight(opt, cols, page, base);
  } else {
    o = identifyCorrelations(opt, cols, page, base);
  }

  for (const auto& p : o.params) {
    fmt::print("{:<45} {:>14.7g} ± {:<10.3g} {}\n", p.name, p.e.value, p.e.std_error, p.unit);
  }
  for (const auto& f : o.fits) {
    fmt::print("residual RMS {:<32} {:>10.4g} {:<6} ({} samples, {} outliers)\n", f.name,
               f.stats.residual_rms, f.unit, f.stats.count, f.stats.outliers);
  }
  for (const auto& w : o.warnings) std::cerr << "geaware: warning: " << w << "\n";

  if (!opt.out.empty()) {
    if (o.update.empty()) throw std::invalid_argument("--out: `identify " + opt.kind + "` fits no vehicle-file keys");
    o.update.provenance = std::filesystem::path(opt.log).filename().string();
    const auto result = opt.vehicle.empty()
                            ? io::writeVehicleFile(io::builtinVehicleYaml(), "built-in vehicle", opt.out, o.update)
                            : io::writeVehicleFile(opt.vehicle, opt.out, o.update);
    for (const auto& n : result.notes) std::cerr << "geaware: note: " << opt.out << ": " << n << "\n";
  }
  if (!opt.json.empty()) {
    std::string doc = fmt::format("{{\"command\":{},\"log\":{},\"parameters\":{{", jsonString(opt.kind), jsonString(opt.log));
    for (std::size_t i = 0; i < o.params.size(); ++i) {
      doc += fmt::format("{}{}:{{\"value\":{},\"std_error\":{},\"unit\":{}}}", i ? "," : "",
                         jsonString(o.params[i].name), jsonNumber(o.params[i].e.value),
                         jsonNumber(o.params[i].e.std_error), jsonString(o.params[i].unit));
    }
    doc += "},\"fits\":{";
    for (std::size_t i = 0; i < o.fits.size(); ++i) {
      doc += fmt::format("{}{}:{{\"residual_rms\":{},\"unit\":{},\"count\":{},\"outliers\":{}}}", i ? "," : "",
                         jsonString(o.fits[i].name), jsonNumber(o.fits[i].stats.residual_rms),
                         jsonString(o.fits[i].unit), o.fits[i].stats.count, o.fits[i].stats.outliers);
    }
    doc += "},\"warnings\":[";
    for (std::size_t i = 0; i < o.warnings.size(); ++i) doc += (i ? "," : "") + jsonString(o.warnings[i]);
    doc += "]" + o.json_extra + "}\n";
    if (opt.json == "-") {
      std::cout << doc;
    } else {
      std::ofstream f(opt.json);
      if (!(f << doc)) throw std::runtime_error(opt.json + ": cannot write JSON output");
    }
  }
  if (!opt.report.empty()) {
    for (const auto& w : o.warnings) page.addText("Warning: " + w);
    std::filesystem::create_directories(opt.report);
    page.write(std::filesystem::path(opt.report) / "index.html");
  }
  return 0;
}

}  // namespace

Runner addIdentifyCommand(CLI::App& app) {
  auto opts = std::make_shared<IdentifyOptions>();
  auto* cmd = app.add_subcommand("identify", "Fit vehicle parameters from rig and flight logs");
  cmd->require_subcommand(1);
  const std::vector<std::pair<std::string, std::string>> kinds = {
      {"rotor", "k_T, k_I, J_R and the throttle curve from a single-rotor stand log"},
      {"platform", "k_T, F_G (g1, g2), k_TX, k_TY, k_I and the leveling torque from a quadrotor platform log"},
      {"flight", "the drag table D(h) from a flight log, or F_G from a hover descent (--hover)"},
      {"correlations", "the Spearman rank-correlation table of a quadrotor platform log"}};
  for (const auto& [name, help] : kinds) {
    auto* sub = cmd->add_subcommand(name, help);
    sub->add_option("log", opts->log, "the log (CSV; formats in docs/identification.md)")
        ->required()
        ->check(CLI::ExistingFile);
    sub->add_option("--vehicle", opts->vehicle,
                    "base vehicle file: b, m and the priors the fits need, and the file --out merges into "
                    "(default: the built-in paper quadrotor)")
        ->check(CLI::ExistingFile);
    sub->add_option("--out", opts->out, "write the base vehicle file with the fitted keys merged in");
    sub->add_option("--json", opts->json, "write every parameter, standard error and residual RMS as JSON ('-': stdout)");
    sub->add_option("--report", opts->report, "write an HTML report (parameters, residuals, fit plots) to DIR");
    sub->add_option("--column", opts->columns, "rename a column, DEFAULT=ACTUAL (e.g. fz_N=Fz); repeatable");
    sub->add_option("--loss", opts->loss, "robust loss")->check(CLI::IsMember({"huber", "cauchy", "none"}))->capture_default_str();
    if (name == "platform") {
      sub->add_option("--tilt-limit", opts->tilt_limit_deg, "largest board tilt used for the leveling torque [deg]")
          ->capture_default_str();
      sub->add_option("--ground-effect", opts->ground_effect,
                      "form of F_G and M_G: 'paper' (g2/(h² + g1), scale·h/(h² + g3·h + g4)²) or 'table' "
                      "(values at knot heights, for curves the closed forms do not follow)")
          ->check(CLI::IsMember({"paper", "table"}))
          ->capture_default_str();
      sub->add_option("--table-top", opts->table_top_m,
                      "table: F_G knots at the logged heights up to this one; level samples above it follow the "
                      "1/h² tail and fix k_T [m]")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
      sub->add_option("--table-heights", opts->table_heights,
                      "table: explicit knot heights FROM:TO:STEP for both curves [m] (instead of the logged heights)");
    }
    if (name == "platform" || name == "flight") {
      sub->add_option("--height-bands", opts->height_bands, "number of height bands")->check(CLI::Range(1, 100))->capture_default_str();
    }
    if (name == "flight") sub->add_flag("--hover", opts->hover, "the log is a hover descent: fit F_G (eq. 10)");
    sub->callback([opts, name = name] { opts->kind = name; });
  }
  return [opts] { return runIdentify(*opts); };
}

}  // namespace geaware::cli
