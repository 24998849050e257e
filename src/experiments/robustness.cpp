// SPDX-License-Identifier: BSD-3-Clause
// The robustness suite's cells and its run (experiments/robustness.hpp, docs/robustness.md).
// The comparisons, checks, text and JSON are in robustness_summary.cpp, the page in
// robustness_report.cpp.

#include "geaware/experiments/robustness.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "geaware/control/controller_schema.hpp"
#include "geaware/experiments/flight_pool.hpp"
#include "geaware/experiments/table_one.hpp"
#include "geaware/experiments/world_setup.hpp"
#include "geaware/io/truth_file.hpp"
#include "geaware/traj/lemniscate.hpp"

namespace geaware::experiments {
namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Room air's correlation time when the world has none: docs/world.md, "Room air" (indoor
/// arenas, τ ≈ 1–2 s) [s].
constexpr double kGustCorrelationTimeS = 1.5;

}  // namespace

std::string Perturbation::meaning() const {
  using K = PerturbationKind;
  switch (kind) {
    case K::kNone:
      return "the world the belief was calibrated in";
    case K::kMass:
      return fmt::format("truth mass × {:.2f} (payload, battery)", 1.0 + value);
    case K::kThrustCoefficient:
      return fmt::format("k_T of every motor × {:.2f} (propeller swap)", 1.0 + value);
    case K::kMotorSpread:
      return fmt::format("per-motor k_T × {:.2f}, {:.2f}, {:.2f}, {:.2f} (mixer order)",
                         1.0 + value, 1.0 - value, 1.0 + value, 1.0 - value);
    case K::kCogOffset:
      return fmt::format("CoG moved {:g} cm forward (body x)", value * 100.0);
    case K::kInFlightCushion:
      return fmt::format("in-flight cushion scale × {:g}", value);
    case K::kMocapLatency:
      return fmt::format("true mocap latency + {:g} ms, stamped latency unchanged", value * 1000.0);
    case K::kGusts:
      return fmt::format("room air: gusts σ {:g} m/s per axis", value);
    case K::kGroundEffectLaw:
      return fmt::format("truth ground-effect law '{}', rigs and identification re-run",
                         sim::toString(law));
  }
  return "?";
}

std::vector<Perturbation> robustnessCells() {
  using K = PerturbationKind;
  using L = sim::GroundEffectLaw;
  return {
      {"none", K::kNone, 0.0, L::kCalibrated},
      {"mass-10%", K::kMass, -0.10, L::kCalibrated},
      {"mass-5%", K::kMass, -0.05, L::kCalibrated},
      {"mass+5%", K::kMass, 0.05, L::kCalibrated},
      {"mass+10%", K::kMass, 0.10, L::kCalibrated},
      {"k_T-5%", K::kThrustCoefficient, -0.05, L::kCalibrated},
      {"k_T+5%", K::kThrustCoefficient, 0.05, L::kCalibrated},
      {"spread±5%", K::kMotorSpread, 0.05, L::kCalibrated},
      {"cog+1cm", K::kCogOffset, 0.01, L::kCalibrated},
      {"cushion×0.5", K::kInFlightCushion, 0.5, L::kCalibrated},
      {"cushion×0.8", K::kInFlightCushion, 0.8, L::kCalibrated},
      {"cushion×1.2", K::kInFlightCushion, 1.2, L::kCalibrated},
      {"latency+20ms", K::kMocapLatency, 0.020, L::kCalibrated},
      {"gusts0.3", K::kGusts, 0.3, L::kCalibrated},
      {"law:cheeseman_bennett", K::kGroundEffectLaw, 0.0, L::kCheesemanBennett},
      {"law:sanchez_cuevas", K::kGroundEffectLaw, 0.0, L::kSanchezCuevas},
  };
}

void applyPerturbation(const Perturbation& p, FlightScenario& s) {
  if (!s.truth) {
    throw std::invalid_argument("applyPerturbation: the scenario has no truth to change");
  }
  sim::TruthParams& t = *s.truth;
  using K = PerturbationKind;
  switch (p.kind) {
    case K::kNone:
      break;
    case K::kMass:
      t.mass_kg *= 1.0 + p.value;
      break;
    case K::kThrustCoefficient:
      t.k_T_N_per_rpm2 *= 1.0 + p.value;
      break;
    case K::kMotorSpread:
      for (std::size_t i = 0; i < 4; ++i) {
        t.thrust_multiplier[i] *= 1.0 + (i % 2 == 0 ? p.value : -p.value);
      }
      break;
    case K::kCogOffset:
      t.cog_offset_B.x() += p.value;
      break;
    case K::kInFlightCushion:
      t.aero.in_flight_cushion_scale *= p.value;
      break;
    case K::kMocapLatency: {
      sim::MocapParams& m = s.sensors.mocap;
      // The driver keeps stamping what it believed before the change.
      if (m.reported_latency_s < 0.0) m.reported_latency_s = m.latency_s;
      m.latency_s += p.value;
      break;
    }
    case K::kGusts:
      if (!s.disturbances.wind) {
        s.disturbances.wind = true;
        s.disturbances.wind_params = sim::WindParams{};
        s.disturbances.wind_params.gust_correlation_time_s = kGustCorrelationTimeS;
      }
      s.disturbances.wind_params.gust_std_mps = Eigen::Vector3d::Constant(p.value);
      break;
    case K::kGroundEffectLaw:
      t.aero.law = p.law;
      break;
  }
}

std::string SuiteCondition::describe() const {
  return experiment > 0 ? fmt::format("exp {}'s lemniscate", experiment) : "lemniscate " + name;
}

SuiteCondition suiteCondition(const traj::LemniscateParams& lemniscate, std::string name) {
  SuiteCondition c{std::move(name), lemniscate, 0};
  for (const auto& e : tableOneExperiments()) {
    const traj::LemniscateParams shape = lemniscateFor(e);  // its height and speed aside
    const bool same = shape.centre_xy_m == lemniscate.centre_xy_m &&
                      shape.half_extent_x_m == lemniscate.half_extent_x_m &&
                      shape.half_extent_y_m == lemniscate.half_extent_y_m &&
                      shape.height_swing_m == lemniscate.height_swing_m && shape.laps == lemniscate.laps &&
                      shape.ramp_time_s == lemniscate.ramp_time_s && shape.yaw_rad == lemniscate.yaw_rad;
    if (same) {
      c.experiment = e.number;
      break;
    }
  }
  return c;
}

int SuiteCell::strikes() const noexcept {
  return static_cast<int>(std::count_if(flights.begin(), flights.end(),
                                        [](const SuiteFlight& f) { return f.struck; }));
}

double SuiteCell::meanFinished(double SuiteFlight::*metric) const noexcept {
  double sum = 0.0;
  int n = 0;
  for (const auto& f : flights) {
    if (f.struck) continue;
    sum += f.*metric;
    ++n;
  }
  return n == 0 ? std::numeric_limits<double>::quiet_NaN() : sum / n;
}

std::optional<double> SuiteCell::guardActiveS() const noexcept {
  double sum = 0.0;
  for (const auto& f : flights) {
    if (!f.guard_active_s) return std::nullopt;
    sum += *f.guard_active_s;
  }
  if (flights.empty()) return std::nullopt;
  return sum / static_cast<double>(flights.size());
}

const SuiteCell* RobustnessResult::cell(const std::string& case_name,
                                        const std::string& controller,
                                        double height_m) const noexcept {
  for (const auto& c : cells) {
    if (c.case_name == case_name && c.controller == controller && c.height_m == height_m) {
      return &c;
    }
  }
  return nullptr;
}

namespace {

void checkOptions(const RobustnessOptions& o) {
  if (o.seeds < 1) throw std::invalid_argument("robustness: seeds must be at least 1");
  if (o.cells.empty()) throw std::invalid_argument("robustness: no cell to fly");
  if (o.controllers.empty()) throw std::invalid_argument("robustness: no controller to fly");
  if (o.conditions.empty()) throw std::invalid_argument("robustness: no height/speed to fly");
  std::set<std::string> names;
  for (const auto& c : o.cells) {
    if (!names.insert(c.name).second) {
      throw std::invalid_argument("robustness: case '" + c.name + "' is listed twice");
    }
  }
  names.clear();
  for (const auto& c : o.controllers) {
    if (!names.insert(c.name).second) {
      throw std::invalid_argument("robustness: controller '" + c.name + "' is listed twice");
    }
  }
  std::set<double> heights;
  for (const auto& c : o.conditions) {
    if (const auto problems = c.lemniscate.validate(); !problems.empty()) {
      throw std::invalid_argument("robustness: height/speed '" + c.name + "': " + problems.front());
    }
    // The cells of a case and controller are told apart by their height.
    if (!heights.insert(c.height_m()).second) {
      throw std::invalid_argument(fmt::format("robustness: two heights/speeds at {:g} m", c.height_m()));
    }
  }
}

bool fliesNeural(const RobustnessOptions& o) {
  return std::any_of(o.controllers.begin(), o.controllers.end(), [](const SuiteController& c) {
    return c.params.acceleration == control::AccelerationCompensation::kNeural;
  });
}

/// The unperturbed world as a scenario without trajectory (the campaign's base scenario).
FlightScenario worldScenario(const RobustnessOptions& o, const sim::World& world) {
  FlightScenario s;
  s.vehicle = o.vehicle;
  applyWorld(s, world);
  s.start_hover_s = o.start_hover_s;
  return s;
}

/// Calibrates the belief in `world` (rigs + identification, and the Neural-Lander training when
/// a neural configuration flies): the base scenario of every flight of that world.
struct CalibratedWorld {
  SuiteCalibration calibration;
  FlightScenario base;
};

CalibratedWorld calibrate(const RobustnessOptions& o, const std::string& name,
                          const FlightScenario& world, double scale_error_std_kg,
                          const std::string& world_key, RobustnessResult& r) {
  auto say = [&](const std::string& m) {
    if (o.progress != nullptr) o.progress->message(m);
  };
  CalibratedWorld w;
  w.calibration.world = name;
  say(fmt::format("calibration ({}): virtual platform and rotor stand on the truth, the scale, "
                  "hover and drag flights", name));
  auto t0 = Clock::now();
  CalibrationSweeps sweeps = o.calibration;
  sweeps.flight_controller = control::applyParameters(sweeps.flight_controller, o.controller_values);
  w.calibration.calibration = calibrateController(o.vehicle, {world, scale_error_std_kg}, sweeps);
  r.calibration_s += since(t0);
  w.base = world;
  w.base.vehicle = w.calibration.calibration.vehicle;
  w.base.eskf = w.calibration.calibration.estimator;
  w.base.controller = control::applyParameters(w.base.controller, o.controller_values);
  if (fliesNeural(o)) {
    t0 = Clock::now();
    NeuralSettings neural = o.neural;
    neural.world_key = world_key;  // as the campaign's; a law family changes the truth's key
    w.calibration.neural = prepareNeuralBaseline(w.base, neural, o.cache_dir, o.jobs, o.progress);
    r.neural_s += since(t0);
  }
  return w;
}


}  // namespace

SuiteFlight toSuiteFlight(std::uint64_t seed, const FlightResult& fr) {
  SuiteFlight f;
  f.seed = seed;
  f.struck = fr.crash.has_value();
  f.strike_t_s = fr.crash ? fr.crash->t_s : 0.0;
  const TableMetrics m = toCentimetres(fr.tracking);
  f.rmse_all_cm = m.rmse_all_cm;
  f.rmse_xy_cm = m.rmse_xy_cm;
  f.rmse_z_cm = m.rmse_z_cm;
  f.max_cm = m.max_cm;
  f.guard_active_s = fr.guard_active_s;
  return f;
}

RobustnessResult runRobustness(const RobustnessOptions& o) {
  checkOptions(o);
  const auto t_start = Clock::now();
  RobustnessResult r;
  r.cases = o.cells;
  r.conditions = o.conditions;
  for (const auto& c : o.controllers) r.controllers.push_back(c.name);
  for (int s = 0; s < o.seeds; ++s) r.seeds.push_back(o.first_seed + static_cast<std::uint64_t>(s));
  const control::ControllerParams rec = control::recommendedControllerParams();
  r.recommended = std::string(control::toString(rec.acceleration)) + ":" + control::toString(rec.torque);
  r.threads = resolveThreads(o.jobs);

  // 1. The belief, calibrated once on the unperturbed world; the law families get their own.
  const sim::World unperturbed = o.world ? *o.world : sim::idealWorld(o.vehicle);
  const std::string world_key = io::truthSectionYaml(unperturbed);
  const FlightScenario world = worldScenario(o, unperturbed);
  std::vector<CalibratedWorld> worlds;
  const double scale_std = unperturbed.team_scale_error_std_kg;
  worlds.push_back(calibrate(o, "none", world, scale_std, world_key, r));
  std::vector<std::size_t> world_of_case;
  for (const auto& p : o.cells) {
    if (!p.recalibrates()) {
      world_of_case.push_back(0);
      continue;
    }
    FlightScenario changed = world;
    applyPerturbation(p, changed);
    worlds.push_back(calibrate(o, p.name, changed, scale_std, world_key, r));
    world_of_case.push_back(worlds.size() - 1);
  }
  for (const auto& w : worlds) r.calibrations.push_back(w.calibration);

  // 2. Every flight in a fixed order: case, condition, controller, seed.
  std::vector<FlightJob> jobs;
  for (std::size_t k = 0; k < o.cells.size(); ++k) {
    const Perturbation& p = o.cells[k];
    const CalibratedWorld& w = worlds[world_of_case[k]];
    for (const auto& cond : o.conditions) {
      const auto trajectory = std::make_shared<traj::Lemniscate>(cond.lemniscate);
      for (const auto& c : o.controllers) {
        SuiteCell cell{p.name, c.name, cond.height_m(), cond.speed_mps(), {}};
        r.cells.push_back(std::move(cell));
        for (const auto seed : r.seeds) {
          FlightScenario f = w.base;
          applyPerturbation(p, f);
          f.trajectory = trajectory;
          f.controller = control::applyParameters(c.params, o.controller_values);
          if (c.params.acceleration == control::AccelerationCompensation::kNeural) {
            f.residual = w.calibration.neural->network;
          }
          f.seed = seed;
          jobs.push_back({std::move(f), nullptr,
                          fmt::format("{} {} {:.2f} m seed {}", p.name, c.name, cond.height_m(), seed)});
        }
      }
    }
  }
  if (o.progress != nullptr) {
    o.progress->message(fmt::format("flights: {} ({} cases × {} heights × {} controllers × {} seeds) "
                                    "on {} thread{}",
                                    jobs.size(), o.cells.size(), o.conditions.size(),
                                    o.controllers.size(), o.seeds, r.threads,
                                    r.threads == 1 ? "" : "s"));
  }
  auto t0 = Clock::now();
  const auto results = runFlights(
      jobs, o.jobs, [&](std::size_t done, std::size_t total, const FlightJob&, const FlightResult&) {
        if (o.progress != nullptr) {
          o.progress->update(static_cast<double>(done), static_cast<double>(total), "flights");
        }
      });
  r.flights_s = since(t0);
  r.flights = results.size();

  // 3. Results into their cells, in the order they were planned.
  std::size_t j = 0;
  for (auto& cell : r.cells) {
    for (const auto seed : r.seeds) {
      cell.flights.push_back(toSuiteFlight(seed, results[j]));
      r.simulated_s += results[j].simulated_s;
      ++j;
    }
  }
  r.checks = robustnessChecks(r);
  r.wall_s = since(t_start);
  return r;
}

}  // namespace geaware::experiments
