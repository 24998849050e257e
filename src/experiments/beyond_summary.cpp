// SPDX-License-Identifier: BSD-3-Clause
// The beyond suite's text summary and JSON (experiments/beyond_suite.hpp).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "geaware/experiments/beyond_suite.hpp"
#include "geaware/experiments/flight_summary.hpp"
#include "geaware/io/provenance.hpp"

namespace geaware::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const char* kindName(BeyondKind k) {
  switch (k) {
    case BeyondKind::kLanding: return "landing";
    case BeyondKind::kTakeOff: return "take-off";
    case BeyondKind::kFlight: break;
  }
  return "flight";
}

const char* plural(std::size_t n) { return n == 1 ? "" : "s"; }

std::string span(double lo, double hi, const char* unit) {
  if (!std::isfinite(lo)) return "-";
  return lo == hi ? fmt::format("{:.3f} {}", lo, unit) : fmt::format("{:.3f}–{:.3f} {}", lo, hi, unit);
}

/// What a cell adds to its line: touchdown, lift-off, clearance, last lap.
std::string extras(const BeyondScenario& scn, const BeyondCell& c) {
  std::string s;
  if (scn.kind == BeyondKind::kLanding) {
    double lo = kNaN, hi = kNaN, bounce = 0.0;
    int landed = 0;
    for (const auto& f : c.flights) {
      if (!f.contact) continue;
      landed += f.contact->landed ? 1 : 0;
      const double v = f.contact->touchdown_speed_mps;
      if (!std::isfinite(v)) continue;
      lo = std::isfinite(lo) ? std::min(lo, v) : v;
      hi = std::isfinite(hi) ? std::max(hi, v) : v;
      bounce = std::max(bounce, f.contact->bounce_m);
    }
    s += fmt::format("  touchdown {}, bounce ≤ {:.1f} mm, landed {}/{}", span(lo, hi, "m/s"), 1e3 * bounce,
                     landed, c.flights.size());
  }
  if (scn.kind == BeyondKind::kTakeOff) {
    int lifted = 0, back = 0;
    double tilt = 0.0;
    for (const auto& f : c.flights) {
      if (!f.contact) continue;
      lifted += std::isfinite(f.contact->liftoff_t_s) ? 1 : 0;
      back += f.contact->recontacts;
      tilt = std::max(tilt, f.contact->max_tilt_on_ground_deg);
    }
    s += fmt::format("  lifted off {}/{}, back down {}, tilt ≤ {:.1f}°", lifted, c.flights.size(), back, tilt);
  }
  double clearance = kNaN;
  for (const auto& f : c.flights) {
    if (f.min_obstacle_clearance_m) {
      clearance = std::isfinite(clearance) ? std::min(clearance, *f.min_obstacle_clearance_m)
                                           : *f.min_obstacle_clearance_m;
    }
  }
  if (std::isfinite(clearance)) s += fmt::format("  closest rim {:.1f} cm", 100.0 * clearance);
  if (scn.laps >= 2) {
    double sum = 0.0;
    int n = 0;
    for (const auto& f : c.flights) {
      if (f.suite.struck) continue;
      sum += f.last_lap_rmse_cm;
      ++n;
    }
    s += n == 0 ? "  last lap -" : fmt::format("  last lap {:.2f} cm", sum / n);
  }
  return s;
}

}  // namespace

std::string formatBeyond(const BeyondResult& r) {
  std::string s = fmt::format(
      "Beyond suite ({}): {} scenario{} × {} controller{} × {} seed{} = {} flights, as the sweep "
      "flies them (the belief calibrated once in the unperturbed world).\n"
      "Each line: strikes, the mean all-RMSE and max of the finished flights [cm].\n",
      r.source, r.scenarios.size(), plural(r.scenarios.size()), r.controllers.size(),
      plural(r.controllers.size()), r.seeds.size(), plural(r.seeds.size()), r.flights);
  std::size_t width = 0;
  for (const auto& c : r.controllers) width = std::max(width, c.size());
  for (const auto& scn : r.scenarios) {
    s += fmt::format("\n{} ({}, {:.1f} s)\n", scn.sweep.name, kindName(scn.kind), scn.sweep.trajectory->duration());
    for (const auto& ctl : r.controllers) {
      const BeyondCell* c = r.cell(scn.sweep.name, ctl);
      if (c == nullptr) continue;
      const double rmse = c->meanFinished(&SuiteFlight::rmse_all_cm);
      const double max = c->meanFinished(&SuiteFlight::max_cm);
      s += fmt::format("  {:<{}}  strikes {}/{}  all-RMSE {}  max {}{}\n", ctl, width, c->strikes(),
                       c->flights.size(), std::isnan(rmse) ? "     -" : fmt::format("{:6.2f}", rmse),
                       std::isnan(max) ? "     -" : fmt::format("{:6.2f}", max), extras(scn, *c));
    }
  }
  s += "\nChecks of the issue (reported as they are):\n";
  for (const auto& c : r.checks) {
    s += fmt::format("  [{}] {} — {}: {}\n", c.pass ? "pass" : "FAIL", c.name, c.criterion, c.value);
  }
  s += fmt::format("\n{} flights, {:.0f} s simulated, on {} thread{}: calibration {:.1f} s, flights {:.1f} s, "
                   "wall {:.1f} s\n",
                   r.flights, r.simulated_s, r.threads, plural(static_cast<std::size_t>(r.threads)),
                   r.calibration_s, r.flights_s, r.wall_s);
  return s;
}

io::Json beyondJson(const BeyondResult& r) {
  io::Json doc = {{"geaware_version", io::geawareVersion()},
                  {"suite", "beyond"},
                  {"sweep", r.source},
                  {"seeds", r.seeds},
                  {"controllers", r.controllers}};
  io::Json scenarios = io::Json::array();
  for (const auto& scn : r.scenarios) {
    scenarios.push_back({{"case", scn.sweep.name},
                         {"kind", kindName(scn.kind)},
                         {"duration_s", scn.sweep.trajectory->duration()},
                         {"laps", scn.laps},
                         {"terrain", scn.sweep.terrain != nullptr},
                         {"obstacles", scn.sweep.obstacles ? scn.sweep.obstacles->boxes().size() : std::size_t{0}}});
  }
  doc["cases"] = std::move(scenarios);
  io::Json cells = io::Json::array();
  for (const auto& scn : r.scenarios) {
    for (const auto& ctl : r.controllers) {
      const BeyondCell* c = r.cell(scn.sweep.name, ctl);
      if (c == nullptr) continue;
      io::Json seeds = io::Json::array();
      io::Json per_seed = io::Json::array();
      double td_sum = 0.0, bounce_sum = 0.0;
      int touched = 0;
      for (const auto& f : c->flights) {
        seeds.push_back(f.suite.seed);
        io::Json one = {{"seed", f.suite.seed},
                        {"struck", f.suite.struck},
                        {"strike_t_s", f.suite.struck ? f.suite.strike_t_s : kNaN},
                        {"rmse_all_cm", f.suite.rmse_all_cm},
                        {"rmse_xy_cm", f.suite.rmse_xy_cm},
                        {"rmse_z_cm", f.suite.rmse_z_cm},
                        {"max_cm", f.suite.max_cm}};
        if (scn.laps >= 2) one["last_lap_rmse_cm"] = f.last_lap_rmse_cm;
        if (f.min_obstacle_clearance_m) one["min_obstacle_clearance_m"] = *f.min_obstacle_clearance_m;
        if (f.contact) {
          one.update(touchdownJson(*f.contact));
          one["landed"] = f.contact->landed;
          one["liftoff_t_s"] = f.contact->liftoff_t_s;
          one["recontacts"] = f.contact->recontacts;
          one["max_tilt_on_ground_deg"] = f.contact->max_tilt_on_ground_deg;
          if (std::isfinite(f.contact->touchdown_speed_mps)) {
            td_sum += f.contact->touchdown_speed_mps;
            bounce_sum += f.contact->bounce_m;
            ++touched;
          }
        }
        per_seed.push_back(std::move(one));
      }
      io::Json j = {{"case", c->scenario},
                    {"controller", c->controller},
                    {"seeds", std::move(seeds)},
                    {"flights", c->flights.size()},
                    {"strikes", c->strikes()},
                    {"rmse_all_cm", c->meanFinished(&SuiteFlight::rmse_all_cm)},
                    {"rmse_xy_cm", c->meanFinished(&SuiteFlight::rmse_xy_cm)},
                    {"rmse_z_cm", c->meanFinished(&SuiteFlight::rmse_z_cm)},
                    {"max_cm", c->meanFinished(&SuiteFlight::max_cm)}};
      if (scn.kind == BeyondKind::kLanding) {
        // Means over the flights that touched down.
        j["touchdown_speed_mps"] = touched ? td_sum / touched : kNaN;
        j["bounce_m"] = touched ? bounce_sum / touched : kNaN;
      }
      j["per_seed"] = std::move(per_seed);
      cells.push_back(std::move(j));
    }
  }
  doc["cells"] = std::move(cells);
  doc["checks"] = suiteChecksJson(r.checks);
  doc["timing"] = {{"threads", r.threads},         {"flights", r.flights},
                   {"simulated_s", r.simulated_s}, {"calibration_s", r.calibration_s},
                   {"flights_s", r.flights_s},     {"wall_s", r.wall_s}};
  return doc;
}

}  // namespace geaware::experiments
