// SPDX-License-Identifier: BSD-3-Clause
// The campaign's summary: the text of `geaware bench` and its JSON document (docs/results.md),
// apart from the run (campaign.cpp) so that the run can change without touching its outputs.
#include "geaware/experiments/campaign_summary.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

namespace geaware::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string cell(const MeanStd& m, double paper) {
  if (!std::isfinite(paper)) return fmt::format("{:6.2f} ±{:5.2f} ({:>5})", m.mean, m.std, "-");
  return fmt::format("{:6.2f} ±{:5.2f} ({:5.2f})", m.mean, m.std, paper);
}

/// The acc and torque columns of a row (7 + 1 + 11 characters): the pair, or "recommended".
std::string configurationCells(const TableOneExperiment& x) {
  if (x.recommended) return fmt::format("{:<19}", "recommended");
  return fmt::format("{:<7} {:<11}", control::toString(x.acceleration), control::toString(x.torque));
}

std::string calibrationText(const CampaignResult& r) {
  std::string s;
  const auto& cal = r.calibration;
  s += fmt::format("Calibration as a team would (rigs holding the world's rotors, the scale, {} "
                   "flight{} in the world): {} platform rows, {} stand rows, {:.2f} s\n",
                   cal.flights.size(), cal.flights.size() == 1 ? "" : "s", cal.platform_rows,
                   cal.stand_rows, r.calibration_s);
  s += fmt::format("  {:<42} {:>14} {:>14} {:>10}  {}\n", "parameter", "vehicle file", "measured",
                   "std. err.", "source");
  for (const auto& p : cal.parameters) {
    s += fmt::format("  {:<42} {:>14.6g} {:>14.6g} {:>10.2g}  {}\n", p.key, p.file_value,
                     p.identified, p.std_error, p.source);
  }
  if (cal.k_T_hover_N_per_rpm2 > 0.0) {
    s += fmt::format("  k_T [N/rpm²]: stand {:.5g}, platform {:.5g}, hover flight {:.5g} (flown; the "
                     "paper's 4.0083e-08, 3.7840e-08, 4.2958e-08)\n",
                     cal.k_T_stand_N_per_rpm2, cal.k_T_platform_N_per_rpm2, cal.k_T_hover_N_per_rpm2);
  }
  for (const auto& f : cal.flights) {
    s += fmt::format("  flight '{}': mean logged height {:.3f} m, {} samples, guard {:.3f} s\n",
                     f.purpose, f.mean_height_m, f.samples, f.guard_active_s);
  }
  s += "  F_G(h): truth (noise-free level board) / identified / vehicle file\n";
  for (const auto& pt : cal.thrust_ratio) {
    const int cm = static_cast<int>(std::lround(pt.h_m * 100));
    if (cm != 7 && cm != 10 && cm != 12 && cm != 15 && cm != 18 && cm != 20 && cm != 25 &&
        cm != 30 && cm != 50 && cm != 100)
      continue;
    s += fmt::format("    h = {:4.2f} m: {:.4f} / {:.4f} ({:+5.1f} %) / {:.4f} ({:+5.1f} %)\n",
                     pt.h_m, pt.truth, pt.identified, 100.0 * (pt.identified / pt.truth - 1.0),
                     pt.file, 100.0 * (pt.file / pt.truth - 1.0));
  }
  s += fmt::format("  leveling torque at {:g}° tilt, {:g} rpm [N·m]: truth / identified / vehicle "
                   "file\n",
                   cal.torque_tilt_deg, cal.torque_rpm);
  for (const auto& pt : cal.leveling_torque) {
    const int cm = static_cast<int>(std::lround(pt.h_m * 100));
    if (cm != 10 && cm != 12 && cm != 15 && cm != 18 && cm != 20 && cm != 25 && cm != 30 &&
        cm != 35 && cm != 40)
      continue;
    s += fmt::format("    h = {:4.2f} m: {:+.4f} / {:+.4f} / {:+.4f}\n", pt.h_m, pt.truth,
                     pt.identified, pt.file);
  }
  for (const auto& w : cal.warnings) s += "  warning: " + w + "\n";
  return s;
}

std::string neuralText(const CampaignResult& r) {
  std::string s;
  if (r.neural) {
    const auto& n = *r.neural;
    if (n.user_file) {
      s += fmt::format("\nNeural-Lander: the weight file {} (--neural-weights), not trained here\n", n.file.string());
    } else if (n.trained) {
      s += fmt::format("\nNeural-Lander: trained on {} rows, validation MSE {:.4f} N² per component "
                       "({:.1f} s){}\n",
                       n.rows, n.validation_loss_N2, r.neural_s,
                       n.file.empty() ? "" : ", cached as " + n.file.string());
    } else {
      s += fmt::format("\nNeural-Lander: loaded from the cache, {} ({:.2f} s)\n", n.file.string(),
                       r.neural_s);
    }
  }
  return s;
}

std::string tableOneText(const CampaignResult& r) {
  std::string s;
  if (!r.experiments.empty()) {
    s += fmt::format("\nTable I — ours: mean ±std over {} seed{} (the paper's real flight in "
                     "parentheses), cm\n",
                     r.seeds, r.seeds == 1 ? "" : "s");
    s += fmt::format("{:>3} {:<7} {:<11} {:>5} {:>4} | {:^21} | {:^21} | {:^21} | {:^21} | {:^21} "
                     "| {}\n",
                     "exp", "acc", "torque", "h [m]", "v", "RMSE XOY", "RMSE Z", "RMSE all",
                     "max ‖E_P‖", "σ‖E_P‖", "crashes");
    for (const auto& e : r.experiments) {
      const auto& x = e.experiment;
      s += fmt::format("{:>3} {} {:>5.2f} {:>4g} | {} | {} | {} | {} | {} | {}\n", x.number,
                       configurationCells(x), x.height_m,
                       x.speed_mps, cell(e.rmse_xy_cm, x.paper.rmse_xy_cm),
                       cell(e.rmse_z_cm, x.paper.rmse_z_cm), cell(e.rmse_all_cm, x.paper.rmse_all_cm),
                       cell(e.max_cm, x.paper.max_cm), cell(e.std_cm, x.paper.std_cm), e.crashes);
    }
    for (const auto& e : r.experiments) {
      if (e.crashes == 0) continue;
      std::string times;
      for (std::size_t k = 0; k < e.seeds.size(); ++k) {
        if (e.crashed[k]) {
          times += fmt::format("{}seed {} at {:.2f} s", times.empty() ? "" : ", ", e.seeds[k],
                               e.crash_t_s[k]);
        }
      }
      s += fmt::format("  exp {}: ground strike{} ({}); its metrics are those up to the strike\n",
                       e.experiment.number, e.crashes == 1 ? "" : "s", times);
    }
    for (const auto& e : r.experiments) {
      if (std::isnan(e.guard_active_s)) continue;
      s += fmt::format("  exp {} ({}): clearance guard active {:.3f} s over its {} flight{}\n",
                       e.experiment.number, control::configurationName(e.experiment.controller()),
                       e.guard_active_s, e.seeds.size(), e.seeds.size() == 1 ? "" : "s");
    }
  }
  return s;
}

std::string hoverText(const CampaignResult& r) {
  std::string s;
  if (!r.hover.empty()) {
    s += fmt::format("\nHover descent (acceleration side: recommended's; torque compensation per "
                     "column): angle error E between desired and true attitude by true rotor-plane "
                     "height, deg (mean over {} seed{})\n",
                     r.seeds, r.seeds == 1 ? "" : "s");
    s += "  (peaks among the bins every seed visited; reported, not checked)\n";
    s += fmt::format("{:>13}", "h [m]");
    for (const auto& c : r.hover) s += fmt::format(" {:>11}", control::toString(c.torque));
    s += "\n";
    // The union of bins (every curve has the same binning).
    std::set<double> centres;
    for (const auto& c : r.hover) {
      for (const auto& b : c.bins) centres.insert(std::round(b.centre_m() * 1e6) / 1e6);
    }
    for (double h : centres) {
      s += fmt::format("{:>13}", fmt::format("{:.3f}", h));
      for (const auto& c : r.hover) {
        double v = kNaN;
        for (const auto& b : c.bins) {
          if (std::abs(b.centre_m() - h) < 1e-6) v = b.angle_err_deg;
        }
        s += std::isfinite(v) ? fmt::format(" {:>11.3f}", v) : fmt::format(" {:>11}", "–");
      }
      s += "\n";
    }
    for (const auto& c : r.hover) {
      const double peak_h = peakHeight(c);
      s += fmt::format("  {:<11} peak {:.3f}° at {:.3f} m; mean E 0.1–0.3 m {:.3f}°, 1–1.5 m "
                       "{:.3f}° (ratio {:.2f}){}\n",
                       control::toString(c.torque), bandMax(c, peak_h - 1e-6, peak_h + 1e-6), peak_h,
                       bandMean(c, 0.1, 0.3), bandMean(c, 1.0, 1.5),
                       bandMean(c, 0.1, 0.3) / bandMean(c, 1.0, 1.5),
                       c.crashes ? fmt::format(", {} crashes", c.crashes) : "");
    }
  }
  return s;
}

std::string checksText(const CampaignResult& r) {
  std::string s;
  s += "\nHeadline ratios and acceptance checks (issue 6):\n";
  for (const auto& c : r.checks) {
    s += fmt::format("  [{}] {}: {:.3f} (criterion {}; paper {})\n", c.pass ? "pass" : "FAIL",
                     c.name, c.value, c.criterion, c.paper);
  }
  const auto* e1 = r.experiment(1);
  const auto* e5 = r.experiment(5);
  const auto* e6 = r.experiment(6);
  const auto* e7 = r.experiment(7);
  // A row with a struck flight has no comparable RMSE (its mean covers flights cut short).
  const auto reduction = [&s](const ExperimentSummary* a, const ExperimentSummary* b,
                              double paper_a_cm, double paper_b_cm) {
    if (!a || !b) return;
    const std::string what = fmt::format("  reduction of RMSE all, exp {} vs exp {}: ",
                                         a->experiment.number, b->experiment.number);
    const double paper = 100.0 * (1.0 - paper_a_cm / paper_b_cm);
    if (a->crashes > 0 || b->crashes > 0) {
      s += fmt::format("{}not comparable, a row struck (paper {:.1f} %)\n", what, paper);
    } else {
      s += fmt::format("{}{:.1f} % (paper {:.1f} %)\n", what,
                       100.0 * (1.0 - a->rmse_all_cm.mean / b->rmse_all_cm.mean), paper);
    }
  };
  reduction(e5, e1, 4.45, 10.85);
  reduction(e7, e6, 6.97, 12.74);
  s += fmt::format("\n{} flights, {:.0f} s simulated, on {} thread{}; wall time {:.1f} s "
                   "(calibration {:.1f} s, Neural-Lander {:.1f} s, flights {:.1f} s)\n",
                   r.flights, r.simulated_s, r.threads, r.threads == 1 ? "" : "s", r.wall_s,
                   r.calibration_s, r.neural_s, r.flights_s);
  return s;
}

}  // namespace

std::string formatCampaign(const CampaignResult& r) {
  return calibrationText(r) + neuralText(r) + tableOneText(r) + hoverText(r) + checksText(r);
}

// ------------------------------------------------------------------------------------ JSON

namespace {

io::Json metricsJson(const TableMetrics& m) {
  return {{"rmse_xy_cm", m.rmse_xy_cm}, {"rmse_z_cm", m.rmse_z_cm}, {"rmse_all_cm", m.rmse_all_cm},
          {"max_cm", m.max_cm}, {"std_cm", m.std_cm}};
}

io::Json experimentJson(const ExperimentSummary& e) {
  const auto& x = e.experiment;
  const TableMetrics mean{e.rmse_xy_cm.mean, e.rmse_z_cm.mean, e.rmse_all_cm.mean, e.max_cm.mean,
                          e.std_cm.mean};
  const TableMetrics sd{e.rmse_xy_cm.std, e.rmse_z_cm.std, e.rmse_all_cm.std, e.max_cm.std,
                        e.std_cm.std};
  io::Json j = {{"exp", x.number},
                {"acc", control::toString(x.acceleration)},
                {"torque", control::toString(x.torque)},
                {"controller", control::configurationName(x.controller())},
                {"height_m", x.height_m},
                {"speed_mps", x.speed_mps},
                {"half_extent_x_m", x.half_extent_x_m},
                {"half_extent_y_m", x.half_extent_y_m}};
  j.update(metricsJson(mean));
  j["crashes"] = e.crashes;
  j["guard_active_s"] = std::isnan(e.guard_active_s) ? io::Json(nullptr) : io::Json(e.guard_active_s);
  j["seeds"] = e.seeds.size();
  j["std_over_seeds"] = metricsJson(sd);
  j["paper"] = x.hasPaper() ? metricsJson(x.paper) : io::Json(nullptr);
  io::Json per_seed = io::Json::array();
  for (std::size_t s = 0; s < e.per_seed.size(); ++s) {
    io::Json f = {{"seed", e.seeds[s]}};
    f.update(metricsJson(e.per_seed[s]));
    f["crashed"] = static_cast<bool>(e.crashed[s]);
    f["crash_t_s"] = e.crash_t_s[s];
    per_seed.push_back(std::move(f));
  }
  j["per_seed"] = std::move(per_seed);
  return j;
}

io::Json hoverJson(const HoverCurve& c) {
  io::Json bins = io::Json::array();
  for (const auto& bin : c.bins) {
    bins.push_back({{"h_m", bin.centre_m()},
                    {"h_low_m", bin.h_low_m},
                    {"h_high_m", bin.h_high_m},
                    {"angle_err_deg", bin.angle_err_deg},
                    {"angle_err_std_deg", bin.angle_err_std_deg},
                    {"samples", bin.samples},
                    {"seeds_visited", bin.seeds_visited},
                    {"per_seed_deg", bin.per_seed_deg}});
  }
  return {{"torque", control::toString(c.torque)},
          {"acc", "model"},
          {"crashes", c.crashes},
          {"bins", std::move(bins)}};
}

io::Json calibrationJson(const ControllerCalibration& cal) {
  io::Json parameters = io::Json::array();
  for (const auto& p : cal.parameters) {
    parameters.push_back({{"key", p.key},
                          {"unit", p.unit},
                          {"source", p.source},
                          {"vehicle_file", p.file_value},
                          {"identified", p.identified},
                          {"std_error", p.std_error}});
  }
  io::Json ratio = io::Json::array();
  for (const auto& p : cal.thrust_ratio) {
    ratio.push_back(
        {{"h_m", p.h_m}, {"truth", p.truth}, {"identified", p.identified}, {"vehicle_file", p.file}});
  }
  io::Json flights = io::Json::array();
  for (const auto& f : cal.flights) {
    flights.push_back({{"purpose", f.purpose},
                       {"reference_height_m", f.reference_height_m},
                       {"mean_height_m", f.mean_height_m},
                       {"samples", f.samples},
                       {"guard_active_s", f.guard_active_s}});
  }
  io::Json k_T = {{"stand", cal.k_T_stand_N_per_rpm2}, {"platform", cal.k_T_platform_N_per_rpm2}};
  k_T["hover"] = cal.k_T_hover_N_per_rpm2 > 0.0 ? io::Json(cal.k_T_hover_N_per_rpm2) : io::Json(nullptr);
  return {{"parameters", std::move(parameters)},
          {"scale", {{"reading_kg", cal.scale_reading_kg}, {"std_kg", cal.scale_error_std_kg}}},
          {"k_T_N_per_rpm2", std::move(k_T)},
          {"flights", std::move(flights)},
          {"thrust_ratio", std::move(ratio)}};
}

}  // namespace

io::Json campaignJson(const CampaignResult& r) {
  io::Json j;
  j["experiments"] = io::Json::array();
  for (const auto& e : r.experiments) j["experiments"].push_back(experimentJson(e));
  j["hover"] = io::Json::array();
  for (const auto& c : r.hover) j["hover"].push_back(hoverJson(c));
  j["checks"] = io::Json::array();
  for (const auto& c : r.checks) {
    j["checks"].push_back({{"name", c.name},
                           {"criterion", c.criterion},
                           {"value", c.value},
                           {"paper", c.paper},
                           {"pass", c.pass}});
  }
  j["calibration"] = calibrationJson(r.calibration);
  if (r.neural) {
    const auto& n = *r.neural;
    j["neural"] = {{"trained", n.trained},
                   {"user_file", n.user_file},
                   {"key_hash", n.key_hash},
                   {"file", n.file.string()},
                   {"rows", n.rows},
                   {"validation_loss_N2", n.validation_loss_N2}};
  }
  j["seeds"] = r.seeds;
  j["threads"] = r.threads;
  j["flights"] = r.flights;
  j["simulated_s"] = r.simulated_s;
  j["wall_s"] = r.wall_s;
  j["calibration_s"] = r.calibration_s;
  j["neural_s"] = r.neural_s;
  j["flights_s"] = r.flights_s;
  return j;
}

}  // namespace geaware::experiments
