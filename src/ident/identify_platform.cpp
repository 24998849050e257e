// SPDX-License-Identifier: BSD-3-Clause
// Identification result of the quadrotor platform: k_T and F_G from the level board, the mixing
// coefficients from the rpm differences, M_G from the tilted board, in the paper's closed forms
// or as tables; the height-band table and the F_G and M_G plots.

#include <algorithm>
#include <cmath>
#include <functional>

#include <fmt/format.h>

#include "geaware/ident/identify.hpp"
#include "geaware/model/ground_effect.hpp"
#include "geaware/model/height_table.hpp"
#include "identify_support.hpp"

namespace geaware::ident {
namespace {

using detail::curveData;
using detail::plotStride;
using detail::sampledCurve;

/// A fitted curve: as the model evaluates it (for the plots) and the height range of its data.
struct FittedCurve {
  std::function<double(double)> f;
  double h_min_m = 0.0;
  double h_max_m = 0.0;
};

std::vector<double> values(const TableCurve& c) {
  std::vector<double> v;
  for (const auto& e : c.values) v.push_back(e.value);
  return v;
}

/// A fitted table into the result: one parameter row per knot ("F_G(h = 0.07 m)"), the vehicle
/// update with the standard errors, the table itself. Returns the curve as the model
/// interpolates it (PCHIP).
std::function<double(double)> takeTable(IdentifyResult& r, const std::string& curve,
                                        const std::string& unit, FittedTable table) {
  std::vector<double> errors;
  const TableCurve& c = table.curve;
  for (std::size_t j = 0; j < c.values.size(); ++j) {
    r.parameters.push_back({fmt::format("{}(h = {:.4g} m)", curve, c.heights_m[j]), c.values[j], unit});
    errors.push_back(c.values[j].std_error);
  }
  r.update.setTable("ground_effect." + table.section, c.heights_m, values(c), errors);
  auto f = [m = model::HeightTable(c.heights_m, values(c))](double h) { return m.value(h); };
  r.tables.push_back(std::move(table));
  return f;
}

PlatformFitOptions platformOptions(const IdentifyOptions& options) {
  PlatformFitOptions po;
  po.robust = options.robust;
  po.height_bands = options.height_bands;
  if (options.ground_effect == CurveForm::kTable) {
    po.thrust_table.top_m = options.table_top_m;
    if (!options.table_heights_m.empty()) po.thrust_table.heights_m = options.table_heights_m;
  }
  return po;
}

/// k_T alone (IdentifyOptions::k_T_only): one height band, F_G taken as 0, said in the notes.
FittedCurve thrustAlone(IdentifyResult& r, const PlatformLog& log, const PlatformFitOptions& po,
                        const model::VehicleParams& base) {
  const ThrustAloneFit fit = fitThrustAlone(log, po);
  r.parameters = {{"rotor.k_T_N_per_rpm2", fit.k_T_N_per_rpm2, "N/rpm²"}};
  r.residuals = {{"f_z = k_T·Σn² (F_G taken as 0)", fit.stats, "N"}};
  r.warnings = fit.warnings;
  setEstimate(r.update, "rotor.k_T_N_per_rpm2", fit.k_T_N_per_rpm2);
  if (!(fit.k_T_N_per_rpm2.value > 0.0)) {
    r.blocking.push_back(fmt::format("k_T = {:.4g} fitted at or below 0, outside its physical range (> 0)",
                                     fit.k_T_N_per_rpm2.value));
  }
  r.notes.push_back(fmt::format("F_G not fitted (--k-T-only): k_T from every level sample, {:.4g}–{:.4g} m, as one "
                                "height band, with F_G taken as 0",
                                fit.h_min_m, fit.h_max_m));
  const double reach_m = 3.0 * base.propeller_radius_m;
  if (fit.h_min_m < reach_m) {
    r.warnings.push_back(fmt::format("--k-T-only: level samples down to {:.4g} m, below 3 rotor radii ({:.4g} m): "
                                     "their ground effect is counted as k_T",
                                     fit.h_min_m, reach_m));
  }
  return {[](double) { return 0.0; }, fit.h_min_m, fit.h_max_m};
}

/// k_T and F_G from the level board, in the chosen form.
FittedCurve additionalThrust(IdentifyResult& r, const PlatformLog& log, const PlatformFitOptions& po,
                             CurveForm form) {
  const std::string fit_name = "f_z = k_T·Σn²·(1 + F_G(h))";
  if (form == CurveForm::kTable) {
    auto fit = fitAdditionalThrustTable(log, po);
    r.parameters.push_back({"rotor.k_T_N_per_rpm2", fit.k_T_N_per_rpm2, "N/rpm²"});
    r.residuals = {{fit_name, fit.stats, "N"}};
    r.warnings = fit.warnings;
    setEstimate(r.update, "rotor.k_T_N_per_rpm2", fit.k_T_N_per_rpm2);
    FittedCurve c{takeTable(r, "F_G", "-", {"additional_thrust", "F_G", fit.F_G}), fit.h_min_m,
                  fit.h_max_m};
    r.fits.additional_thrust_table = std::move(fit);
    return c;
  }
  auto fit = fitAdditionalThrust(log, po);
  r.parameters = {{"rotor.k_T_N_per_rpm2", fit.k_T_N_per_rpm2, "N/rpm²"},
                  {"ground_effect.additional_thrust.g1_m2", fit.g1_m2, "m²"},
                  {"ground_effect.additional_thrust.g2_m2", fit.g2_m2, "m²"}};
  r.residuals = {{fit_name, fit.stats, "N"}};
  r.warnings = fit.warnings;
  r.blocking = fit.blocking;
  addAdditionalThrust(r.update, fit);
  FittedCurve c{[g1 = fit.g1_m2.value, g2 = fit.g2_m2.value](double h) { return g2 / (h * h + g1); },
                fit.h_min_m, fit.h_max_m};
  r.fits.additional_thrust = std::move(fit);
  return c;
}

void mixingCoefficients(IdentifyResult& r, MixingFit mixing) {
  r.parameters.push_back({"k_T of the top height band (paper's method)", mixing.k_T_top_N_per_rpm2, "N/rpm²"});
  if (mixing.k_TX_N_per_rpm2) r.parameters.push_back({"rotor.k_TX_N_per_rpm2", *mixing.k_TX_N_per_rpm2, "N/rpm²"});
  if (mixing.k_TY_N_per_rpm2) r.parameters.push_back({"rotor.k_TY_N_per_rpm2", *mixing.k_TY_N_per_rpm2, "N/rpm²"});
  if (mixing.k_I_Nm_per_rpm2) r.parameters.push_back({"rotor.k_I_Nm_per_rpm2", *mixing.k_I_Nm_per_rpm2, "N·m/rpm²"});
  r.residuals.push_back({"roll torque", mixing.roll, "N·m"});
  r.residuals.push_back({"pitch torque", mixing.pitch, "N·m"});
  r.residuals.push_back({"yaw torque", mixing.yaw, "N·m"});
  detail::appendWarnings(r.warnings, mixing.warnings);
  addMixing(r.update, mixing);
  r.fits.mixing = std::move(mixing);
}

/// M_G from the tilted board, in the chosen form.
FittedCurve leveling(IdentifyResult& r, const PlatformLog& log, const LevelingInputs& in,
                     const LevelingFitOptions& lo, CurveForm form) {
  if (form == CurveForm::kTable) {
    auto fit = fitLevelingTable(log, in, lo);
    r.residuals.push_back({"leveling torque", fit.stats, "N·m"});
    detail::appendWarnings(r.warnings, fit.warnings);
    FittedCurve c{takeTable(r, "M_G", "m", {"leveling_torque", "M_G_m", fit.M_G}), fit.h_min_m,
                  fit.h_max_m};
    r.fits.leveling_table = std::move(fit);
    return c;
  }
  auto fit = fitLeveling(log, in, lo);
  r.parameters.push_back({"ground_effect.leveling_torque.g3_m", fit.g3_m, "m"});
  r.parameters.push_back({"ground_effect.leveling_torque.g4_m2", fit.g4_m2, "m²"});
  r.parameters.push_back({"ground_effect.leveling_torque.scale_m4", fit.scale_m4, "m⁴"});
  r.residuals.push_back({"leveling torque", fit.stats, "N·m"});
  detail::appendWarnings(r.warnings, fit.warnings);
  detail::appendWarnings(r.blocking, fit.blocking);
  addLeveling(r.update, fit);
  FittedCurve c{[g3 = fit.g3_m.value, g4 = fit.g4_m2.value, s = fit.scale_m4.value](double h) {
                  return levelingCoefficient(g3, g4, s, h);
                },
                fit.h_min_m, fit.h_max_m};
  r.fits.leveling = std::move(fit);
  return c;
}

TextTable bandTable(const MixingFit& mixing) {
  TextTable t{"Coefficients per height band (k_T is k_T·(1 + F_G(h)))",
              {"h [m]", "samples", "k_T", "k_TX", "k_TY", "k_I"},
              {}};
  auto cell = [](const std::optional<Estimate>& e) {
    return e ? fmt::format("{:.5g} ± {:.2g}", e->value, e->std_error) : std::string("–");
  };
  for (const auto& hb : mixing.bands) {
    t.rows.push_back({fmt::format("{:.3g}–{:.3g}", hb.h_min_m, hb.h_max_m), std::to_string(hb.count),
                      cell(hb.k_T_N_per_rpm2), cell(hb.k_TX_N_per_rpm2), cell(hb.k_TY_N_per_rpm2),
                      cell(hb.k_I_Nm_per_rpm2)});
  }
  return t;
}

/// F_G: the paper's per-sample F̃_G (eq. 9) with the fitted k_T, the fit and the base curve.
PlotData thrustPlot(const PlatformLog& log, double k_T, double level_tilt_deg, const FittedCurve& fitted,
                    bool table, const model::GroundEffectModel& base_ge) {
  const auto F = measuredAdditionalThrust(log, k_T);
  PlotData fg{"Additional thrust F_G(h) (level board)", "h [m]", "F_G [-]", {}};
  CurveData pts = curveData("F̃_G = f̃_z/T̃ − 1 (eq. 9)", "markers");
  for (std::size_t i = 0; i < log.size(); i += plotStride(log.size())) {
    if (std::abs(log.tilt_deg[i]) > level_tilt_deg) continue;
    pts.x.push_back(log.h_m[i]);
    pts.y.push_back(F[i]);
  }
  fg.curves = {pts,
               sampledCurve(table ? "fit, table (PCHIP)" : "fit g2/(h² + g1)", fitted.f,
                            fitted.h_min_m, fitted.h_max_m),
               sampledCurve("base vehicle", [&](double h) { return base_ge.thrustRatio(h); },
                            fitted.h_min_m, fitted.h_max_m, "dash")};
  return fg;
}

/// M_G: the per-sample −τ_G,y/(T·sin δ), the fit and the base curve.
PlotData levelingPlot(const PlatformLog& log, const LevelingInputs& in, const LevelingFitOptions& lo,
                      const FittedCurve& fitted, bool table, const model::GroundEffectModel& base_ge) {
  const auto M = measuredLevelingCoefficient(log, in, lo);
  PlotData mg{"Leveling coefficient M_G(h) (tilted board)", "h [m]", "M_G [m]", {}};
  CurveData mp = curveData("−τ_G,y/(T·sin δ)", "markers");
  for (std::size_t i = 0; i < log.size(); i += plotStride(log.size())) {
    if (std::isnan(M[i])) continue;
    mp.x.push_back(log.h_m[i]);
    mp.y.push_back(M[i]);
  }
  mg.curves = {mp,
               sampledCurve(table ? "fit, table (PCHIP)" : "fit", fitted.f, fitted.h_min_m,
                            fitted.h_max_m),
               sampledCurve("base vehicle", [&](double h) { return base_ge.levelingCoefficient(h); },
                            fitted.h_min_m, fitted.h_max_m, "dash")};
  return mg;
}

}  // namespace

IdentifyResult identifyPlatform(const PlatformLog& log, const model::VehicleParams& base,
                                const IdentifyOptions& options) {
  const PlatformFitOptions po = platformOptions(options);
  const bool table = options.ground_effect == CurveForm::kTable;
  IdentifyResult r;
  r.kind = "platform";
  MixingFit mixing = fitMixing(log, base.diagonal_rotor_distance_m, po);
  const FittedCurve thrust = options.k_T_only ? thrustAlone(r, log, po, base)
                                              : additionalThrust(r, log, po, options.ground_effect);
  const double k_T = r.parameters.front().estimate.value;  // rotor.k_T_N_per_rpm2 comes first
  const double k_TY = mixing.k_TY_N_per_rpm2 ? mixing.k_TY_N_per_rpm2->value : base.rotor.k_TY_N_per_rpm2;
  const TextTable bands = bandTable(mixing);
  mixingCoefficients(r, std::move(mixing));

  // The leveling torque, when the log has tilted-board samples.
  const bool tilted = std::any_of(log.tilt_deg.begin(), log.tilt_deg.end(),
                                  [&](double d) { return std::abs(d) > po.level_tilt_deg; });
  LevelingFitOptions lo;
  lo.robust = po.robust;
  lo.max_tilt_deg = options.tilt_limit_deg;
  if (table && !options.table_heights_m.empty()) lo.table.heights_m = options.table_heights_m;
  const LevelingInputs in{k_T, k_TY, base.diagonal_rotor_distance_m};
  std::optional<FittedCurve> lev;
  if (tilted) {
    lev = leveling(r, log, in, lo, options.ground_effect);
  } else {
    r.warnings.push_back("no tilted-board samples: the leveling torque is not identified");
  }

  detail::addStatsTables(r);
  r.report_tables.push_back(bands);
  const model::GroundEffectModel base_ge(base);
  r.plots.push_back(thrustPlot(log, k_T, po.level_tilt_deg, thrust, table, base_ge));
  if (lev) r.plots.push_back(levelingPlot(log, in, lo, *lev, table, base_ge));
  return r;
}

}  // namespace geaware::ident
