// SPDX-License-Identifier: BSD-3-Clause
// The fault campaign's text summary and JSON (experiments/fault_suite.hpp).
#include <cmath>
#include <cstdint>
#include <string>

#include <fmt/format.h>

#include "geaware/experiments/fault_suite.hpp"
#include "geaware/io/provenance.hpp"

namespace geaware::experiments {
namespace {

std::string cellText(const FaultCell& c) {
  const double rmse = c.cell.meanFinished(&SuiteFlight::rmse_all_cm);
  std::string s = c.outcome;
  if (std::isfinite(rmse)) s += fmt::format(" {:.2f}", rmse);
  if (std::isfinite(c.degraded_cm) && c.cell.case_name != "none") s += fmt::format(" ({:+.2f})", c.degraded_cm);
  return s;
}

/// The flags a cell's flights raised: control ticks summed over its seeds (flights for
/// `terminated`).
struct FlagTotals {
  std::uint64_t motor_failure = 0, pose_stale = 0, imu_clipped = 0, pose_rejected = 0, height_invalid = 0;
  int terminated = 0;
};

FlagTotals totals(const FaultCell& c) {
  FlagTotals t;
  for (const auto& f : c.flights) {
    t.motor_failure += f.motor_failure_ticks;
    t.pose_stale += f.pose_stale_ticks;
    t.imu_clipped += f.imu_clipped_ticks;
    t.pose_rejected += f.pose_rejected_ticks;
    t.height_invalid += f.height_invalid_ticks;
    t.terminated += f.terminated ? 1 : 0;
  }
  return t;
}

/// As "motor_failure 120, pose_stale 98", or "-".
std::string flagsText(const FaultCell& c) {
  const FlagTotals t = totals(c);
  std::string s;
  const auto add = [&](const char* name, std::uint64_t n) {
    if (n > 0) s += fmt::format("{}{} {}", s.empty() ? "" : ", ", name, n);
  };
  add("motor_failure", t.motor_failure);
  add("terminated", static_cast<std::uint64_t>(t.terminated));
  add("pose_stale", t.pose_stale);
  add("imu_clipped", t.imu_clipped);
  add("pose_rejected", t.pose_rejected);
  add("height_invalid", t.height_invalid);
  return s.empty() ? "-" : s;
}

}  // namespace

std::string formatFaultSuite(const FaultSuiteResult& r) {
  std::string out = fmt::format(
      "Fault campaign: belief calibrated once on the unperturbed world; {} cases × {} heights × {} "
      "controllers × {} seed{} = {} flights. recommended = {} + additions.\n"
      "Each entry: outcome, mean all-RMSE of the finished flights [cm], (its change from the same "
      "flights without the fault, paired seeds). Faults begin at t = 4 s of the lap.\n",
      r.cases.size(), r.conditions.size(), r.controllers.size(), r.seeds.size(),
      r.seeds.size() == 1 ? "" : "s", r.flights, r.recommended);
  std::size_t k = 0;
  for (const auto& cond : r.conditions) {
    out += fmt::format("\n{:.2f} m / {:g} m/s ({})\n  {:<17}", cond.height_m(), cond.speed_mps(), cond.describe(), "case");
    for (const auto& c : r.controllers) out += fmt::format(" {:>30}", c);
    out += "\n";
    for (const auto& fc : r.cases) {
      out += fmt::format("  {:<17}", fc.name);
      for (std::size_t i = 0; i < r.controllers.size(); ++i) {
        const FaultCell* cell = nullptr;
        for (const auto& c : r.cells) {
          if (c.cell.case_name == fc.name && c.cell.controller == r.controllers[i] && c.cell.height_m == cond.height_m()) cell = &c;
        }
        out += fmt::format(" {:>30}", cell != nullptr ? cellText(*cell) : "-");
      }
      out += "\n";
    }
    ++k;
  }
  out += "\nFlags raised by recommended (control ticks summed over the seeds; estimator: pose_stale, imu_clipped, pose_rejected):\n";
  for (const auto& c : r.cells) {
    if (c.cell.controller != "recommended" || c.cell.case_name == "none") continue;
    out += fmt::format("  {:<17} {:.2f} m  {}\n", c.cell.case_name, c.cell.height_m, flagsText(c));
  }
  out += "\nChecks of the issue (reported as they are):\n";
  for (const auto& c : r.checks) {
    out += fmt::format("  [{}] {} — {}: {}\n", c.pass ? "pass" : "FAIL", c.name, c.criterion, c.value);
  }
  out += fmt::format("\n{} flights, {:.0f} s simulated, on {} thread{}: calibration {:.1f} s, flights {:.1f} s, wall {:.1f} s\n",
                     r.flights, r.simulated_s, r.threads, r.threads == 1 ? "" : "s", r.calibration_s,
                     r.flights_s, r.wall_s);
  return out;
}

io::Json faultSuiteJson(const FaultSuiteResult& r) {
  io::Json doc = {{"geaware_version", io::geawareVersion()},
                  {"suite", "faults"},
                  {"recommended", r.recommended},
                  {"seeds", r.seeds}};
  io::Json cases = io::Json::array();
  for (const auto& c : r.cases) {
    io::Json faults = io::Json::array();
    for (const auto& f : c.faults) {
      faults.push_back({{"kind", toString(f.kind)}, {"start_s", f.start_s},
                        {"duration_s", std::isfinite(f.duration_s) ? io::Json(f.duration_s) : io::Json(nullptr)},
                        {"motor", f.motor}, {"value", f.value}});
    }
    cases.push_back({{"case", c.name}, {"meaning", c.meaning}, {"survivable", c.survivable},
                     {"mass_scale", c.mass_scale}, {"faults", std::move(faults)}});
  }
  doc["cases"] = std::move(cases);
  doc["controllers"] = r.controllers;
  io::Json cells = io::Json::array();
  for (const auto& c : r.cells) {
    io::Json j = suiteCellJson(c.cell);
    j["outcome"] = c.outcome;
    j["survivable"] = c.survivable;
    j["degraded_cm"] = std::isfinite(c.degraded_cm) ? io::Json(c.degraded_cm) : io::Json(nullptr);
    j["non_finite_commands"] = c.non_finite_commands;
    const FlagTotals t = totals(c);
    j["terminated"] = t.terminated;
    j["flag_ticks"] = {{"motor_failure", t.motor_failure}, {"pose_stale", t.pose_stale},
                       {"imu_clipped", t.imu_clipped}, {"pose_rejected", t.pose_rejected},
                       {"height_invalid", t.height_invalid}};
    cells.push_back(std::move(j));
  }
  doc["cells"] = std::move(cells);
  doc["checks"] = suiteChecksJson(r.checks);
  doc["timing"] = {{"threads", r.threads}, {"flights", r.flights}, {"simulated_s", r.simulated_s},
                   {"calibration_s", r.calibration_s}, {"flights_s", r.flights_s}, {"wall_s", r.wall_s}};
  return doc;
}

}  // namespace geaware::experiments
