// SPDX-License-Identifier: BSD-3-Clause
// A sweep's keys and its flights (experiments/sweep.hpp, docs/sweeps.md): the flight of a key
// is built as the robustness suite builds its flights (robustness.cpp), from a belief
// calibrated once per world and process (memoised), so that a key's record does not depend on
// who flies it or in which order.

#include "geaware/experiments/sweep.hpp"

#include "geaware/experiments/flight_setup.hpp"
#include "geaware/experiments/flight_summary.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "geaware/control/controller_schema.hpp"
#include "geaware/experiments/calibration.hpp"
#include "geaware/experiments/fault_suite.hpp"
#include "geaware/experiments/neural_baseline.hpp"
#include "geaware/experiments/world_setup.hpp"
#include "geaware/io/json.hpp"
#include "geaware/io/truth_file.hpp"
#include "geaware/model/units.hpp"

namespace geaware::experiments {
namespace {

/// A world's belief: the base scenario of its flights, computed once (std::call_once), and
/// the Neural-Lander network trained on it, once, when a neural controller flies.
struct WorldEntry {
  std::once_flag base_once;
  FlightScenario base;
  std::once_flag neural_once;
  std::shared_ptr<const control::ResidualForceModel> neural;
};

std::mutex g_memo_mutex;
std::map<std::string, std::shared_ptr<WorldEntry>> g_memo;

std::shared_ptr<WorldEntry> entryFor(const std::string& id) {
  const std::lock_guard<std::mutex> lock(g_memo_mutex);
  auto& e = g_memo[id];
  if (!e) e = std::make_shared<WorldEntry>();
  return e;
}

/// The world a case flies in as calibrated: its own for a law family (when the sweep
/// calibrates), the unperturbed one otherwise.
bool ownWorld(const SweepSpec& spec, const Perturbation& p) {
  return spec.calibrate && p.recalibrates();
}

/// The unperturbed world as a scenario without trajectory (the robustness suite's).
FlightScenario worldScenario(const SweepSpec& spec) {
  FlightScenario s;
  s.vehicle = spec.vehicle;
  applyWorld(s, spec.world);
  s.start_hover_s = spec.start_hover_s;
  s.max_sim_s = spec.max_sim_s;
  return s;
}

FlightScenario calibratedBase(const SweepSpec& spec, const Perturbation* own) {
  FlightScenario world = worldScenario(spec);
  if (own != nullptr) applyPerturbation(*own, world);
  if (!spec.calibrate) {
    world.controller = control::applyParameters(world.controller, spec.controller_values);
    return world;
  }
  CalibrationSweeps sweeps = CalibrationSweeps::defaults();
  sweeps.flight_controller = control::applyParameters(sweeps.flight_controller, spec.controller_values);
  // The sweep's max_sim_s bounds its own flights, not the calibration's hover and drag flights.
  FlightScenario calibration_world = world;
  calibration_world.max_sim_s = FlightScenario{}.max_sim_s;
  const ControllerCalibration c =
      calibrateController(spec.vehicle, {calibration_world, spec.world.team_scale_error_std_kg}, sweeps);
  FlightScenario base = world;
  base.vehicle = c.vehicle;
  base.eskf = c.estimator;
  base.controller = control::applyParameters(base.controller, spec.controller_values);
  return base;
}

WorldEntry& worldOf(const SweepSpec& spec, const Perturbation& p, bool neural) {
  const bool own = ownWorld(spec, p);
  const std::string name = own ? p.name : "none";
  const auto entry = entryFor(spec.fingerprint + "|" + name);
  std::call_once(entry->base_once, [&] { entry->base = calibratedBase(spec, own ? &p : nullptr); });
  if (neural) {
    std::call_once(entry->neural_once, [&] {
      NeuralSettings settings;
      // As the robustness suite's: the unperturbed world's truth section is the key text.
      settings.world_key = io::truthSectionYaml(spec.world);
      entry->neural = prepareNeuralBaseline(entry->base, settings, {}, 1).network;
    });
  }
  return *entry;
}

std::size_t indexOf(const std::string& key, const std::string& part, const std::string& value,
                    const std::vector<std::string>& names) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == value) return i;
  }
  throw std::invalid_argument("sweep key '" + key + "': " + part + "='" + value +
                              "' is not one of this sweep's");
}

template <typename T>
std::vector<std::string> namesOf(const std::vector<T>& items) {
  std::vector<std::string> out;
  out.reserve(items.size());
  for (const auto& i : items) out.push_back(i.name);
  return out;
}

bool isNeural(const SuiteController& c) {
  return c.params.acceleration == control::AccelerationCompensation::kNeural;
}

}  // namespace

std::string sweepKeyText(const SweepSpec& spec, const SweepKey& k) {
  return fmt::format("case={}/ctl={}/scn={}/seed={}", spec.cases.at(k.case_index).name,
                     spec.controllers.at(k.controller_index).name,
                     spec.scenarios.at(k.scenario_index).name, k.seed);
}

std::vector<std::string> sweepKeys(const SweepSpec& spec) {
  std::vector<std::string> out;
  out.reserve(spec.flights());
  for (std::size_t c = 0; c < spec.cases.size(); ++c) {
    for (std::size_t k = 0; k < spec.controllers.size(); ++k) {
      for (std::size_t n = 0; n < spec.scenarios.size(); ++n) {
        for (std::uint64_t i = 0; i < spec.seed_count; ++i) {
          out.push_back(sweepKeyText(spec, {c, k, n, spec.first_seed + i}));
        }
      }
    }
  }
  return out;
}

SweepKey parseSweepKey(const SweepSpec& spec, const std::string& key) {
  static const char* const kParts[] = {"case=", "ctl=", "scn=", "seed="};
  std::vector<std::string> values;
  std::size_t at = 0;
  for (const char* part : kParts) {
    const std::string prefix(part);
    if (key.compare(at, prefix.size(), prefix) != 0) {
      throw std::invalid_argument("sweep key '" + key + "': expected '" + prefix + "' at offset " +
                                  std::to_string(at) + " (keys read case=…/ctl=…/scn=…/seed=N)");
    }
    at += prefix.size();
    const std::size_t end = prefix == "seed=" ? key.size() : key.find('/', at);
    if (end == std::string::npos) {
      throw std::invalid_argument("sweep key '" + key + "': expected '/' after '" + prefix + "'");
    }
    values.push_back(key.substr(at, end - at));
    at = end + 1;
  }
  SweepKey k;
  k.case_index = indexOf(key, "case", values[0], namesOf(spec.cases));
  k.controller_index = indexOf(key, "ctl", values[1], namesOf(spec.controllers));
  k.scenario_index = indexOf(key, "scn", values[2], namesOf(spec.scenarios));
  const std::string& seed = values[3];
  std::uint64_t v = 0;
  bool ok = !seed.empty() && seed.size() <= 10 && (seed == "0" || seed[0] != '0');
  for (const char c : seed) {
    ok = ok && c >= '0' && c <= '9';
    if (ok) v = v * 10 + static_cast<std::uint64_t>(c - '0');
  }
  if (!ok || v < spec.first_seed || v - spec.first_seed >= spec.seed_count) {
    throw std::invalid_argument(fmt::format("sweep key '{}': seed='{}' is not one of this sweep's ({} … {})",
                                            key, seed, spec.first_seed,
                                            spec.first_seed + spec.seed_count - 1));
  }
  k.seed = v;
  return k;
}

std::string sweepKeyFileName(std::string_view key) {
  std::string out;
  out.reserve(key.size() + 5);
  for (const char c : key) {
    const bool plain = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                       c == '.' || c == '+' || c == '=' || c == '-';
    if (plain) {
      out += c;
    } else if (c == '/') {
      out += ',';
    } else {
      out += fmt::format("_{:02x}", static_cast<unsigned char>(c));
    }
  }
  // A leading '.' would hide the file (and match the temporary files' pattern).
  if (!out.empty() && out[0] == '.') out.replace(0, 1, "_2e");
  return out + ".json";
}

FlightScenario sweepFlightScenario(const SweepSpec& spec, const SweepKey& k) {
  const Perturbation& p = spec.cases.at(k.case_index);
  const SuiteController& c = spec.controllers.at(k.controller_index);
  const SweepScenario& scn = spec.scenarios.at(k.scenario_index);
  const WorldEntry& w = worldOf(spec, p, isNeural(c));
  FlightScenario f = w.base;
  applyPerturbation(p, f);
  f.trajectory = scn.trajectory;
  if (scn.terrain) f.terrain = scn.terrain;
  f.obstacles = scn.obstacles;
  f.beam_rangers = scn.beam_rangers;
  f.controller = control::applyParameters(c.params, spec.controller_values);
  if (isNeural(c)) f.residual = w.neural;
  f.seed = k.seed;
  // A fault case, as the fault suite flies it (fault_suite.cpp).
  const FaultCase& fault = spec.case_faults.at(k.case_index);
  f.faults = fault.faults;
  if (fault.mass_scale != 1.0) {
    applyPerturbation({"mass", PerturbationKind::kMass, fault.mass_scale - 1.0, {}}, f);
  }
  if (fault.low_imu_ranges) {
    f.eskf.imu_gyro_range_rad_per_s = 250.0 * std::numbers::pi / 180.0;
    f.eskf.imu_accel_range_m_per_s2 = 4.0 * model::kGravity;
  }
  applyTouchdown(f);  // a landing or take-off scenario
  return f;
}

std::vector<ScenarioProblem> sweepScenarioProblems(const SweepSpec& spec, std::size_t scenario_index) {
  // The unperturbed, uncalibrated world: the calibration moves the belief by a few per cent at
  // most; what it changes is checked again when the flight starts (its key then names it).
  FlightScenario f = worldScenario(spec);
  const SweepScenario& scn = spec.scenarios.at(scenario_index);
  f.trajectory = scn.trajectory;
  if (scn.terrain) f.terrain = scn.terrain;
  f.obstacles = scn.obstacles;
  f.beam_rangers = scn.beam_rangers;
  if (!spec.controllers.empty()) {
    f.controller = control::applyParameters(spec.controllers.front().params, spec.controller_values);
  }
  applyTouchdown(f);
  return validate(f, ScenarioStage::kFile);
}

double sweepSimulatedSeconds(const SweepSpec& spec, std::size_t cases, std::size_t controllers,
                             const std::vector<std::string>& scenarios) {
  double per_seed = 0.0;  // one flight of each scenario flown
  for (const auto& s : spec.scenarios) {
    if (!scenarios.empty() && std::find(scenarios.begin(), scenarios.end(), s.name) == scenarios.end()) continue;
    per_seed += spec.start_hover_s + s.trajectory->duration() + FlightScenario{}.settle_s;
  }
  return per_seed * static_cast<double>(cases) * static_cast<double>(controllers) *
         static_cast<double>(spec.seed_count);
}

void prepareSweep(const SweepSpec& spec, const std::vector<std::string>& keys, Progress* progress) {
  // The worlds these keys fly in, each with whether a neural controller flies there.
  std::map<std::string, std::pair<std::size_t, bool>> worlds;  // name → (a case of it, neural)
  for (const auto& key : keys) {
    const SweepKey k = parseSweepKey(spec, key);
    const Perturbation& p = spec.cases[k.case_index];
    auto& w = worlds.try_emplace(ownWorld(spec, p) ? p.name : "none", k.case_index, false).first->second;
    w.second = w.second || isNeural(spec.controllers[k.controller_index]);
  }
  for (const auto& [name, w] : worlds) {
    if (progress != nullptr && (spec.calibrate || w.second)) {
      progress->message(fmt::format("world '{}':{}{}", name,
                                    spec.calibrate ? " calibration (rigs, scale, hover and drag flights)" : "",
                                    w.second ? " Neural-Lander training" : ""));
    }
    (void)worldOf(spec, spec.cases[w.first], w.second);
  }
}

std::string sweepRecord(const SweepSpec& spec, const SweepKey& k, const FlightResult& r) {
  const SuiteFlight f = toSuiteFlight(k.seed, r);
  io::Json j;
  j["key"] = sweepKeyText(spec, k);
  j["case"] = spec.cases.at(k.case_index).name;
  j["controller"] = spec.controllers.at(k.controller_index).name;
  j["scenario"] = spec.scenarios.at(k.scenario_index).name;
  j["seed"] = k.seed;
  j["struck"] = f.struck;
  j["strike_t_s"] = f.struck ? io::Json(f.strike_t_s) : io::Json(nullptr);
  j["rmse_all_cm"] = f.rmse_all_cm;
  j["rmse_xy_cm"] = f.rmse_xy_cm;
  j["rmse_z_cm"] = f.rmse_z_cm;
  j["max_cm"] = f.max_cm;
  j["guard_active_s"] = f.guard_active_s ? io::Json(*f.guard_active_s) : io::Json(nullptr);
  // The fault suite's: the controller cut the motors; throttles the plant had to replace.
  const FaultFlight ff = toFaultFlight(k.seed, r, f);
  j["terminated"] = ff.terminated;
  j["non_finite_commands"] = ff.non_finite_commands;
  j["simulated_s"] = r.simulated_s;
  // Flights with obstacles only (the ceiling and wall scenarios): other records keep their bytes.
  if (r.min_obstacle_clearance_m) j["min_obstacle_clearance_m"] = *r.min_obstacle_clearance_m;
  if (const auto& g = r.ground_contact) {
    // Landings and take-offs (flights with ground contact) only: other records keep their bytes.
    j.update(groundContactJson(*g));
  }
  // Compact, NaN as null, invalid UTF-8 replaced: one line, the same bytes everywhere.
  return j.dump(-1, ' ', false, io::Json::error_handler_t::replace);
}

std::string sweepCaseMeaning(const SweepSpec& spec, std::size_t i) {
  const FaultCase& fault = spec.case_faults.at(i);
  return fault.name.empty() ? spec.cases.at(i).meaning() : fault.meaning;
}

std::string runSweepFlight(const SweepSpec& spec, const std::string& key) {
  const SweepKey k = parseSweepKey(spec, key);
  return sweepRecord(spec, k, runFlight(sweepFlightScenario(spec, k)));
}

}  // namespace geaware::experiments
