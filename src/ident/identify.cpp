// SPDX-License-Identifier: BSD-3-Clause
// Identification results of the single-rotor stand, flights, hover descents and the platform's
// correlation table (the platform's own: identify_platform.cpp), and their text form.

#include "geaware/ident/identify.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "identify_support.hpp"

namespace geaware::ident {

namespace detail {

CurveData sampledCurve(std::string name, const std::function<double(double)>& f, double from,
                       double to, std::string dash) {
  CurveData c = curveData(std::move(name), "lines", std::move(dash));
  for (int k = 0; k <= 400; ++k) {
    const double h = from + (to - from) * k / 400.0;
    c.x.push_back(h);
    c.y.push_back(f(h));
  }
  return c;
}

void addStatsTables(IdentifyResult& r) {
  TextTable params{"Parameters", {"parameter", "value", "std. error", "unit"}, {}};
  for (const auto& p : r.parameters) {
    params.rows.push_back({p.name, fmt::format("{:.6g}", p.estimate.value),
                           fmt::format("{:.3g}", p.estimate.std_error), p.unit});
  }
  r.report_tables.push_back(std::move(params));
  TextTable fits{"Residuals", {"fit", "residual RMS", "unit", "samples", "outliers", "condition number"}, {}};
  for (const auto& f : r.residuals) {
    fits.rows.push_back({f.name, fmt::format("{:.4g}", f.stats.residual_rms), f.unit,
                         std::to_string(f.stats.count), std::to_string(f.stats.outliers),
                         fmt::format("{:.3g}", f.stats.condition_number)});
    if (f.stats.condition_number > kIllConditioned) {
      r.warnings.push_back(fmt::format("fit {}: condition number {:.3g} of its design (above {:g}): its parameters "
                                       "trade off against each other, the data determine only a combination of "
                                       "them (widen the heights or rotor speeds logged)",
                                       f.name, f.stats.condition_number, kIllConditioned));
    }
  }
  r.report_tables.push_back(std::move(fits));
}

void appendWarnings(std::vector<std::string>& to, const std::vector<std::string>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

}  // namespace detail

using detail::curveData;
using detail::plotStride;

RobustOptions robustLoss(std::string_view name) {
  RobustOptions r;
  if (name == "cauchy") {
    r.loss = RobustLoss::kCauchy;
    r.loss_scale = 2.385;
  } else if (name == "none") {
    r.loss = RobustLoss::kNone;
  } else if (name != "huber") {
    throw std::invalid_argument("unknown robust loss '" + std::string(name) +
                                "' (huber, cauchy or none)");
  }
  return r;
}

IdentifyResult identifyRotorStand(const RotorStandLog& log, const IdentifyOptions& options) {
  RotorFitOptions fo;
  fo.robust = options.robust;
  fo.reference_voltage_V = options.reference_voltage_V;
  const RotorFit fit = fitRotorStand(log, fo);
  IdentifyResult r;
  r.kind = "rotor";
  r.parameters = {{"rotor.k_T_N_per_rpm2", fit.k_T_N_per_rpm2, "N/rpm²"},
                  {"rotor.k_I_Nm_per_rpm2", fit.k_I_Nm_per_rpm2, "N·m/rpm²"}};
  if (fit.J_R_kgm2) r.parameters.push_back({"rotor.J_R_kgm2", *fit.J_R_kgm2, "kg·m²"});
  r.parameters.push_back({"throttle_curve.c2_rpm2", fit.c2_rpm2, "rpm²"});
  r.parameters.push_back({"throttle_curve.c1_rpm2", fit.c1_rpm2, "rpm²"});
  r.parameters.push_back({"throttle_curve.c0_rpm2", fit.c0_rpm2, "rpm²"});
  if (fit.reference_voltage_V && fit.voltage_exponent) {
    // V_ref is chosen (the median voltage, or the option), not fitted: no standard error.
    r.parameters.push_back({"throttle_curve.reference_voltage_V", {*fit.reference_voltage_V, 0.0}, "V"});
    r.parameters.push_back({"throttle_curve.voltage_exponent", *fit.voltage_exponent, ""});
  }
  r.residuals = {{"thrust", fit.thrust, "N"},
                 {"torque", fit.torque, "N·m"},
                 {"throttle curve (n²/n)", fit.throttle, "rpm"}};
  r.warnings = fit.warnings;
  r.blocking = fit.blocking;
  addRotorFit(r.update, fit);
  detail::addStatsTables(r);

  // Measurements (at most 4000 of each) and the fitted curves.
  PlotData thrust{"Thrust vs rpm² (single-rotor stand)", "n² [rpm²]", "thrust [N]", {}};
  PlotData throttle{"Throttle curve", "throttle [-]", "n [rpm]", {}};
  CurveData meas = curveData("measured", "markers");
  CurveData tmeas = curveData("measured", "markers");
  for (std::size_t i = 0; i < log.size(); i += plotStride(log.size())) {
    meas.x.push_back(log.rpm[i] * log.rpm[i]);
    meas.y.push_back(log.thrust_N[i]);
    tmeas.x.push_back(log.throttle[i]);
    tmeas.y.push_back(log.rpm[i]);
  }
  CurveData line = curveData("k_T·n²", "lines");
  CurveData curve = curveData("√(c2·t² + c1·t + c0)", "lines");
  const double n_max = *std::max_element(log.rpm.begin(), log.rpm.end());
  for (int k = 0; k <= 50; ++k) {
    const double n2 = n_max * n_max * k / 50.0;
    line.x.push_back(n2);
    line.y.push_back(fit.k_T_N_per_rpm2.value * n2);
    const double t = k / 50.0;
    curve.x.push_back(t);
    curve.y.push_back(std::sqrt(
        std::max(0.0, (fit.c2_rpm2.value * t + fit.c1_rpm2.value) * t + fit.c0_rpm2.value)));
  }
  thrust.curves = {meas, line};
  throttle.curves = {tmeas, curve};
  r.plots = {thrust, throttle};
  r.fits.rotor = fit;
  return r;
}

namespace {

/// Fewer samples out of ground effect than this do not give k_T alone in place of a failed F_G fit.
constexpr std::size_t kMinHoverKTSamples = 10;

/// The rows of `log` whose height is at least `h_m`.
FlightLog rowsAtOrAbove(const FlightLog& log, double h_m) {
  FlightLog out;
  out.source = log.source;
  out.first_data_line = log.first_data_line;
  const auto copy = [](const std::vector<double>& from, std::vector<double>& to, std::size_t i) {
    if (i < from.size()) to.push_back(from[i]);
  };
  for (std::size_t i = 0; i < log.size(); ++i) {
    if (!(log.h_m[i] >= h_m)) continue;
    copy(log.t_s, out.t_s, i);
    copy(log.h_m, out.h_m, i);
    for (std::size_t k = 0; k < 3; ++k) copy(log.v_W[k], out.v_W[k], i), copy(log.a_ext_W[k], out.a_ext_W[k], i);
    for (std::size_t k = 0; k < 4; ++k) copy(log.q_WB[k], out.q_WB[k], i), copy(log.n_rpm[k], out.n_rpm[k], i);
  }
  return out;
}

/// A hover that never came within kHoverGroundEffectRadii rotor radii of the ground: k_T alone.
IdentifyResult hoverKTAlone(const FlightLog& log, const model::VehicleParams& base,
                            const IdentifyOptions& options, double reach_m) {
  const HoverThrustFit fit = fitHoverThrustOutOfGroundEffect(log, base.mass_kg, base.rotor.k_T_N_per_rpm2,
                                                             options.robust);
  IdentifyResult r;
  r.kind = "hover";
  r.parameters = {{"rotor.k_T_N_per_rpm2", fit.k_T_N_per_rpm2, "N/rpm²"}};
  r.residuals = {{"m·a_ext,z + k_T·Σn² = k_T'·Σn²", fit.stats, "N"}};
  r.warnings = fit.warnings;
  if (!(fit.k_T_N_per_rpm2.value > 0.0)) {
    r.blocking.push_back(fmt::format("k_T = {:.4g} fitted at or below 0, outside its physical range (> 0)",
                                     fit.k_T_N_per_rpm2.value));
  }
  r.notes.push_back(fmt::format(
      "F_G not fitted: the lowest logged height {:.4g} m is not below {:g} rotor radii ({:.4g} m for "
      "geometry.propeller_radius_m = {:.4g}); k_T alone, with F_G taken as 0 (descend below {:.4g} m to fit g1, g2)",
      fit.h_min_m, kHoverGroundEffectRadii, reach_m, base.propeller_radius_m, reach_m));
  setEstimate(r.update, "rotor.k_T_N_per_rpm2", fit.k_T_N_per_rpm2);
  detail::addStatsTables(r);
  r.fits.hover_thrust = fit;
  return r;
}

}  // namespace

IdentifyResult identifyHover(const FlightLog& log, const model::VehicleParams& base,
                             const IdentifyOptions& options) {
  if (!(base.propeller_radius_m > 0.0)) {
    throw IdentError(log.source + ": the base vehicle has no geometry.propeller_radius_m: the hover fit needs it to "
                     "tell whether the log comes near the ground (below 3 rotor radii)");
  }
  const double reach_m = kHoverGroundEffectRadii * base.propeller_radius_m;
  if (!log.h_m.empty() && *std::min_element(log.h_m.begin(), log.h_m.end()) >= reach_m) {
    return hoverKTAlone(log, base, options, reach_m);
  }
  AdditionalThrustFit fit;
  try {
    fit = fitHoverAdditionalThrust(log, base.mass_kg, base.rotor.k_T_N_per_rpm2, options.robust);
  } catch (const IdentError& e) {
    // Too few or too collinear samples near the ground (a take-off and a landing logged at a few
    // Hz): k_T alone from the samples out of ground effect, and said so; with none, the error.
    const FlightLog high = rowsAtOrAbove(log, reach_m);
    if (high.size() < kMinHoverKTSamples) throw;
    IdentifyResult r = hoverKTAlone(high, base, options, reach_m);
    r.notes.clear();
    r.warnings.push_back(fmt::format(
        "F_G not fitted: {} ({} of {} samples below {:g} rotor radii, {:.4g} m); k_T alone from the {} samples at "
        "or above that height, with F_G taken as 0 there",
        e.what(), log.size() - high.size(), log.size(), kHoverGroundEffectRadii, reach_m, high.size()));
    return r;
  }
  IdentifyResult r;
  r.kind = "hover";
  r.parameters = {{"rotor.k_T_N_per_rpm2", fit.k_T_N_per_rpm2, "N/rpm²"},
                  {"ground_effect.additional_thrust.g1_m2", fit.g1_m2, "m²"},
                  {"ground_effect.additional_thrust.g2_m2", fit.g2_m2, "m²"}};
  r.residuals = {{"m·a_ext,z + k_T·Σn² = k_T'·Σn²·(1 + F_G(h))", fit.stats, "N"}};
  r.warnings = fit.warnings;
  // k_T, g1 and g2 are bounded to [0 or 1e-9, …] in the fit: a value at or below 0 is one at its bound.
  r.blocking = fit.blocking;
  addAdditionalThrust(r.update, fit);  // k_T in hover goes with its g1, g2
  detail::addStatsTables(r);
  PlotData fg{"F_G from the hover descent (eq. 10)", "h [m]", "F_G [-]", {}};
  CurveData pts = curveData("m·a_ext,z/T̃", "markers");
  CurveData fitted = curveData("fit", "lines");
  for (std::size_t i = 0; i < log.size(); i += plotStride(log.size())) {
    double S = 0.0;
    for (const auto& n : log.n_rpm) S += n[i] * n[i];
    pts.x.push_back(log.h_m[i]);
    // F̃_G with the hover's own k_T: (m·a_ext,z + k_T·S)/(k_T'·S) − 1.
    pts.y.push_back((base.mass_kg * log.a_ext_W[2][i] + base.rotor.k_T_N_per_rpm2 * S) /
                        (fit.k_T_N_per_rpm2.value * S) -
                    1.0);
    fitted.x.push_back(log.h_m[i]);
    fitted.y.push_back(fit.g2_m2.value / (log.h_m[i] * log.h_m[i] + fit.g1_m2.value));
  }
  fg.curves = {pts, fitted};
  r.plots = {fg};
  r.fits.additional_thrust = fit;
  return r;
}

IdentifyResult identifyForwardFade(const FlightLog& log, const model::VehicleParams& base,
                                   const IdentifyOptions& options) {
  const ForwardFadeFit fit = fitForwardFade(log, base, options.robust);
  IdentifyResult r;
  r.kind = "fade";
  r.parameters = {{"ground_effect.forward_fade.induced_velocity_mps", fit.induced_velocity_mps, "m/s"},
                  {"w = 1/v_i²", fit.w_s2_per_m2, "s²/m²"},
                  {"cushion scale s (against the vehicle's F_G)", fit.cushion_scale, "-"},
                  {"translational lift c_TL", fit.translational_lift_per_mps2, "s²/m²"},
                  {"k_T in this flight (not merged)", fit.k_T_N_per_rpm2, "N/rpm²"}};
  r.residuals = {{"m·z_Bᵀa_ext + k_T·Σn² = k_T'·Σn²·(1 + c_TL·V² + s·F_G(h)/(1 + w·V²))", fit.stats, "N"}};
  r.warnings = fit.warnings;
  r.blocking = fit.blocking;
  r.notes.push_back(fmt::format("{} samples near the ground (F_G(h) >= {:g}), the fastest at {:.3g} m/s",
                                fit.near_ground, kFadeMinThrustRatio, fit.max_speed_near_ground_mps));
  if (std::isfinite(fit.induced_velocity_mps.value)) {
    setEstimate(r.update, "ground_effect.forward_fade.induced_velocity_mps", fit.induced_velocity_mps);
  }
  detail::addStatsTables(r);
  PlotData fade{"Forward-flight fade of the ground cushion", "V [m/s]", "fade [-]", {}};
  CurveData fitted = curveData("fit 1/(1 + w·V²)", "lines");
  for (int k = 0; k <= 50; ++k) {
    const double V = 0.2 * k;
    fitted.x.push_back(V);
    fitted.y.push_back(1.0 / (1.0 + fit.w_s2_per_m2.value * V * V));
  }
  fade.curves = {fitted};
  r.plots = {fade};
  r.fits.forward_fade = fit;
  return r;
}

IdentifyResult identifyFlight(const FlightLog& log, const model::VehicleParams& base,
                              const IdentifyOptions& options) {
  DragFitOptions dopt;
  dopt.robust = options.robust;
  dopt.height_bands = options.height_bands;
  const DragFit fit = fitDrag(log, base.mass_kg, dopt);
  IdentifyResult r;
  r.kind = "flight";
  PlotData dp{"Drag coefficients per height (eq. 20)", "h [m]", "d [N/(m/s)]", {}};
  CurveData dx = curveData("d_x", "lines+markers");
  CurveData dy = curveData("d_y", "lines+markers");
  for (const auto& band : fit.bands) {
    const std::string h = fmt::format("{:.3g}", band.h_mean_m);
    r.parameters.push_back({"d_x at h = " + h + " m", band.d_x_N_per_mps, "N/(m/s)"});
    r.parameters.push_back({"d_y at h = " + h + " m", band.d_y_N_per_mps, "N/(m/s)"});
    r.residuals.push_back({"drag x, h = " + h + " m", band.x, "N"});
    r.residuals.push_back({"drag y, h = " + h + " m", band.y, "N"});
    dx.x.push_back(band.h_mean_m);
    dx.y.push_back(band.d_x_N_per_mps.value);
    dy.x.push_back(band.h_mean_m);
    dy.y.push_back(band.d_y_N_per_mps.value);
  }
  r.warnings = fit.warnings;
  for (const auto& band : fit.bands) {
    for (const auto& [axis, d] : {std::pair{"d_x", band.d_x_N_per_mps}, std::pair{"d_y", band.d_y_N_per_mps}}) {
      if (d.value >= 0.0) continue;
      // Drag opposes the motion: a negative coefficient is no drag. It is never written (as 0 or
      // otherwise): the band is left out of the table --out writes (dragTable).
      r.blocking.push_back(fmt::format("{} at h = {:.3g} m fitted negative ({:.4g} ± {:.3g} N/(m/s)), outside the "
                                       "physical range d ≥ 0 (a wrong mass, k_T or frame in the log?); the band is "
                                       "left out of the drag table --out writes",
                                       axis, band.h_mean_m, d.value, d.std_error));
    }
  }
  addDrag(r.update, fit);
  detail::addStatsTables(r);
  dp.curves = {dx, dy};
  r.plots = {dp};
  r.fits.drag = fit;
  return r;
}

IdentifyResult identifyCorrelations(const PlatformLog& log, const model::VehicleParams& base) {
  IdentifyResult r;
  r.kind = "correlations";
  const CorrelationTable t = platformCorrelations(log, base);
  TextTable table{"Spearman rank correlations (ties: average ranks)", {""}, {}};
  for (const auto& c : t.column_names) table.header.push_back(c);
  for (Eigen::Index i = 0; i < t.r.rows(); ++i) {
    std::vector<std::string> row{t.row_names[static_cast<std::size_t>(i)]};
    for (Eigen::Index j = 0; j < t.r.cols(); ++j) row.push_back(fmt::format("{:+.4f}", t.r(i, j)));
    table.rows.push_back(std::move(row));
  }
  r.report_tables = {std::move(table)};
  r.fits.correlations = t;
  return r;
}

std::string resultText(const IdentifyResult& result) {
  std::string s;
  if (result.fits.correlations) {
    const CorrelationTable& t = *result.fits.correlations;
    s += fmt::format("{:>10}", "");
    for (const auto& c : t.column_names) s += fmt::format(" {:>21}", c);
    s += "\n";
    for (Eigen::Index i = 0; i < t.r.rows(); ++i) {
      s += fmt::format("{:>10}", t.row_names[static_cast<std::size_t>(i)]);
      for (Eigen::Index j = 0; j < t.r.cols(); ++j) {
        s += fmt::format(" {:>21}", fmt::format("{:+.4f}", t.r(i, j)));
      }
      s += "\n";
    }
  }
  for (const auto& p : result.parameters) {
    s += fmt::format("{:<45} {:>14.7g} ± {:<10.3g} {}\n", p.name, p.estimate.value,
                     p.estimate.std_error, p.unit);
  }
  for (const auto& f : result.residuals) {
    s += fmt::format("residual RMS {:<32} {:>10.4g} {:<6} ({} samples, {} outliers, condition number {:.3g})\n",
                     f.name, f.stats.residual_rms, f.unit, f.stats.count, f.stats.outliers,
                     f.stats.condition_number);
  }
  for (const auto& n : result.notes) s += "note: " + n + "\n";
  return s;
}

}  // namespace geaware::ident
