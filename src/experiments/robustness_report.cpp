// SPDX-License-Identifier: BSD-3-Clause
// The robustness suite's report page (experiments/robustness.hpp): the checks, then per
// height/speed a heat map of strikes and one of all-RMSE, case × controller.

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "geaware/experiments/flight_plots.hpp"
#include "geaware/experiments/robustness.hpp"

namespace geaware::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

int heatMapHeight(std::size_t rows) { return 160 + 28 * static_cast<int>(rows); }

report::HeatMap strikesMap(const RobustnessResult& r, const SuiteCondition& cond) {
  report::HeatMap m;
  m.title = fmt::format("Strikes, {:.2f} m / {:g} m/s (of {} flight{} per cell)", cond.height_m(),
                        cond.speed_mps(), r.seeds.size(), r.seeds.size() == 1 ? "" : "s");
  m.x_label = "controller";
  m.y_label = "case";
  m.columns = r.controllers;
  m.z_label = "strikes";
  m.colorscale = "Reds";
  m.z_min = 0.0;
  m.z_max = static_cast<double>(r.seeds.size());
  m.height_px = heatMapHeight(r.cases.size());
  for (const auto& p : r.cases) {
    m.rows.push_back(p.name);
    std::vector<double> z;
    std::vector<std::string> text;
    for (const auto& c : r.controllers) {
      const SuiteCell* cell = r.cell(p.name, c, cond.height_m());
      z.push_back(cell ? cell->strikes() : kNaN);
      text.push_back(cell ? std::to_string(cell->strikes()) : "");
    }
    m.z.push_back(std::move(z));
    m.text.push_back(std::move(text));
  }
  return m;
}

report::HeatMap rmseMap(const RobustnessResult& r, const SuiteCondition& cond) {
  report::HeatMap m;
  m.title = fmt::format("All-RMSE of the finished flights [cm], {:.2f} m / {:g} m/s (blank: all "
                        "struck; colour capped at 10 cm)",
                        cond.height_m(), cond.speed_mps());
  m.x_label = "controller";
  m.y_label = "case";
  m.columns = r.controllers;
  m.z_label = "RMSE [cm]";
  m.colorscale = "Viridis";
  m.z_min = 0.0;
  m.z_max = 10.0;
  m.height_px = heatMapHeight(r.cases.size());
  for (const auto& p : r.cases) {
    m.rows.push_back(p.name);
    std::vector<double> z;
    std::vector<std::string> text;
    for (const auto& c : r.controllers) {
      const SuiteCell* cell = r.cell(p.name, c, cond.height_m());
      const double v = cell ? cell->meanFinished(&SuiteFlight::rmse_all_cm) : kNaN;
      z.push_back(v);
      std::string t = std::isnan(v) ? (cell ? "struck" : "") : fmt::format("{:.2f}", v);
      if (cell && !std::isnan(v) && cell->strikes() > 0) t += fmt::format(" ({}✕)", cell->strikes());
      text.push_back(std::move(t));
    }
    m.z.push_back(std::move(z));
    m.text.push_back(std::move(text));
  }
  return m;
}

}  // namespace

report::Table suiteChecksTable(const std::vector<SuiteCheck>& checks) {
  report::Table t{"The issue's checks of `recommended`, as they are", {"check", "criterion", "measured", "result"}, {}};
  for (const auto& c : checks) t.rows.push_back({c.name, c.criterion, c.value, c.pass ? "pass" : "FAIL"});
  return t;
}

report::Page robustnessPage(const RobustnessResult& r, const io::RunInfo& run) {
  report::Page page("geaware bench --suite robustness");
  page.addText(fmt::format(
      "The belief is calibrated once on the unperturbed world (rigs, identification{}); then the "
      "world changes, one case at a time (the law families re-run the rigs and the "
      "identification in their world). {} flights ({:.0f} s simulated) on {} thread{}, wall "
      "time {:.1f} s. `recommended` stands for {} with geaware's additions. See "
      "docs/robustness.md.",
      r.calibrations.empty() || !r.calibrations.front().neural ? "" : ", Neural-Lander training",
      r.flights, r.simulated_s, r.threads, r.threads == 1 ? "" : "s", r.wall_s, r.recommended));
  page.addTable(suiteChecksTable(r.checks));
  report::Table cases{"Cases", {"case", "what changes"}, {}};
  for (const auto& p : r.cases) cases.rows.push_back({p.name, p.meaning()});
  page.addTable(std::move(cases));
  for (const auto& cond : r.conditions) {
    page.addHeading(fmt::format("{:.2f} m / {:g} m/s ({})", cond.height_m(), cond.speed_mps(), cond.describe()));
    page.addHeatMap(strikesMap(r, cond));
    page.addHeatMap(rmseMap(r, cond));
  }
  page.addTable(plots::provenanceTable(run));
  return page;
}

std::filesystem::path writeRobustnessReport(const RobustnessResult& r,
                                            const std::filesystem::path& dir,
                                            const io::RunInfo& run, bool png) {
  if (std::filesystem::exists(dir) && !std::filesystem::is_directory(dir)) {
    throw std::runtime_error("report: " + dir.string() + " exists and is not a directory");
  }
  std::filesystem::create_directories(dir);
  const auto html = dir / "robustness.html";
  robustnessPage(r, run).write(html);
  if (png) report::exportPagePng(html, dir / "robustness.png");
  return html;
}

}  // namespace geaware::experiments
