// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/campaign_report.hpp"

#include "geaware/experiments/flight_plots.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace geaware::experiments {
namespace {

using plots::line;
using plots::trajectoryPart;

/// "ours ± std [paper]" in one cell.
std::string withPaper(const MeanStd& m, double paper) {
  if (!std::isfinite(paper)) return fmt::format("{:.2f} ± {:.2f}", m.mean, m.std);
  return fmt::format("{:.2f} ± {:.2f} [{:.2f}]", m.mean, m.std, paper);
}

std::string label(const TableOneExperiment& e) {
  return fmt::format("exp {} {}", e.number, control::configurationName(e.controller()));
}

void addTables(report::Page& page, const CampaignResult& r) {
  if (!r.experiments.empty()) {
    report::Table t{fmt::format("Table I: ours, mean ± std over {} seed{}, and in brackets the "
                                "paper's real flight; cm",
                                r.seeds, r.seeds == 1 ? "" : "s"),
                    {"exp", "acc:torque", "h [m]", "v [m/s]", "RMSE XOY", "RMSE Z", "RMSE all",
                     "max ‖E_P‖", "σ‖E_P‖", "crashes"},
                    {}};
    for (const auto& e : r.experiments) {
      const auto& x = e.experiment;
      t.rows.push_back({std::to_string(x.number), control::configurationName(x.controller()),
                        fmt::format("{:.2f}", x.height_m), fmt::format("{:g}", x.speed_mps),
                        withPaper(e.rmse_xy_cm, x.paper.rmse_xy_cm),
                        withPaper(e.rmse_z_cm, x.paper.rmse_z_cm),
                        withPaper(e.rmse_all_cm, x.paper.rmse_all_cm),
                        withPaper(e.max_cm, x.paper.max_cm), withPaper(e.std_cm, x.paper.std_cm),
                        fmt::format("{} of {}", e.crashes, e.seeds.size())});
    }
    page.addTable(std::move(t));
  }
  report::Table checks{"Headline ratios and acceptance checks (issue 6)",
                       {"check", "ours", "criterion", "paper", "result"},
                       {}};
  for (const auto& c : r.checks) {
    checks.rows.push_back({c.name, fmt::format("{:.3f}", c.value), c.criterion, c.paper,
                           c.pass ? "pass" : "FAIL"});
  }
  page.addTable(std::move(checks));
  report::Table cal{"Calibration: the controller's parameters and where each was measured "
                    "(rigs, scale, hover and drag flights; CAD)",
                    {"parameter", "vehicle file", "measured", "std. error", "source"},
                    {}};
  for (const auto& p : r.calibration.parameters) {
    cal.rows.push_back({p.key + " [" + p.unit + "]", fmt::format("{:.6g}", p.file_value),
                        fmt::format("{:.6g}", p.identified), fmt::format("{:.2g}", p.std_error),
                        p.source});
  }
  page.addTable(std::move(cal));
}

void addCalibrationPlots(report::Page& page, const CampaignResult& r) {
  const auto& c = r.calibration;
  report::Plot fg{"Additional thrust F_G(h): truth, identified, vehicle file", "h [m]", "F_G [-]", {}};
  std::vector<double> h, truth, ident, file;
  for (const auto& p : c.thrust_ratio) {
    h.push_back(p.h_m);
    truth.push_back(p.truth);
    ident.push_back(p.identified);
    file.push_back(p.file);
  }
  fg.series = {line("truth (noise-free level board)", h, truth),
               line("identified g2/(h² + g1)", h, ident, "dash"),
               line("vehicle file (paper's g1, g2)", h, file, "dot")};
  page.addPlot(std::move(fg));
  report::Plot tq{fmt::format("Leveling torque at {:g}° tilt and {:g} rpm", c.torque_tilt_deg,
                              c.torque_rpm),
                  "h [m]", "τ_y [N·m]", {}};
  h.clear();
  truth.clear();
  ident.clear();
  file.clear();
  for (const auto& p : c.leveling_torque) {
    h.push_back(p.h_m);
    truth.push_back(p.truth);
    ident.push_back(p.identified);
    file.push_back(p.file);
  }
  tq.series = {line("truth", h, truth), line("identified −M_G(h)·T·sin δ", h, ident, "dash"),
               line("vehicle file", h, file, "dot")};
  page.addPlot(std::move(tq));
}

/// Each experiment keeps its colour on every plot of the page.
plots::Flown flownOf(const CampaignResult& r, int number) {
  return {label(r.experiment(number)->experiment), &r.series.at(number),
          plots::color(static_cast<std::size_t>(number - 1))};
}

void addTrajectoryPlots(report::Page& page, const CampaignResult& r) {
  const std::vector<std::pair<std::string, std::vector<int>>> groups = {
      {"0.12 m, 1 m/s (exps 1–5)", {1, 2, 3, 4, 5}},
      {"0.18 m, 3 m/s (exps 6–7)", {6, 7}},
      {"1.75 m, 5 m/s (exp 8)", {8}}};
  for (const auto& [title, numbers] : groups) {
    std::vector<plots::Flown> flown;
    for (int n : numbers) {
      if (r.experiment(n) && r.series.count(n)) flown.push_back(flownOf(r, n));
    }
    if (flown.empty()) continue;
    page.addPlot(plots::topView("Trajectories from above, " + title, flown));
    page.addPlot(plots::sideView("Trajectories from the side, " + title, flown));
    page.addPlot(plots::errorPlot("Position error ‖E_P‖ over time, " + title, flown));
  }
}

void addHoverPlots(report::Page& page, const CampaignResult& r) {
  if (r.hover.empty()) return;
  report::Plot p{fmt::format("Hover descent: angle error E against height (mean over {} seeds; "
                             "acceleration side: recommended's)",
                             r.seeds),
                 "true rotor-plane height h [m]", "E [deg]", {}};
  for (std::size_t k = 0; k < r.hover.size(); ++k) {
    const auto& c = r.hover[k];
    std::vector<double> h, e;
    for (const auto& b : c.bins) {
      h.push_back(b.centre_m());
      e.push_back(b.angle_err_deg);
    }
    report::Series s =
        line(std::string("torque ") + control::toString(c.torque), h, e, "", plots::color(k));
    s.mode = "lines+markers";
    p.series.push_back(std::move(s));
  }
  page.addPlot(std::move(p));
  if (!r.hover_series.empty()) {
    report::Plot raw{"Hover descent, first seed: angle error over time", "t [s]", "E [deg]", {}};
    for (std::size_t k = 0; k < r.hover_series.size(); ++k) {
      const auto& hs = r.hover_series[k];
      raw.series.push_back(line(std::string("torque ") + control::toString(hs.torque),
                                trajectoryPart(hs.series, hs.series.t_s),
                                trajectoryPart(hs.series, hs.series.att_err_deg), "",
                                plots::color(k)));
    }
    page.addPlot(std::move(raw));
  }
}

void addRotorPlots(report::Page& page, const CampaignResult& r) {
  // The paper's flight figure is exp 7; fall back to whichever experiment was flown.
  int pick = 0;
  for (int n : {7, 5, 8, 6, 4, 3, 2, 1}) {
    if (r.series.count(n)) {
      pick = n;
      break;
    }
  }
  if (pick == 0) return;
  const FlightSeries& s = r.series.at(pick);
  const std::string name = label(r.experiment(pick)->experiment);
  page.addPlot(plots::rotorPlot("Rotor speeds (truth), " + name + ", first seed", s));
  page.addPlot(plots::torquePlot("Body torques: command τ_des and rotor estimate τ̂_B, " + name, s));
}

}  // namespace

report::Page campaignPage(const CampaignResult& r, const io::RunInfo& run) {
  report::Page page("geaware bench: the paper's Table I and hover experiment in simulation");
  page.addText(fmt::format(
      "{} flights ({:.0f} s simulated) on {} thread{}, wall time {:.1f} s. Every controller runs on "
      "the parameters identified from the virtual rigs; the truth is the simulator's per-rotor "
      "aerodynamics. The paper's numbers are real flights. See docs/results.md.",
      r.flights, r.simulated_s, r.threads, r.threads == 1 ? "" : "s", r.wall_s));
  addTables(page, r);
  page.addTable(plots::provenanceTable(run));
  page.addHeading("Calibration");
  addCalibrationPlots(page, r);
  if (!r.series.empty()) {
    page.addHeading("Tracking (first seed of each experiment)");
    addTrajectoryPlots(page, r);
  }
  if (!r.hover.empty()) {
    page.addHeading("Hover experiment");
    addHoverPlots(page, r);
  }
  if (!r.series.empty()) {
    page.addHeading("Rotor speeds and torques");
    addRotorPlots(page, r);
  }
  return page;
}

std::filesystem::path writeCampaignReport(const CampaignResult& r, const std::filesystem::path& dir,
                                          const io::RunInfo& run, bool png) {
  if (std::filesystem::exists(dir) && !std::filesystem::is_directory(dir)) {
    throw std::runtime_error("report: " + dir.string() + " exists and is not a directory");
  }
  std::filesystem::create_directories(dir);
  const auto html = dir / "bench.html";
  campaignPage(r, run).write(html);
  if (png) report::exportPagePng(html, dir / "bench.png");
  return html;
}

}  // namespace geaware::experiments
