// SPDX-License-Identifier: BSD-3-Clause
// The beyond suite's report (experiments/beyond_suite.hpp): an index page with the checks and
// every cell, and a page per scenario with its geometry (terrain under the flights, the boxes'
// outlines seen from the side and from above) and the first seed of each controller.

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "geaware/experiments/beyond_suite.hpp"
#include "geaware/experiments/flight_plots.hpp"
#include "geaware/sim/obstacles.hpp"

namespace geaware::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The page file of the scenario at `index` in the sweep file: its number (from 1) and its name
/// with every byte other than A–Z a–z 0–9 . + - written '_' (distinct for distinct indices,
/// whatever the names; the same page name whichever scenarios a run picks).
std::string pageName(std::size_t index, const std::string& name) {
  std::string safe;
  for (const char ch : name) {
    const bool ok = (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') ||
                    ch == '.' || ch == '+' || ch == '-';
    safe += ok ? ch : '_';
  }
  return fmt::format("beyond-{:02}-{}.html", index + 1, safe);
}

/// Convex hull (Andrew's monotone chain) of `pts`, closed: the first point again at the end.
std::vector<std::array<double, 2>> closedHull(std::vector<std::array<double, 2>> pts) {
  std::sort(pts.begin(), pts.end());
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  if (pts.size() < 3) return pts;
  const auto cross = [](const std::array<double, 2>& o, const std::array<double, 2>& a,
                        const std::array<double, 2>& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  std::vector<std::array<double, 2>> hull(2 * pts.size());
  std::size_t k = 0;
  for (const auto& p : pts) {  // lower
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0.0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = pts.size() - 1, lower = k + 1; i-- > 0;) {  // upper
    while (k >= lower && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0.0) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k);  // the last point is the first again
  return hull;
}

/// The outline of `box` projected on the world axes `a` and `b` (0 x, 1 y, 2 z).
report::Series boxOutline(const sim::Box& box, int a, int b, const std::string& color) {
  std::vector<std::array<double, 2>> pts;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d s((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
    const Eigen::Vector3d c = box.centre_W + box.R_WO * box.half_extent_m.cwiseProduct(s);
    pts.push_back({c[a], c[b]});
  }
  report::Series out = plots::line(box.name.empty() ? "obstacle" : box.name, {}, {}, "", color);
  for (const auto& p : closedHull(std::move(pts))) {
    out.x.push_back(p[0]);
    out.y.push_back(p[1]);
  }
  return out;
}

std::string groundText(const sim::Terrain* terrain) {
  const std::optional<double> level = terrain ? terrain->flatLevel() : std::optional<double>(0.0);
  return level ? fmt::format("flat ground at z = {:g} m", *level) : std::string("the scenario's terrain");
}

/// Mean of `metric` over the cell's finished flights, "(k✕)" when k struck, "struck" when all did.
std::string cellEntry(const BeyondCell* c, double SuiteFlight::*metric) {
  if (c == nullptr) return "";
  const double v = c->suite.meanFinished(metric);
  const int k = c->suite.strikes();
  if (std::isnan(v)) return "struck";
  return k > 0 ? fmt::format("{:.2f} ({}✕)", v, k) : fmt::format("{:.2f}", v);
}

/// Touchdown and lift-off of a cell, in words.
std::string contactEntry(const BeyondCell& c) {
  double td = 0.0, bounce = 0.0, tilt = 0.0;
  int touched = 0, lifted = 0, back = 0;
  for (const auto& x : c.extras) {
    if (!x.contact) continue;
    if (std::isfinite(x.contact->touchdown_speed_mps)) {
      td = std::max(td, x.contact->touchdown_speed_mps);
      bounce = std::max(bounce, x.contact->bounce_m);
      ++touched;
    }
    lifted += std::isfinite(x.contact->liftoff_t_s) ? 1 : 0;
    back += x.contact->recontacts;
    tilt = std::max(tilt, x.contact->max_tilt_on_ground_deg);
  }
  std::string s;
  if (touched > 0) s = fmt::format("touchdown ≤ {:.3f} m/s, bounce ≤ {:.1f} mm; ", td, 1e3 * bounce);
  if (lifted > 0) s += fmt::format("lifted off {}/{}, back down {}; ", lifted, c.extras.size(), back);
  if (touched > 0 || lifted > 0) s += fmt::format("tilt on the ground ≤ {:.1f}°", tilt);
  return s;
}

report::Table cellTable(const BeyondResult& r, const std::vector<const BeyondScenario*>& scenarios) {
  report::Table t{"Cells (means over the finished flights; (k✕): k flights struck)",
                  {"scenario", "controller", "strikes", "all-RMSE [cm]", "max [cm]", "last lap [cm]",
                   "closest rim [cm]", "ground contact"},
                  {}};
  for (const BeyondScenario* scn : scenarios) {
    for (const auto& ctl : r.controllers) {
      const BeyondCell* c = r.cell(scn->sweep.name, ctl);
      if (c == nullptr) continue;
      double clearance = kNaN;
      for (const auto& x : c->extras) {
        if (x.min_obstacle_clearance_m) clearance = std::fmin(clearance, *x.min_obstacle_clearance_m);
      }
      const double lap = meanLastLapCm(*c);
      t.rows.push_back({scn->sweep.name, ctl, fmt::format("{}/{}", c->suite.strikes(), c->suite.flights.size()),
                        cellEntry(c, &SuiteFlight::rmse_all_cm), cellEntry(c, &SuiteFlight::max_cm),
                        scn->laps >= 2 && !std::isnan(lap) ? fmt::format("{:.2f}", lap) : "",
                        std::isnan(clearance) ? "" : fmt::format("{:.1f}", 100.0 * clearance),
                        contactEntry(*c)});
    }
  }
  return t;
}

report::HeatMap cellMap(const BeyondResult& r, bool strikes) {
  report::HeatMap m;
  m.title = strikes ? fmt::format("Strikes (of {} flight{} per cell)", r.seeds.size(), r.seeds.size() == 1 ? "" : "s")
                    : "All-RMSE of the finished flights [cm] (blank: all struck; colour capped at 10 cm)";
  m.x_label = "controller";
  m.y_label = "scenario";
  m.columns = r.controllers;
  m.z_label = strikes ? "strikes" : "RMSE [cm]";
  m.colorscale = strikes ? "Reds" : "Viridis";
  m.z_min = 0.0;
  m.z_max = strikes ? static_cast<double>(r.seeds.size()) : 10.0;
  m.height_px = 160 + 28 * static_cast<int>(r.scenarios.size());
  for (const auto& scn : r.scenarios) {
    m.rows.push_back(scn.sweep.name);
    std::vector<double> z;
    std::vector<std::string> text;
    for (const auto& ctl : r.controllers) {
      const BeyondCell* c = r.cell(scn.sweep.name, ctl);
      if (c == nullptr) {
        z.push_back(kNaN);
        text.emplace_back();
      } else if (strikes) {
        z.push_back(c->suite.strikes());
        text.push_back(std::to_string(c->suite.strikes()));
      } else {
        z.push_back(c->suite.meanFinished(&SuiteFlight::rmse_all_cm));
        text.push_back(cellEntry(c, &SuiteFlight::rmse_all_cm));
      }
    }
    m.z.push_back(std::move(z));
    m.text.push_back(std::move(text));
  }
  return m;
}

report::Page scenarioPage(const BeyondResult& r, const BeyondScenario& scn, const io::RunInfo& run) {
  report::Page page("geaware bench --suite beyond: " + scn.sweep.name);
  const std::size_t boxes = scn.sweep.obstacles ? scn.sweep.obstacles->boxes().size() : 0;
  page.addText(fmt::format(
      "{}: a {:.1f} s trajectory{}, over {}{}. The first seed ({}) of each controller is drawn; the "
      "table covers every seed. Terrain: the true surface under the longest of these flights.",
      scn.sweep.name, scn.sweep.trajectory->duration(),
      scn.laps > 0 ? fmt::format(" ({} lap{} of a lemniscate)", scn.laps, scn.laps == 1 ? "" : "s") : "",
      groundText(scn.sweep.terrain.get()),
      boxes > 0 ? fmt::format(", with {} box{} (outlined)", boxes, boxes == 1 ? "" : "es") : "",
      r.seeds.empty() ? 0 : r.seeds.front()));
  page.addTable(cellTable(r, {&scn}));
  std::vector<plots::Flown> flown;
  for (std::size_t i = 0; i < r.controllers.size(); ++i) {
    const auto it = r.series.find({scn.sweep.name, r.controllers[i]});
    if (it != r.series.end() && it->second.size() > 0) {
      flown.push_back({r.controllers[i], &it->second, plots::color(i)});
    }
  }
  if (flown.empty()) {
    page.addText("No flight series were collected for this page.");
    return page;
  }
  // The terrain and the reference are drawn along the first flight: the one that flew longest
  // (a struck flight ends early). Each controller keeps its colour.
  std::stable_sort(flown.begin(), flown.end(), [](const plots::Flown& a, const plots::Flown& b) {
    return a.series->size() > b.series->size();
  });
  report::Plot side = plots::sideView("Seen from the side (x–z)", flown);
  report::Plot top = plots::topView("Seen from above (x–y)", flown);
  if (scn.sweep.obstacles) {
    for (const auto& box : scn.sweep.obstacles->boxes()) {
      side.series.push_back(boxOutline(box, 0, 2, "#7f7f7f"));
      top.series.push_back(boxOutline(box, 0, 1, "#7f7f7f"));
    }
  }
  page.addPlot(std::move(side));
  page.addPlot(std::move(top));
  page.addPlot(plots::heightPlot("Height over time", flown));
  page.addPlot(plots::errorPlot("Position error over time", flown));
  page.addTable(plots::provenanceTable(run));
  return page;
}

report::Page indexPage(const BeyondResult& r, const io::RunInfo& run) {
  report::Page page("geaware bench --suite beyond");
  page.addText(fmt::format(
      "The scenarios of {} × {} controller{} × {} seed{}: {} flights ({:.0f} s simulated) on {} "
      "thread{}, wall time {:.1f} s, each the sweep's own flight (the belief calibrated once in the "
      "unperturbed world). See docs/controller.md, \"The beyond suite\".",
      r.source, r.controllers.size(), r.controllers.size() == 1 ? "" : "s", r.seeds.size(),
      r.seeds.size() == 1 ? "" : "s", r.flights, r.simulated_s, r.threads, r.threads == 1 ? "" : "s", r.wall_s));
  page.addTable(suiteChecksTable(r.checks));
  page.addHeatMap(cellMap(r, true));
  page.addHeatMap(cellMap(r, false));
  std::vector<const BeyondScenario*> all;
  for (const auto& s : r.scenarios) all.push_back(&s);
  page.addTable(cellTable(r, all));
  std::vector<std::pair<std::string, std::string>> pages;
  for (const auto& scn : r.scenarios) pages.emplace_back(scn.sweep.name, pageName(scn.index, scn.sweep.name));
  page.addLinks("A page per scenario, beside this one", std::move(pages));
  page.addTable(plots::provenanceTable(run));
  return page;
}

}  // namespace

std::filesystem::path writeBeyondReport(const BeyondResult& r, const std::filesystem::path& dir,
                                        const io::RunInfo& run, bool png) {
  if (std::filesystem::exists(dir) && !std::filesystem::is_directory(dir)) {
    throw std::runtime_error("report: " + dir.string() + " exists and is not a directory");
  }
  std::filesystem::create_directories(dir);
  for (std::size_t i = 0; i < r.scenarios.size(); ++i) {
    scenarioPage(r, r.scenarios[i], run).write(dir / pageName(r.scenarios[i].index, r.scenarios[i].sweep.name));
  }
  const auto html = dir / "beyond.html";
  indexPage(r, run).write(html);
  if (png) report::exportPagePng(html, dir / "beyond.png");
  return html;
}

}  // namespace geaware::experiments
