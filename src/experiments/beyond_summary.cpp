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

}  // namespace

double meanLastLapCm(const BeyondCell& c) noexcept {
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < c.extras.size(); ++i) {
    if (c.suite.flights[i].struck) continue;
    sum += c.extras[i].last_lap_rmse_cm;
    ++n;
  }
  return n == 0 ? kNaN : sum / n;
}

namespace {

std::string span(double lo, double hi, const char* unit) {
  if (!std::isfinite(lo)) return "-";
  return lo == hi ? fmt::format("{:.3f} {}", lo, unit) : fmt::format("{:.3f}–{:.3f} {}", lo, hi, unit);
}

/// What a cell adds to its line: touchdown, lift-off, clearance, last lap.
std::string extras(const BeyondScenario& scn, const BeyondCell& c) {
  std::string s;
  const std::size_t n = c.extras.size();
  if (scn.kind == BeyondKind::kLanding) {
    double lo = kNaN, hi = kNaN, bounce = 0.0;
    int landed = 0;
    for (const auto& x : c.extras) {
      if (!x.contact) continue;
      landed += x.contact->landed ? 1 : 0;
      const double v = x.contact->touchdown_speed_mps;
      if (!std::isfinite(v)) continue;
      lo = std::fmin(lo, v);
      hi = std::fmax(hi, v);
      bounce = std::max(bounce, x.contact->bounce_m);
    }
    s += fmt::format("  touchdown {}, bounce ≤ {:.1f} mm, landed {}/{}", span(lo, hi, "m/s"), 1e3 * bounce, landed, n);
  }
  if (scn.kind == BeyondKind::kTakeOff) {
    int lifted = 0, back = 0;
    double tilt = 0.0;
    for (const auto& x : c.extras) {
      if (!x.contact) continue;
      lifted += std::isfinite(x.contact->liftoff_t_s) ? 1 : 0;
      back += x.contact->recontacts;
      tilt = std::max(tilt, x.contact->max_tilt_on_ground_deg);
    }
    s += fmt::format("  lifted off {}/{}, back down {}, tilt ≤ {:.1f}°", lifted, n, back, tilt);
  }
  double clearance = kNaN;
  for (const auto& x : c.extras) {
    if (x.min_obstacle_clearance_m) clearance = std::fmin(clearance, *x.min_obstacle_clearance_m);
  }
  if (std::isfinite(clearance)) s += fmt::format("  closest rim {:.1f} cm", 100.0 * clearance);
  if (scn.laps >= 2) {
    const double lap = meanLastLapCm(c);
    s += std::isnan(lap) ? "  last lap -" : fmt::format("  last lap {:.2f} cm", lap);
  }
  return s;
}

}  // namespace

std::string formatBeyond(const BeyondResult& r) {
  std::string s = fmt::format(
      "Beyond suite ({}): {} scenario{} × {} controller{} × {} seed{} = {} flights, as the sweep "
      "flies them ({}). recommended = {} + additions.\n"
      "Each line: strikes, the mean all-RMSE and max of the finished flights [cm].\n",
      r.source, r.scenarios.size(), plural(r.scenarios.size()), r.controllers.size(),
      plural(r.controllers.size()), r.seeds.size(), plural(r.seeds.size()), r.flights,
      r.calibrated ? "the belief calibrated once in the unperturbed world" : "the belief as the vehicle file gives it",
      r.recommended);
  std::size_t width = 0;
  for (const auto& c : r.controllers) width = std::max(width, c.size());
  for (const auto& scn : r.scenarios) {
    s += fmt::format("\n{} ({}, {:.1f} s)\n", scn.sweep.name, kindName(scn.kind), scn.sweep.trajectory->duration());
    for (const auto& ctl : r.controllers) {
      const BeyondCell* c = r.cell(scn.sweep.name, ctl);
      if (c == nullptr) continue;
      const double rmse = c->suite.meanFinished(&SuiteFlight::rmse_all_cm);
      const double max = c->suite.meanFinished(&SuiteFlight::max_cm);
      s += fmt::format("  {:<{}}  strikes {}/{}  all-RMSE {}  max {}{}\n", ctl, width, c->suite.strikes(),
                       c->suite.flights.size(), std::isnan(rmse) ? "     -" : fmt::format("{:6.2f}", rmse),
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
                  {"recommended", r.recommended},
                  {"seeds", r.seeds}};
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
  doc["controllers"] = r.controllers;
  io::Json cells = io::Json::array();
  for (const auto& scn : r.scenarios) {
    for (const auto& ctl : r.controllers) {
      const BeyondCell* c = r.cell(scn.sweep.name, ctl);
      if (c == nullptr) continue;
      // The shared schema's cell (height and speed 0: the scenario sets them), then what the
      // scenario adds, per seed and for landings as the finished flights' means.
      io::Json j = suiteCellJson(c->suite);
      double td_sum = 0.0, bounce_sum = 0.0;
      int touched = 0;
      for (std::size_t i = 0; i < c->extras.size(); ++i) {
        const BeyondExtras& x = c->extras[i];
        io::Json& one = j["per_seed"][i];
        if (scn.laps >= 2) one["last_lap_rmse_cm"] = x.last_lap_rmse_cm;
        if (x.min_obstacle_clearance_m) one["min_obstacle_clearance_m"] = *x.min_obstacle_clearance_m;
        if (!x.contact) continue;
        one.update(groundContactJson(*x.contact));
        if (std::isfinite(x.contact->touchdown_speed_mps) && !c->suite.flights[i].struck) {
          td_sum += x.contact->touchdown_speed_mps;
          bounce_sum += x.contact->bounce_m;
          ++touched;
        }
      }
      if (scn.laps >= 2) j["last_lap_rmse_cm"] = meanLastLapCm(*c);
      if (scn.kind == BeyondKind::kLanding) {
        j["touchdown_speed_mps"] = touched ? td_sum / touched : kNaN;
        j["bounce_m"] = touched ? bounce_sum / touched : kNaN;
      }
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
