// SPDX-License-Identifier: BSD-3-Clause
// The robustness suite's paired comparisons, the checks, the text summary and the JSON
// document (experiments/robustness.hpp, docs/robustness.md).

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geaware/experiments/robustness.hpp"
#include "geaware/io/provenance.hpp"

namespace geaware::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The flight of `cell` with this seed, or null.
const SuiteFlight* flightOf(const SuiteCell& cell, std::uint64_t seed) {
  for (const auto& f : cell.flights) {
    if (f.seed == seed) return &f;
  }
  return nullptr;
}

}  // namespace

PairedComparison comparePaired(const SuiteCell& a, const SuiteCell& b) {
  PairedComparison c;
  double sum_a = 0.0;
  double sum_b = 0.0;
  for (const auto& fa : a.flights) {
    const SuiteFlight* fb = flightOf(b, fa.seed);
    if (fb == nullptr) continue;
    ++c.seeds;
    if (fa.struck && fb->struck) {
      ++c.both_struck;
    } else if (fa.struck) {
      ++c.only_a_struck;
    } else if (fb->struck) {
      ++c.only_b_struck;
    } else {
      ++c.both_finished;
      sum_a += fa.rmse_all_cm;
      sum_b += fb->rmse_all_cm;
    }
  }
  c.a_rmse_all_cm = c.both_finished > 0 ? sum_a / c.both_finished : kNaN;
  c.b_rmse_all_cm = c.both_finished > 0 ? sum_b / c.both_finished : kNaN;
  return c;
}

bool PairedComparison::atMost(double factor) const noexcept {
  if (only_a_struck > 0) return false;
  if (both_finished == 0) return true;
  return a_rmse_all_cm <= factor * b_rmse_all_cm;
}

namespace {

constexpr const char* kRecommended = "recommended";

/// Checks of `recommended` against one other controller over every case and height: the
/// fraction of cells where it is at most `factor` × the other.
struct Tally {
  int cells = 0;
  int at_most = 0;
  std::vector<std::string> failed;  ///< "case @ h m"
};

std::string where(const SuiteCell& c) { return fmt::format("{} @ {:.2f} m", c.case_name, c.height_m); }

std::string listed(const std::vector<std::string>& items) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) s += (i ? "; " : "") + items[i];
  return s;
}

void addShareCheck(const RobustnessResult& r, const std::string& other, const std::string& label,
                   std::vector<SuiteCheck>& out) {
  Tally all;
  Tally none;
  for (const auto& c : r.cells) {
    if (c.controller != kRecommended) continue;
    const SuiteCell* o = r.cell(c.case_name, other, c.height_m);
    if (o == nullptr) continue;
    const PairedComparison p = comparePaired(c, *o);
    ++all.cells;
    if (p.atMost(1.0)) {
      ++all.at_most;
    } else {
      all.failed.push_back(where(c));
    }
    if (c.case_name == "none") {
      ++none.cells;
      if (p.atMost(0.5)) {
        ++none.at_most;
      } else {
        none.failed.push_back(fmt::format("{} ({:.2f} vs {:.2f} cm, {} own strikes)", where(c),
                                          p.a_rmse_all_cm, p.b_rmse_all_cm, p.only_a_struck));
      }
    }
  }
  if (all.cells > 0) {
    out.push_back({fmt::format("recommended all-RMSE ≤ {}'s (paired seeds)", label),
                   "in ≥ 90 % of the cells",
                   fmt::format("{} of {} cells ({:.0f} %){}", all.at_most, all.cells,
                               100.0 * all.at_most / all.cells,
                               all.failed.empty() ? "" : "; not in: " + listed(all.failed)),
                   all.at_most >= 0.9 * all.cells});
  }
  if (none.cells > 0) {
    out.push_back({fmt::format("recommended all-RMSE ≤ ½ × {}'s in \"none\"", label),
                   "at both heights",
                   fmt::format("{} of {}{}", none.at_most, none.cells,
                               none.failed.empty() ? "" : "; not in: " + listed(none.failed)),
                   none.at_most == none.cells});
  }
}

}  // namespace

std::vector<SuiteCheck> robustnessChecks(const RobustnessResult& r) {
  std::vector<SuiteCheck> out;
  bool any = false;
  int cells = 0;
  std::vector<std::string> struck;
  for (const auto& c : r.cells) {
    if (c.controller != kRecommended) continue;
    any = true;
    ++cells;
    if (c.strikes() > 0) struck.push_back(fmt::format("{} ({} of {})", where(c), c.strikes(), c.flights.size()));
  }
  if (!any) return out;
  out.push_back({"recommended: no strike", "0 strikes in every cell",
                 fmt::format("{} of {} cells with strikes{}", struck.size(), cells,
                             struck.empty() ? "" : ": " + listed(struck)),
                 struck.empty()});
  addShareCheck(r, "indi:none", "indi:none (exp 2's configuration)", out);
  addShareCheck(r, "indi:indi", "indi:indi", out);
  // ≤ model:model_indi wherever that one finishes (at least one of its flights).
  int compared = 0;
  std::vector<std::string> worse;
  for (const auto& c : r.cells) {
    if (c.controller != kRecommended) continue;
    const SuiteCell* m = r.cell(c.case_name, "model:model_indi", c.height_m);
    if (m == nullptr || m->strikes() == static_cast<int>(m->flights.size())) continue;
    ++compared;
    const PairedComparison p = comparePaired(c, *m);
    if (!p.atMost(1.0)) {
      worse.push_back(fmt::format("{} ({:.2f} vs {:.2f} cm, {} own strikes)", where(c),
                                  p.a_rmse_all_cm, p.b_rmse_all_cm, p.only_a_struck));
    }
  }
  if (compared > 0) {
    out.push_back({"recommended all-RMSE ≤ model:model_indi's (exp 5's configuration)",
                   "in every cell where model:model_indi finishes",
                   fmt::format("{} of {} cells{}", compared - static_cast<int>(worse.size()),
                               compared, worse.empty() ? "" : "; not in: " + listed(worse)),
                   worse.empty()});
  }
  double guard = 0.0;
  bool has_guard = false;
  for (const auto& c : r.cells) {
    if (c.controller != kRecommended || c.case_name != "none") continue;
    for (const auto& f : c.flights) {
      if (!f.guard_active_s) continue;
      has_guard = true;
      guard += *f.guard_active_s;
    }
  }
  if (has_guard) {
    out.push_back({"recommended: guard never active in \"none\"", "0 s",
                   fmt::format("{:.3f} s in total", guard), guard == 0.0});
  }
  return out;
}

namespace {
const char* plural(std::size_t n) { return n == 1 ? "" : "s"; }
}  // namespace

std::string formatRobustness(const RobustnessResult& r) {
  std::string s = fmt::format(
      "Robustness suite: belief calibrated once on the unperturbed world; {} case{} × {} "
      "height{} × {} controller{} × {} seed{} = {} flights. recommended = {} + additions.\n",
      r.cases.size(), plural(r.cases.size()), r.conditions.size(), plural(r.conditions.size()),
      r.controllers.size(), plural(r.controllers.size()), r.seeds.size(), plural(r.seeds.size()),
      r.flights, r.recommended);
  s += "Each entry: mean all-RMSE of the finished flights [cm], '(k✕)' when k of them struck, "
       "'struck' when all did.\n";
  for (const auto& cond : r.conditions) {
    s += fmt::format("\n{:.2f} m / {:g} m/s ({})\n", cond.height_m(), cond.speed_mps(), cond.describe());
    s += fmt::format("  {:<22}", "case");
    for (const auto& c : r.controllers) s += fmt::format(" {:>17}", c);
    s += "\n";
    for (const auto& p : r.cases) {
      s += fmt::format("  {:<22}", p.name);
      for (const auto& c : r.controllers) {
        const SuiteCell* cell = r.cell(p.name, c, cond.height_m());
        std::string entry = "-";
        if (cell != nullptr) {
          const double rmse = cell->meanFinished(&SuiteFlight::rmse_all_cm);
          const int k = cell->strikes();
          entry = std::isnan(rmse) ? "struck"
                                   : fmt::format("{:.2f}{}", rmse, k ? fmt::format(" ({}✕)", k) : "");
        }
        s += fmt::format(" {:>17}", entry);
      }
      s += "\n";
    }
  }
  s += "\nChecks of the issue (reported as they are):\n";
  for (const auto& c : r.checks) {
    s += fmt::format("  [{}] {} — {}: {}\n", c.pass ? "pass" : "FAIL", c.name, c.criterion, c.value);
  }
  s += fmt::format(
      "\n{} flights, {:.0f} s simulated, on {} thread{}: calibration {:.1f} s, Neural-Lander "
      "{:.1f} s, flights {:.1f} s, wall {:.1f} s\n",
      r.flights, r.simulated_s, r.threads, r.threads == 1 ? "" : "s", r.calibration_s, r.neural_s,
      r.flights_s, r.wall_s);
  return s;
}

io::Json suiteCellJson(const SuiteCell& c) {
  io::Json seeds = io::Json::array();
  io::Json per_seed = io::Json::array();
  for (const auto& f : c.flights) {
    seeds.push_back(f.seed);
    io::Json one = {{"seed", f.seed},
                    {"struck", f.struck},
                    {"strike_t_s", f.struck ? f.strike_t_s : kNaN},
                    {"rmse_all_cm", f.rmse_all_cm},
                    {"rmse_xy_cm", f.rmse_xy_cm},
                    {"rmse_z_cm", f.rmse_z_cm},
                    {"max_cm", f.max_cm}};
    one["guard_active_s"] = f.guard_active_s ? io::Json(*f.guard_active_s) : io::Json(nullptr);
    per_seed.push_back(std::move(one));
  }
  const auto guard = c.guardActiveS();
  io::Json j = {{"case", c.case_name},
                {"controller", c.controller},
                {"height_m", c.height_m},
                {"speed_mps", c.speed_mps},
                {"seeds", std::move(seeds)},
                {"flights", c.flights.size()},
                {"strikes", c.strikes()},
                {"rmse_all_cm", c.meanFinished(&SuiteFlight::rmse_all_cm)},
                {"rmse_xy_cm", c.meanFinished(&SuiteFlight::rmse_xy_cm)},
                {"rmse_z_cm", c.meanFinished(&SuiteFlight::rmse_z_cm)},
                {"max_cm", c.meanFinished(&SuiteFlight::max_cm)}};
  j["guard_active_s"] = guard ? io::Json(*guard) : io::Json(nullptr);
  j["per_seed"] = std::move(per_seed);
  return j;
}

io::Json suiteChecksJson(const std::vector<SuiteCheck>& checks) {
  io::Json out = io::Json::array();
  for (const auto& c : checks) {
    out.push_back({{"name", c.name}, {"criterion", c.criterion}, {"value", c.value}, {"pass", c.pass}});
  }
  return out;
}

io::Json robustnessJson(const RobustnessResult& r) {
  io::Json doc = {{"geaware_version", io::geawareVersion()},
                  {"suite", "robustness"},
                  {"recommended", r.recommended},
                  {"seeds", r.seeds}};
  io::Json cases = io::Json::array();
  for (const auto& p : r.cases) {
    cases.push_back({{"case", p.name}, {"meaning", p.meaning()}, {"recalibrated", p.recalibrates()}});
  }
  doc["cases"] = std::move(cases);
  doc["controllers"] = r.controllers;
  io::Json cells = io::Json::array();
  for (const auto& c : r.cells) cells.push_back(suiteCellJson(c));
  doc["cells"] = std::move(cells);
  doc["checks"] = suiteChecksJson(r.checks);
  io::Json cal = io::Json::array();
  for (const auto& w : r.calibrations) {
    io::Json params = io::Json::array();
    for (const auto& p : w.calibration.parameters) {
      params.push_back({{"key", p.key}, {"source", p.source}, {"identified", p.identified}});
    }
    cal.push_back({{"world", w.world},
                   {"identified", std::move(params)},
                   {"neural_key", w.neural ? io::Json(w.neural->key_hash) : io::Json(nullptr)}});
  }
  doc["calibrations"] = std::move(cal);
  doc["timing"] = {{"threads", r.threads},      {"flights", r.flights},
                   {"simulated_s", r.simulated_s}, {"calibration_s", r.calibration_s},
                   {"neural_s", r.neural_s},     {"flights_s", r.flights_s},
                   {"wall_s", r.wall_s}};
  return doc;
}

}  // namespace geaware::experiments
