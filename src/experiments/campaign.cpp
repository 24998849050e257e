#include "geaware/experiments/campaign.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "geaware/experiments/flight_pool.hpp"
#include "geaware/io/json.hpp"
#include "geaware/traj/hover_descent.hpp"
#include "geaware/traj/lemniscate.hpp"

namespace geaware::experiments {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string comboName(control::AccelerationCompensation a, control::TorqueCompensation t) {
  return std::string(control::toString(a)) + ":" + control::toString(t);
}

void checkOptions(const CampaignOptions& o) {
  if (o.seeds < 1) throw std::invalid_argument("campaign: seeds must be at least 1");
  std::set<int> seen;
  for (int e : o.experiments) {
    (void)tableOneExperiment(e);  // throws std::out_of_range for an unknown number
    if (!seen.insert(e).second) {
      throw std::invalid_argument(fmt::format("campaign: experiment {} is listed twice", e));
    }
  }
  if (o.experiments.empty() && !o.hover) {
    throw std::invalid_argument("campaign: nothing to fly (no experiment and no hover)");
  }
}

}  // namespace

sim::MismatchSpec defaultTruthMismatch() {
  sim::MismatchSpec m;
  m.mass_rel = 0.01;
  m.inertia_rel = 0.10;
  m.cog_offset_m = 0.002;
  m.cog_offset_z_m = 0.005;
  m.thrust_spread_rel = 0.02;
  return m;
}

const ExperimentSummary* CampaignResult::experiment(int number) const noexcept {
  for (const auto& e : experiments) {
    if (e.experiment.number == number) return &e;
  }
  return nullptr;
}

const HoverCurve* CampaignResult::hoverCurve(control::TorqueCompensation t) const noexcept {
  for (const auto& c : hover) {
    if (c.torque == t) return &c;
  }
  return nullptr;
}

CampaignResult runCampaign(const CampaignOptions& o) {
  checkOptions(o);
  const auto t_start = Clock::now();
  auto say = [&](const std::string& m) {
    if (o.progress) o.progress(m);
  };
  CampaignResult r;
  r.seeds = o.seeds;
  r.threads = resolveThreads(o.jobs);

  // 1. Calibration on the truth.
  const sim::TruthParams truth = sim::fromNominal(o.vehicle);
  say("calibration: virtual platform (level, tilted, rpm differences) and rotor stand on the truth");
  auto t0 = Clock::now();
  r.calibration = calibrateController(o.vehicle, truth, o.calibration);
  r.calibration_s = since(t0);
  say(fmt::format("calibration: {} platform + {} stand rows identified in {:.2f} s",
                  r.calibration.platform_rows, r.calibration.stand_rows, r.calibration_s));

  // The scenario every flight starts from: the identified controller vehicle, the truth.
  FlightScenario base;
  base.vehicle = r.calibration.vehicle;
  base.truth = truth;
  base.mismatch = o.mismatch;
  base.disturbances.turbulence = o.turbulence;
  base.start_hover_s = o.start_hover_s;

  // 2. Neural-Lander, when experiment 3 is flown.
  const bool neural = std::find(o.experiments.begin(), o.experiments.end(), 3) != o.experiments.end();
  if (neural) {
    t0 = Clock::now();
    r.neural = prepareNeuralBaseline(base, o.neural, o.cache_dir, o.jobs, o.progress);
    r.neural_s = since(t0);
  }

  // 3. The flights: every experiment × seed, then every hover curve × seed.
  std::vector<std::uint64_t> seeds;
  for (int s = 0; s < o.seeds; ++s) seeds.push_back(o.first_seed + static_cast<std::uint64_t>(s));
  std::vector<FlightJob> jobs;
  std::vector<std::unique_ptr<SeriesCollector>> collectors;  // index: job, null if none
  for (int number : o.experiments) {
    const TableOneExperiment& e = tableOneExperiment(number);
    const auto trajectory = std::make_shared<traj::Lemniscate>(lemniscateFor(e));
    for (std::size_t s = 0; s < seeds.size(); ++s) {
      FlightScenario f = base;
      f.trajectory = trajectory;
      f.controller.acceleration = e.acceleration;
      f.controller.torque = e.torque;
      if (e.acceleration == control::AccelerationCompensation::kNeural) f.residual = r.neural->network;
      f.seed = seeds[s];
      collectors.push_back(o.collect_series && s == 0
                               ? std::make_unique<SeriesCollector>(expectedTicks(f), 4)
                               : nullptr);
      jobs.push_back({std::move(f), collectors.back().get(),
                      fmt::format("exp {} ({}) seed {}", number,
                                  comboName(e.acceleration, e.torque), seeds[s])});
    }
  }
  if (o.hover) {
    const auto trajectory = std::make_shared<traj::HoverDescent>(hoverDescentFor(o.hover_settings));
    for (const auto torque : o.hover_settings.torques) {
      for (std::size_t s = 0; s < seeds.size(); ++s) {
        FlightScenario f = base;
        f.trajectory = trajectory;
        f.controller.acceleration = o.hover_settings.acceleration;
        f.controller.torque = torque;
        f.hover_bins = hoverBinning(o.hover_settings);
        f.seed = seeds[s];
        collectors.push_back(o.collect_series && s == 0
                                 ? std::make_unique<SeriesCollector>(expectedTicks(f), 4)
                                 : nullptr);
        jobs.push_back({std::move(f), collectors.back().get(),
                        fmt::format("hover ({}) seed {}",
                                    comboName(o.hover_settings.acceleration, torque), seeds[s])});
      }
    }
  }
  say(fmt::format("flights: {} on {} thread{}", jobs.size(), r.threads, r.threads == 1 ? "" : "s"));
  t0 = Clock::now();
  const auto results = runFlights(
      jobs, o.jobs,
      [&](std::size_t done, std::size_t total, const FlightJob& job, const FlightResult& fr) {
        say(fmt::format("[{}/{}] {}: RMSE all {:.2f} cm{}", done, total, job.label,
                        fr.tracking.rmse_all_m * 100.0,
                        fr.crash ? " — CRASH: " + fr.crash_description : std::string()));
      });
  r.flights_s = since(t0);
  r.flights = results.size();
  for (const auto& fr : results) r.simulated_s += fr.simulated_s;

  // 4. Summaries, in the order the jobs were built.
  std::size_t k = 0;
  for (int number : o.experiments) {
    std::vector<FlightResult> mine(results.begin() + static_cast<long>(k),
                                   results.begin() + static_cast<long>(k + seeds.size()));
    if (collectors[k]) r.series[number] = collectors[k]->take();
    r.experiments.push_back(summarise(tableOneExperiment(number), seeds, mine));
    k += seeds.size();
  }
  if (o.hover) {
    for (const auto torque : o.hover_settings.torques) {
      std::vector<FlightResult> mine(results.begin() + static_cast<long>(k),
                                     results.begin() + static_cast<long>(k + seeds.size()));
      if (collectors[k]) r.hover_series.push_back({torque, collectors[k]->take()});
      r.hover.push_back(summariseHover(torque, seeds, mine));
      k += seeds.size();
    }
  }
  r.checks = acceptanceChecks(r);
  r.wall_s = since(t_start);
  return r;
}

std::vector<AcceptanceCheck> acceptanceChecks(const CampaignResult& r) {
  std::vector<AcceptanceCheck> c;
  const auto* e1 = r.experiment(1);
  const auto* e5 = r.experiment(5);
  const auto* e6 = r.experiment(6);
  const auto* e7 = r.experiment(7);
  if (e1 && e5) {
    const double v = e5->rmse_all_cm.mean / e1->rmse_all_cm.mean;
    c.push_back({"exp 5 / exp 1, RMSE all", "≤ 0.45", v, fmt::format("{:.3f}", 4.45 / 10.85),
                 v <= 0.45});
  }
  if (e6 && e7) {
    const double v = e7->rmse_all_cm.mean / e6->rmse_all_cm.mean;
    c.push_back({"exp 7 / exp 6, RMSE all", "≤ 0.55", v, fmt::format("{:.3f}", 6.97 / 12.74),
                 v <= 0.55});
  }
  const auto* e4 = r.experiment(4);
  if (e4) {
    double best_other = kNaN;
    std::string which;
    for (int n : {1, 2, 3}) {
      const auto* e = r.experiment(n);
      if (!e) continue;
      if (!(e->rmse_z_cm.mean >= best_other)) {
        best_other = e->rmse_z_cm.mean;
        which = std::to_string(n);
      }
    }
    if (!which.empty()) {
      const double v = e4->rmse_z_cm.mean / best_other;
      c.push_back({"RMSE Z: exp 4 / lowest of exps 1–3 (exp " + which + ")", "< 1", v,
                   fmt::format("{:.3f}", 1.94 / 4.94), v < 1.0});
    }
  }
  if (e5) {
    for (const bool xy : {true, false}) {
      double best_other = kNaN;
      std::string which;
      for (int n : {1, 2, 3, 4}) {
        const auto* e = r.experiment(n);
        if (!e) continue;
        const double m = xy ? e->rmse_xy_cm.mean : e->rmse_all_cm.mean;
        if (!(m >= best_other)) {
          best_other = m;
          which = std::to_string(n);
        }
      }
      if (which.empty()) continue;
      const double v = (xy ? e5->rmse_xy_cm.mean : e5->rmse_all_cm.mean) / best_other;
      c.push_back({fmt::format("RMSE {}: exp 5 / lowest of exps 1–4 (exp {})", xy ? "XOY" : "all",
                               which),
                   "< 1", v, fmt::format("{:.3f}", xy ? 4.35 / 5.51 : 4.45 / 7.38), v < 1.0});
    }
  }
  if (const auto* none = r.hoverCurve(control::TorqueCompensation::kNone)) {
    const double h = peakHeight(*none);
    c.push_back({"hover, no torque compensation: height of the peak angle error [m]",
                 "in [0.15, 0.30]", h, "≈ 0.2", h >= 0.15 && h <= 0.30});
  }
  if (const auto* mi = r.hoverCurve(control::TorqueCompensation::kModelIndi)) {
    const double v = bandMean(*mi, 0.1, 0.3) / bandMean(*mi, 1.0, 1.5);
    c.push_back({"hover, model + INDI: E(0.1–0.3 m) / E(1–1.5 m)", "≤ 1.25", v, "≈ 1",
                 v <= 1.25});
  }
  int crashes = 0;
  for (const auto& e : r.experiments) crashes += e.crashes;
  for (const auto& h : r.hover) crashes += h.crashes;
  c.push_back({"crashes", "= 0", static_cast<double>(crashes), "0", crashes == 0});
  return c;
}

// ------------------------------------------------------------------------------------ text

namespace {

std::string cell(const MeanStd& m, double paper) {
  return fmt::format("{:6.2f} ±{:5.2f} ({:5.2f})", m.mean, m.std, paper);
}

}  // namespace

std::string formatCampaign(const CampaignResult& r) {
  std::string s;
  const auto& cal = r.calibration;
  s += fmt::format("Calibration on the virtual rigs (truth: the vehicle file's nominal truth): "
                   "{} platform rows, {} stand rows, {:.2f} s\n",
                   cal.platform_rows, cal.stand_rows, r.calibration_s);
  s += fmt::format("  {:<42} {:>14} {:>14} {:>10}  {}\n", "parameter", "vehicle file", "identified",
                   "std. err.", "rig");
  for (const auto& p : cal.parameters) {
    s += fmt::format("  {:<42} {:>14.6g} {:>14.6g} {:>10.2g}  {}\n", p.key, p.file_value,
                     p.identified, p.std_error, p.source);
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

  if (r.neural) {
    const auto& n = *r.neural;
    if (n.trained) {
      s += fmt::format("\nNeural-Lander: trained on {} rows, validation MSE {:.4f} N² per component "
                       "({:.1f} s){}\n",
                       n.rows, n.validation_loss_N2, r.neural_s,
                       n.file.empty() ? "" : ", cached as " + n.file.string());
    } else {
      s += fmt::format("\nNeural-Lander: loaded from the cache, {} ({:.2f} s)\n", n.file.string(),
                       r.neural_s);
    }
  }

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
      s += fmt::format("{:>3} {:<7} {:<11} {:>5.2f} {:>4g} | {} | {} | {} | {} | {} | {}\n", x.number,
                       control::toString(x.acceleration), control::toString(x.torque), x.height_m,
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
  }

  if (!r.hover.empty()) {
    s += fmt::format("\nHover descent ({}:…): angle error E between desired and true attitude by "
                     "true rotor-plane height, deg (mean over {} seed{})\n",
                     "model", r.seeds, r.seeds == 1 ? "" : "s");
    s += "  (peaks among the bins every seed visited)\n";
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

  s += "\nHeadline ratios and acceptance checks (issue 6):\n";
  for (const auto& c : r.checks) {
    s += fmt::format("  [{}] {}: {:.3f} (criterion {}; paper {})\n", c.pass ? "pass" : "FAIL",
                     c.name, c.value, c.criterion, c.paper);
  }
  const auto* e1 = r.experiment(1);
  const auto* e5 = r.experiment(5);
  const auto* e6 = r.experiment(6);
  const auto* e7 = r.experiment(7);
  if (e1 && e5) {
    s += fmt::format("  reduction of RMSE all, exp 5 vs exp 1: {:.1f} % (paper {:.1f} %)\n",
                     100.0 * (1.0 - e5->rmse_all_cm.mean / e1->rmse_all_cm.mean),
                     100.0 * (1.0 - 4.45 / 10.85));
  }
  if (e6 && e7) {
    s += fmt::format("  reduction of RMSE all, exp 7 vs exp 6: {:.1f} % (paper {:.1f} %)\n",
                     100.0 * (1.0 - e7->rmse_all_cm.mean / e6->rmse_all_cm.mean),
                     100.0 * (1.0 - 6.97 / 12.74));
  }
  s += fmt::format("\n{} flights, {:.0f} s simulated, on {} thread{}; wall time {:.1f} s "
                   "(calibration {:.1f} s, Neural-Lander {:.1f} s, flights {:.1f} s)\n",
                   r.flights, r.simulated_s, r.threads, r.threads == 1 ? "" : "s", r.wall_s,
                   r.calibration_s, r.neural_s, r.flights_s);
  return s;
}

// ------------------------------------------------------------------------------------ JSON

namespace {

std::string jnum(double v) { return std::isfinite(v) ? fmt::format("{}", v) : "null"; }
std::string jstr(const std::string& s) { return io::jsonString(s); }

std::string metricsJson(const TableMetrics& m) {
  return fmt::format("\"rmse_xy_cm\":{},\"rmse_z_cm\":{},\"rmse_all_cm\":{},\"max_cm\":{},\"std_cm\":{}",
                     jnum(m.rmse_xy_cm), jnum(m.rmse_z_cm), jnum(m.rmse_all_cm), jnum(m.max_cm),
                     jnum(m.std_cm));
}

}  // namespace

std::string campaignJson(const CampaignResult& r) {
  std::string j = "{\"experiments\":[";
  for (std::size_t i = 0; i < r.experiments.size(); ++i) {
    const auto& e = r.experiments[i];
    const auto& x = e.experiment;
    const TableMetrics mean{e.rmse_xy_cm.mean, e.rmse_z_cm.mean, e.rmse_all_cm.mean, e.max_cm.mean,
                            e.std_cm.mean};
    const TableMetrics sd{e.rmse_xy_cm.std, e.rmse_z_cm.std, e.rmse_all_cm.std, e.max_cm.std,
                          e.std_cm.std};
    j += fmt::format(
        "{}{{\"exp\":{},\"acc\":{},\"torque\":{},\"height_m\":{},\"speed_mps\":{},"
        "\"half_extent_x_m\":{},\"half_extent_y_m\":{},{},\"crashes\":{},\"seeds\":{},"
        "\"std_over_seeds\":{{{}}},\"paper\":{{{}}},\"per_seed\":[",
        i ? "," : "", x.number, jstr(control::toString(x.acceleration)),
        jstr(control::toString(x.torque)), jnum(x.height_m), jnum(x.speed_mps),
        jnum(x.half_extent_x_m), jnum(x.half_extent_y_m), metricsJson(mean), e.crashes,
        e.seeds.size(), metricsJson(sd), metricsJson(x.paper));
    for (std::size_t s = 0; s < e.per_seed.size(); ++s) {
      j += fmt::format("{}{{\"seed\":{},{},\"crashed\":{},\"crash_t_s\":{}}}", s ? "," : "",
                       e.seeds[s], metricsJson(e.per_seed[s]), e.crashed[s] ? "true" : "false",
                       jnum(e.crash_t_s[s]));
    }
    j += "]}";
  }
  j += "],\"hover\":[";
  for (std::size_t i = 0; i < r.hover.size(); ++i) {
    const auto& c = r.hover[i];
    j += fmt::format("{}{{\"torque\":{},\"acc\":\"model\",\"crashes\":{},\"bins\":[", i ? "," : "",
                     jstr(control::toString(c.torque)), c.crashes);
    for (std::size_t b = 0; b < c.bins.size(); ++b) {
      const auto& bin = c.bins[b];
      j += fmt::format("{}{{\"h_m\":{},\"h_low_m\":{},\"h_high_m\":{},\"angle_err_deg\":{},"
                       "\"angle_err_std_deg\":{},\"samples\":{},\"seeds_visited\":{},\"per_seed_deg\":[",
                       b ? "," : "", jnum(bin.centre_m()), jnum(bin.h_low_m), jnum(bin.h_high_m),
                       jnum(bin.angle_err_deg), jnum(bin.angle_err_std_deg), bin.samples,
                       bin.seeds_visited);
      for (std::size_t s = 0; s < bin.per_seed_deg.size(); ++s) {
        j += (s ? "," : "") + jnum(bin.per_seed_deg[s]);
      }
      j += "]}";
    }
    j += "]}";
  }
  j += "],\"checks\":[";
  for (std::size_t i = 0; i < r.checks.size(); ++i) {
    const auto& c = r.checks[i];
    j += fmt::format("{}{{\"name\":{},\"criterion\":{},\"value\":{},\"paper\":{},\"pass\":{}}}",
                     i ? "," : "", jstr(c.name), jstr(c.criterion), jnum(c.value), jstr(c.paper),
                     c.pass ? "true" : "false");
  }
  j += "],\"calibration\":{\"parameters\":[";
  for (std::size_t i = 0; i < r.calibration.parameters.size(); ++i) {
    const auto& p = r.calibration.parameters[i];
    j += fmt::format("{}{{\"key\":{},\"unit\":{},\"source\":{},\"vehicle_file\":{},"
                     "\"identified\":{},\"std_error\":{}}}",
                     i ? "," : "", jstr(p.key), jstr(p.unit), jstr(p.source), jnum(p.file_value),
                     jnum(p.identified), jnum(p.std_error));
  }
  j += "],\"thrust_ratio\":[";
  for (std::size_t i = 0; i < r.calibration.thrust_ratio.size(); ++i) {
    const auto& p = r.calibration.thrust_ratio[i];
    j += fmt::format("{}{{\"h_m\":{},\"truth\":{},\"identified\":{},\"vehicle_file\":{}}}",
                     i ? "," : "", jnum(p.h_m), jnum(p.truth), jnum(p.identified), jnum(p.file));
  }
  j += "]}";
  if (r.neural) {
    const auto& n = *r.neural;
    j += fmt::format(",\"neural\":{{\"trained\":{},\"key_hash\":{},\"file\":{},\"rows\":{},"
                     "\"validation_loss_N2\":{}}}",
                     n.trained ? "true" : "false", jstr(n.key_hash), jstr(n.file.string()), n.rows,
                     jnum(n.validation_loss_N2));
  }
  j += fmt::format(",\"seeds\":{},\"threads\":{},\"flights\":{},\"simulated_s\":{},\"wall_s\":{},"
                   "\"calibration_s\":{},\"neural_s\":{},\"flights_s\":{}}}\n",
                   r.seeds, r.threads, r.flights, jnum(r.simulated_s), jnum(r.wall_s),
                   jnum(r.calibration_s), jnum(r.neural_s), jnum(r.flights_s));
  return j;
}

}  // namespace geaware::experiments
