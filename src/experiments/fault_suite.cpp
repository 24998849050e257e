// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/fault_suite.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "geaware/control/controller_schema.hpp"
#include "geaware/experiments/flight_pool.hpp"
#include "geaware/experiments/world_setup.hpp"
#include "geaware/traj/lemniscate.hpp"

namespace geaware::experiments {
namespace {

/// The index of a controller flag in FlightResult::flag_counts.
constexpr std::size_t flagBit(std::uint32_t flag) noexcept { return static_cast<std::size_t>(std::countr_zero(flag)); }

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

constexpr double kFaultStart_s = 4.0;  // trajectory time every fault begins: mid-lap [s]
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Fault fault(FaultKind kind, double value, double duration_s = kInf, int motor = 0) {
  Fault f;
  f.kind = kind;
  f.start_s = kFaultStart_s;
  f.duration_s = duration_s;
  f.motor = motor;
  f.value = value;
  return f;
}


/// The cell's outcome, against the same controller's baseline cell.
void judge(FaultCell& c, const FaultCell* baseline) {
  int struck = 0, terminated = 0;
  for (const auto& f : c.flights) {
    struck += f.flight.struck ? 1 : 0;
    terminated += f.terminated ? 1 : 0;
    c.non_finite_commands += f.non_finite_commands;
  }
  const auto n = static_cast<int>(c.flights.size());
  double sum = 0.0;
  int both = 0;
  double base_sum = 0.0;
  if (baseline != nullptr) {
    for (std::size_t i = 0; i < c.flights.size() && i < baseline->flights.size(); ++i) {
      const auto& a = c.flights[i].flight;
      const auto& b = baseline->flights[i].flight;
      if (a.struck || b.struck || c.flights[i].terminated) continue;
      sum += a.rmse_all_cm - b.rmse_all_cm;
      base_sum += b.rmse_all_cm;
      ++both;
    }
  }
  c.degraded_cm = both > 0 ? sum / both : kNaN;
  std::vector<std::string> parts;
  if (struck > 0) parts.push_back(fmt::format("struck {}/{}", struck, n));
  if (terminated > 0) parts.push_back(fmt::format("terminated {}/{}", terminated, n));
  if (struck == 0 && terminated == 0) {
    const double base_mean = both > 0 ? base_sum / both : kNaN;
    const bool degraded = both > 0 && (c.degraded_cm > 1.0 || c.degraded_cm > 0.5 * base_mean);
    parts.emplace_back(degraded ? "degraded" : "finished");
  }
  c.outcome.clear();
  for (const auto& p : parts) c.outcome += (c.outcome.empty() ? "" : ", ") + p;
}

}  // namespace

FaultFlight toFaultFlight(std::uint64_t seed, const FlightResult& fr, const SuiteFlight& base) {
  FaultFlight f;
  f.flight = base;
  f.flight.seed = seed;
  f.terminated = fr.flag_counts[flagBit(control::kFlagTerminated)] > 0;
  f.non_finite_commands = fr.throttle_faults;
  f.motor_failure_ticks = fr.flag_counts[flagBit(control::kFlagMotorFailure)];
  f.height_invalid_ticks = fr.flag_counts[flagBit(control::kFlagHeightInvalid)];
  f.pose_stale_ticks = fr.estimation.eskf_flag_ticks[0];
  f.imu_clipped_ticks = fr.estimation.eskf_flag_ticks[1];
  f.pose_rejected_ticks = fr.estimation.eskf_flag_ticks[2];
  return f;
}

std::vector<FaultCase> faultCases() {
  const double deg = std::numbers::pi / 180.0;
  std::vector<FaultCase> c;
  c.push_back({"none", "no fault: the baseline every case is compared with", {}, 1.0, true, false});
  c.push_back({"motor 80%", "motor 1 gives 80 % of its thrust from t = 4 s (worn motor, chipped propeller)",
               {fault(FaultKind::kMotorEffectiveness, 0.8)}, 1.0, true, false});
  c.push_back({"motor 50%", "motor 1 gives 50 % of its thrust from t = 4 s",
               {fault(FaultKind::kMotorEffectiveness, 0.5)}, 1.0, true, false});
  c.push_back({"motor stop", "motor 1 stops at t = 4 s (ESC cut-out): a quadrotor cannot be held",
               {fault(FaultKind::kMotorStop, 0.0)}, 1.0, false, false});
  c.push_back({"mocap 0.5s", "no motion-capture pose for 0.5 s from t = 4 s (occlusion)",
               {fault(FaultKind::kMocapDropout, 0.0, 0.5)}, 1.0, true, false});
  c.push_back({"mocap 2s", "no motion-capture pose for 2 s from t = 4 s",
               {fault(FaultKind::kMocapDropout, 0.0, 2.0)}, 1.0, true, false});
  c.push_back({"ranger outliers", "from t = 4 s each ranger zone returns a random 0.02–4 m with probability 0.2",
               {fault(FaultKind::kRangerOutliers, 0.2)}, 1.0, true, false});
  c.push_back({"ranger dead", "the ranger delivers nothing from t = 4 s",
               {fault(FaultKind::kRangerDead, 0.0)}, 1.0, true, false});
  c.push_back({"kick + IMU clip", "a 0.4 N·m roll kick for 0.1 s at t = 4 s with the IMU clipping at ±250 °/s, ±4 g for 0.3 s",
               {fault(FaultKind::kImuClipKick, 0.4, 0.3)}, 1.0, true, true});
  c.push_back({"gyro bias 2°/s", "the gyro's bias steps by 2 °/s on every axis at t = 4 s",
               {fault(FaultKind::kGyroBiasStep, 2.0 * deg)}, 1.0, true, false});
  c.push_back({"battery sag", "the battery's voltage sags to 85 % at t = 4 s (a 4S pack from 16.8 to 14.3 V under load): every ESC reaches 85 % of the rotor speed asked",
               {fault(FaultKind::kBatterySag, 0.85)}, 1.0, true, false});
  c.push_back({"mass +10%", "the vehicle weighs 10 % more than the scale said, from the start (an unweighed payload)",
               {}, 1.10, true, false});
  c.push_back({"gust 2m/s", "a 2 m/s gust along x, 1 − cos shaped over 2 s, from t = 4 s",
               {fault(FaultKind::kGust, 2.0, 2.0)}, 1.0, true, false});
  return c;
}

FaultSuiteResult runFaultSuite(const FaultSuiteOptions& o) {
  if (o.seeds < 1) throw std::invalid_argument("fault suite: seeds must be at least 1");
  if (o.cases.empty() || o.cases.front().name != "none") {
    throw std::invalid_argument("fault suite: the first case must be \"none\" (the baseline)");
  }
  if (o.controllers.empty() || o.conditions.empty()) {
    throw std::invalid_argument("fault suite: no controller or no height to fly");
  }
  for (std::size_t i = 0; i < o.conditions.size(); ++i) {
    const SuiteCondition& c = o.conditions[i];
    if (const auto problems = c.lemniscate.validate(); !problems.empty()) {
      throw std::invalid_argument("fault suite: height/speed '" + c.name + "': " + problems.front());
    }
    for (std::size_t j = 0; j < i; ++j) {
      // The cells of a case and controller are told apart by their height.
      if (o.conditions[j].height_m() == c.height_m()) {
        throw std::invalid_argument(fmt::format("fault suite: two heights/speeds at {:g} m", c.height_m()));
      }
    }
  }
  for (const auto& c : o.cases) {
    const auto problems = validate(c.faults);
    if (!problems.empty()) {
      throw std::invalid_argument(fmt::format("fault suite: case \"{}\": {} = {}: expected {}", c.name,
                                              problems.front().field, problems.front().value,
                                              problems.front().expected));
    }
  }
  const auto t_start = Clock::now();
  FaultSuiteResult r;
  r.cases = o.cases;
  r.conditions = o.conditions;
  for (const auto& c : o.controllers) r.controllers.push_back(c.name);
  for (int s = 0; s < o.seeds; ++s) r.seeds.push_back(o.first_seed + static_cast<std::uint64_t>(s));
  const control::ControllerParams rec = control::recommendedControllerParams();
  r.recommended = std::string(control::toString(rec.acceleration)) + ":" + control::toString(rec.torque);
  r.threads = resolveThreads(o.jobs);

  // 1. The belief, calibrated once on the unperturbed world.
  const sim::World world = o.world ? *o.world : sim::idealWorld(o.vehicle);
  FlightScenario base;
  base.vehicle = o.vehicle;
  applyWorld(base, world);
  base.start_hover_s = o.start_hover_s;
  if (o.progress != nullptr) o.progress->message("calibration: rigs, scale, hover and drag flights");
  auto t0 = Clock::now();
  CalibrationSweeps sweeps = o.calibration;
  sweeps.flight_controller = control::applyParameters(sweeps.flight_controller, o.controller_values);
  r.calibration = calibrateController(o.vehicle, {base, world.team_scale_error_std_kg}, sweeps);
  r.calibration_s = since(t0);
  base.vehicle = r.calibration.vehicle;
  base.eskf = r.calibration.estimator;

  // 2. Every flight: case, condition, controller, seed.
  std::vector<FlightJob> jobs;
  for (const auto& fc : o.cases) {
    for (const auto& cond : o.conditions) {
      const auto trajectory = std::make_shared<traj::Lemniscate>(cond.lemniscate);
      for (const auto& c : o.controllers) {
        FaultCell cell;
        cell.cell = SuiteCell{fc.name, c.name, cond.height_m(), cond.speed_mps(), {}};
        cell.survivable = fc.survivable;
        r.cells.push_back(std::move(cell));
        for (const auto seed : r.seeds) {
          FlightScenario f = base;
          f.trajectory = trajectory;
          f.controller = control::applyParameters(c.params, o.controller_values);
          f.seed = seed;
          f.faults = fc.faults;
          if (fc.mass_scale != 1.0) applyPerturbation({"mass", PerturbationKind::kMass, fc.mass_scale - 1.0, {}}, f);
          if (fc.low_imu_ranges) {
            f.eskf.imu_gyro_range_rad_per_s = 250.0 * std::numbers::pi / 180.0;
            f.eskf.imu_accel_range_m_per_s2 = 4.0 * model::kGravity;
          }
          jobs.push_back({std::move(f), nullptr,
                          fmt::format("{} {} {:.2f} m seed {}", fc.name, c.name, cond.height_m(), seed)});
        }
      }
    }
  }
  if (o.progress != nullptr) {
    o.progress->message(fmt::format("flights: {} ({} cases × {} heights × {} controllers × {} seeds) on {} thread{}",
                                    jobs.size(), o.cases.size(), o.conditions.size(), o.controllers.size(),
                                    o.seeds, r.threads, r.threads == 1 ? "" : "s"));
  }
  t0 = Clock::now();
  const auto results = runFlights(jobs, o.jobs, [&](std::size_t done, std::size_t total, const FlightJob&, const FlightResult&) {
    if (o.progress != nullptr) o.progress->update(static_cast<double>(done), static_cast<double>(total), "flights");
  });
  r.flights_s = since(t0);
  r.flights = results.size();

  // 3. Into the cells, then each judged against its controller's baseline at that height.
  std::size_t j = 0;
  for (auto& cell : r.cells) {
    for (const auto seed : r.seeds) {
      const SuiteFlight sf = toSuiteFlight(seed, results[j]);
      cell.cell.flights.push_back(sf);
      cell.flights.push_back(toFaultFlight(seed, results[j], sf));
      r.simulated_s += results[j].simulated_s;
      ++j;
    }
  }
  const std::size_t per_case = o.conditions.size() * o.controllers.size();
  for (std::size_t k = 0; k < r.cells.size(); ++k) judge(r.cells[k], &r.cells[k % per_case]);
  r.checks = faultChecks(r);
  r.wall_s = since(t_start);
  return r;
}

std::vector<SuiteCheck> faultChecks(const FaultSuiteResult& r) {
  long non_finite = 0;
  int survivable_cells = 0, struck_cells = 0;
  std::string where;
  for (const auto& c : r.cells) {
    if (c.cell.controller != "recommended") continue;
    non_finite += c.non_finite_commands;
    if (!c.survivable) continue;
    ++survivable_cells;
    if (c.cell.strikes() > 0) {
      ++struck_cells;
      where += fmt::format("{}{} @ {:g} m", where.empty() ? "; struck in: " : ", ", c.cell.case_name, c.cell.height_m);
    }
  }
  std::vector<SuiteCheck> checks;
  checks.push_back({"recommended: no non-finite command", "0 throttles replaced by the plant, in every cell",
                    fmt::format("{}", non_finite), non_finite == 0});
  checks.push_back({"recommended: no strike where the vehicle can be saved",
                    "0 strikes in every case but a stopped motor",
                    fmt::format("{} of {} cells with strikes{}", struck_cells, survivable_cells, where),
                    struck_cells == 0});
  return checks;
}

}  // namespace geaware::experiments
