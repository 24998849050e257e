// SPDX-License-Identifier: BSD-3-Clause
// The beyond suite (experiments/beyond_suite.hpp): flies the sweep's flights with an observer
// each (last-lap error, the report's series), groups them into cells and checks `recommended`.

#include "geaware/experiments/beyond_suite.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "geaware/experiments/flight_pool.hpp"
#include "geaware/experiments/tracking_metrics.hpp"
#include "geaware/traj/lemniscate.hpp"
#include "geaware/traj/touchdown.hpp"

namespace geaware::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Trajectory time at which `profile` has covered `s` of its distance (bisection; the progress
/// is non-decreasing in time) [s].
double timeAtProgress(const traj::SmoothProfile& profile, double s) {
  double lo = 0.0, hi = profile.duration();
  for (int i = 0; i < 100 && hi - lo > 1e-9; ++i) {
    const double mid = 0.5 * (lo + hi);
    (profile.sample(mid).s < s ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

BeyondScenario describe(const SweepScenario& s, std::size_t index) {
  BeyondScenario b;
  b.sweep = s;
  b.index = index;
  b.last_lap_from_s = kNaN;
  const traj::Trajectory* t = s.trajectory.get();
  if (dynamic_cast<const traj::Landing*>(t) != nullptr) b.kind = BeyondKind::kLanding;
  if (dynamic_cast<const traj::TakeOff*>(t) != nullptr) b.kind = BeyondKind::kTakeOff;
  if (const auto* lem = dynamic_cast<const traj::Lemniscate*>(t)) {
    b.laps = lem->params().laps;
    if (b.laps >= 2) {
      const traj::SmoothProfile& phase = lem->phase();
      b.last_lap_from_s = timeAtProgress(phase, phase.distance() * (b.laps - 1) / b.laps);
    }
  }
  return b;
}

/// Per flight: the error over the last lap, and the series when the report wants them.
class BeyondObserver final : public FlightObserver {
 public:
  BeyondObserver(double last_lap_from_s, std::unique_ptr<SeriesCollector> series)
      : from_s_(last_lap_from_s), series_(std::move(series)) {}
  void onTick(const FlightTick& tick) noexcept override {
    if (series_) series_->onTick(tick);
    if (tick.in_trajectory && tick.t_traj_s >= from_s_) {
      last_lap_.add(tick.input.reference.p_W - tick.truth.p_W);
      ++samples_;
    }
  }
  [[nodiscard]] double lastLapRmseCm() const noexcept {
    return samples_ == 0 ? kNaN : 100.0 * last_lap_.result().rmse_all_m;
  }
  [[nodiscard]] SeriesCollector* series() const noexcept { return series_.get(); }

 private:
  double from_s_;  // NaN: no last lap, nothing is accumulated
  std::unique_ptr<SeriesCollector> series_;
  TrackingAccumulator last_lap_;
  std::size_t samples_ = 0;
};

template <class T, class Name>
std::vector<std::size_t> pickIndices(const std::vector<T>& all, const std::vector<std::string>& names,
                                     const char* what, Name name_of) {
  std::vector<std::size_t> out;
  if (names.empty()) {
    for (std::size_t i = 0; i < all.size(); ++i) out.push_back(i);
    return out;
  }
  for (const auto& n : names) {
    const auto it = std::find_if(all.begin(), all.end(), [&](const T& t) { return name_of(t) == n; });
    if (it == all.end()) {
      std::string valid;
      for (const auto& t : all) valid += (valid.empty() ? "" : ", ") + name_of(t);
      throw std::invalid_argument(fmt::format("beyond suite: no {} '{}' (expected one of {})", what, n, valid));
    }
    const auto i = static_cast<std::size_t>(it - all.begin());
    if (std::find(out.begin(), out.end(), i) != out.end()) {
      throw std::invalid_argument(fmt::format("beyond suite: {} '{}' named twice", what, n));
    }
    out.push_back(i);
  }
  return out;
}

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

const BeyondCell* BeyondResult::cell(const std::string& scenario,
                                     const std::string& controller) const noexcept {
  for (const auto& c : cells) {
    if (c.scenario() == scenario && c.controller() == controller) return &c;
  }
  return nullptr;
}

BeyondResult runBeyond(const SweepSpec& spec, const BeyondOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  if (spec.cases.size() != 1) {
    throw std::invalid_argument(fmt::format(
        "beyond suite: {} has {} perturbation cases; the suite flies one world (its first, "
        "normally 'none')", spec.source, spec.cases.size()));
  }
  BeyondResult r;
  r.source = spec.source;
  r.calibrated = spec.calibrate;
  const control::ControllerParams rec = control::recommendedControllerParams();
  r.recommended = std::string(control::toString(rec.acceleration)) + ":" + control::toString(rec.torque);
  const auto scenario_idx = pickIndices(spec.scenarios, o.scenarios, "scenario",
                                        [](const SweepScenario& s) { return s.name; });
  const auto controller_idx = pickIndices(spec.controllers, o.controllers, "controller",
                                          [](const SuiteController& c) { return c.name; });
  for (std::size_t i : scenario_idx) r.scenarios.push_back(describe(spec.scenarios[i], i));
  for (std::size_t i : controller_idx) r.controllers.push_back(spec.controllers[i].name);
  for (std::uint64_t k = 0; k < spec.seed_count; ++k) r.seeds.push_back(spec.first_seed + k);

  // The calibration first (memoised per process and spec), so that its time is its own.
  std::vector<std::string> keys;
  std::vector<SweepKey> parts;
  for (std::size_t s = 0; s < scenario_idx.size(); ++s) {
    for (std::size_t c : controller_idx) {
      for (std::uint64_t seed : r.seeds) {
        parts.push_back({0, c, scenario_idx[s], seed});
        keys.push_back(sweepKeyText(spec, parts.back()));
      }
    }
  }
  prepareSweep(spec, keys, o.progress);
  r.calibration_s = seconds(start);

  const auto flights_start = std::chrono::steady_clock::now();
  std::vector<FlightJob> jobs;
  std::vector<std::unique_ptr<BeyondObserver>> observers;
  jobs.reserve(parts.size());
  for (std::size_t j = 0; j < parts.size(); ++j) {
    const SweepKey& k = parts[j];
    FlightScenario f = sweepFlightScenario(spec, k);
    const auto s = static_cast<std::size_t>(
        std::find(scenario_idx.begin(), scenario_idx.end(), k.scenario_index) - scenario_idx.begin());
    auto series = o.collect_series && k.seed == r.seeds.front()
                      ? std::make_unique<SeriesCollector>(expectedTicks(f), 4)
                      : nullptr;
    observers.push_back(std::make_unique<BeyondObserver>(r.scenarios[s].last_lap_from_s, std::move(series)));
    jobs.push_back({std::move(f), observers.back().get(), keys[j]});
  }
  if (o.progress != nullptr) {
    o.progress->message(fmt::format("flights: {} ({} scenarios × {} controllers × {} seeds)", jobs.size(),
                                    r.scenarios.size(), r.controllers.size(), r.seeds.size()));
  }
  const FlightProgress progress = [&o](std::size_t done, std::size_t total, const FlightJob& job,
                                       const FlightResult&) {
    if (o.progress != nullptr) o.progress->update(static_cast<double>(done), static_cast<double>(total), job.label);
  };
  r.threads = resolveThreads(o.jobs);
  const std::vector<FlightResult> results = runFlights(jobs, r.threads, progress);
  r.flights_s = seconds(flights_start);

  // Cells in scenario-major, then controller order; flights in seed order (the jobs' order).
  std::size_t j = 0;
  for (const auto& scn : r.scenarios) {
    for (const auto& ctl : r.controllers) {
      BeyondCell cell;
      cell.suite.case_name = scn.sweep.name;
      cell.suite.controller = ctl;
      for (std::uint64_t seed : r.seeds) {
        const FlightResult& fr = results[j];
        cell.suite.flights.push_back(toSuiteFlight(seed, fr));
        cell.extras.push_back({observers[j]->lastLapRmseCm(), fr.ground_contact, fr.min_obstacle_clearance_m});
        if (SeriesCollector* s = observers[j]->series()) r.series[{scn.sweep.name, ctl}] = s->take();
        r.simulated_s += fr.simulated_s;
        ++j;
      }
      r.cells.push_back(std::move(cell));
    }
  }
  r.flights = results.size();
  r.checks = beyondChecks(r);
  r.wall_s = seconds(start);
  return r;
}

// --- The checks ---------------------------------------------------------------------

namespace {

using Verdict = std::optional<std::pair<bool, std::string>>;

std::string ratioText(double v) { return std::isnan(v) ? "-" : fmt::format("{:.2f}×", v); }
std::string seedsText(int n) { return fmt::format("{} seed{}", n, n == 1 ? "" : "s"); }

/// `recommended` against `other` in one scenario: it passes when it struck on no seed where the
/// other finished and, on the seeds both finished, its mean all-RMSE is at most `bar` × the
/// other's; with no such seed, only when the other struck where it finished. The text says why.
std::pair<bool, std::string> against(const BeyondCell& rec, const BeyondCell& other, double bar) {
  const PairedComparison c = comparePaired(rec.suite, other.suite);
  const double ratio = c.a_rmse_all_cm / c.b_rmse_all_cm;
  const bool pass = c.atMost(bar) && (c.both_finished > 0 || c.only_b_struck > 0);
  std::string why;
  if (c.both_finished > 0) why = fmt::format("{} on {}", ratioText(ratio), seedsText(c.both_finished));
  const auto add = [&why](const std::string& part) { why += (why.empty() ? "" : "; ") + part; };
  if (c.only_b_struck > 0) add(fmt::format("{} struck on {} where recommended finished", other.controller(), seedsText(c.only_b_struck)));
  if (c.only_a_struck > 0) add(fmt::format("recommended struck on {} where {} finished", seedsText(c.only_a_struck), other.controller()));
  if (c.both_struck > 0) add(fmt::format("both struck on {}", seedsText(c.both_struck)));
  if (why.empty()) why = "no seed flown by both";
  return {pass, why};
}

/// One check over the scenarios: passes when every scenario it applies to passes, and is left
/// out (nullopt) when it applies to none of those flown.
template <class PerScenario>
std::optional<SuiteCheck> overScenarios(const BeyondResult& r, std::string name, std::string criterion,
                                        PerScenario per) {
  SuiteCheck chk{std::move(name), std::move(criterion), {}, true};
  int counted = 0;
  for (const auto& scn : r.scenarios) {
    const Verdict v = per(scn);
    if (!v) continue;
    ++counted;
    chk.pass = chk.pass && v->first;
    chk.value += fmt::format("{}{} {}{}", chk.value.empty() ? "" : "; ", scn.sweep.name, v->second,
                             v->first ? "" : " (FAIL)");
  }
  if (counted == 0) return std::nullopt;
  return chk;
}

Verdict noStrike(const BeyondResult& r, const BeyondScenario& s) {
  const BeyondCell* rec = r.cell(s.sweep.name, kBeyondRecommended);
  if (rec == nullptr) return std::nullopt;
  return std::pair{rec->suite.strikes() == 0, fmt::format("{}/{}", rec->suite.strikes(), rec->suite.flights.size())};
}

Verdict landing(const BeyondResult& r, const BeyondScenario& s) {
  const BeyondCell* rec = r.cell(s.sweep.name, kBeyondRecommended);
  if (s.kind != BeyondKind::kLanding || rec == nullptr) return std::nullopt;
  double worst_speed = 0.0, worst_bounce = 0.0;
  int touched = 0;
  bool pass = true;
  for (std::size_t i = 0; i < rec->extras.size(); ++i) {
    const auto& c = rec->extras[i].contact;
    const bool down = c && c->touched && std::isfinite(c->touchdown_speed_mps) && !rec->suite.flights[i].struck;
    pass = pass && down && c->touchdown_speed_mps <= 0.15 && c->bounce_m <= 0.01;
    if (!down) continue;
    ++touched;
    worst_speed = std::max(worst_speed, c->touchdown_speed_mps);
    worst_bounce = std::max(worst_bounce, c->bounce_m);
  }
  return std::pair{pass, fmt::format("touched down {}/{}, at ≤ {:.3f} m/s, bounce ≤ {:.1f} mm", touched,
                                     rec->extras.size(), worst_speed, 1e3 * worst_bounce)};
}

Verdict takeOff(const BeyondResult& r, const BeyondScenario& s) {
  const BeyondCell* rec = r.cell(s.sweep.name, kBeyondRecommended);
  if (s.kind != BeyondKind::kTakeOff || rec == nullptr) return std::nullopt;
  int lifted = 0, back = 0;
  double tilt = 0.0;
  for (std::size_t i = 0; i < rec->extras.size(); ++i) {
    const auto& c = rec->extras[i].contact;
    if (!c) continue;
    lifted += std::isfinite(c->liftoff_t_s) && !rec->suite.flights[i].struck ? 1 : 0;
    back += c->recontacts;
    tilt = std::max(tilt, c->max_tilt_on_ground_deg);
  }
  return std::pair{lifted == static_cast<int>(rec->extras.size()) && back == 0,
                   fmt::format("lifted off {}/{}, back down {}, tilt on the ground ≤ {:.1f}°", lifted,
                               rec->extras.size(), back, tilt)};
}

/// recommended+learn0 against recommended over the last lap, seed by seed.
Verdict adaptation(const BeyondResult& r, const BeyondScenario& s) {
  const BeyondCell* learn = r.cell(s.sweep.name, kBeyondLearning);
  const BeyondCell* rec = r.cell(s.sweep.name, kBeyondRecommended);
  if (s.laps < 2 || learn == nullptr || rec == nullptr) return std::nullopt;
  double a = 0.0, b = 0.0;
  int n = 0, struck = 0;
  for (std::size_t i = 0; i < learn->suite.flights.size(); ++i) {
    const SuiteFlight& x = learn->suite.flights[i];
    struck += x.struck ? 1 : 0;
    for (std::size_t k = 0; k < rec->suite.flights.size(); ++k) {
      const SuiteFlight& y = rec->suite.flights[k];
      if (y.seed != x.seed || x.struck || y.struck) continue;
      a += learn->extras[i].last_lap_rmse_cm;
      b += rec->extras[k].last_lap_rmse_cm;
      ++n;
    }
  }
  if (n == 0) return std::pair{false, fmt::format("no seed both finished{}", struck ? fmt::format(", {} struck", struck) : "")};
  const double ratio = a / b;
  return std::pair{struck == 0 && ratio <= 1.2,
                   fmt::format("{} ({:.2f} against {:.2f} cm on {}){}", ratioText(ratio), a / n, b / n,
                               seedsText(n), struck ? fmt::format(", {} struck", struck) : "")};
}

}  // namespace

std::vector<SuiteCheck> beyondChecks(const BeyondResult& r) {
  const auto versus = [&r](const char* other, double bar) {
    return [&r, other, bar](const BeyondScenario& s) -> Verdict {
      const BeyondCell* rec = r.cell(s.sweep.name, kBeyondRecommended);
      const BeyondCell* o = r.cell(s.sweep.name, other);
      if (rec == nullptr || o == nullptr) return std::nullopt;
      return against(*rec, *o, bar);
    };
  };
  const auto with = [&r](Verdict (*f)(const BeyondResult&, const BeyondScenario&)) {
    return [&r, f](const BeyondScenario& s) { return f(r, s); };
  };
  std::vector<SuiteCheck> checks;
  for (auto c : {overScenarios(r, "no strike", "recommended strikes on no seed of any scenario", with(noStrike)),
                 overScenarios(r, "vs the paper's configuration",
                               "all-RMSE of recommended ≤ 0.7× model:model_indi's in every scenario (a struck "
                               "flight ranks below every finished one; RMSE on the seeds both finished)",
                               versus(kBeyondPaper, 0.7)),
                 overScenarios(r, "vs INDI", "all-RMSE of recommended ≤ indi:none's in every scenario (same ranking)",
                               versus(kBeyondIndi, 1.0)),
                 overScenarios(r, "landing",
                               "recommended touches down on every seed at ≤ 0.15 m/s with no bounce above 1 cm",
                               with(landing)),
                 overScenarios(r, "take-off",
                               "recommended leaves the ground on every seed without a strike (a tip-over strikes a "
                               "rotor) and without coming back down; the tilt on the ground is reported",
                               with(takeOff)),
                 overScenarios(r, "adaptation from no model",
                               "last-lap all-RMSE of recommended+learn0 ≤ 1.2× recommended's (the "
                               "platform-identified F_G), on the seeds both finished, in every scenario of two "
                               "or more laps",
                               with(adaptation))}) {
    if (c) checks.push_back(std::move(*c));
  }
  return checks;
}

}  // namespace geaware::experiments
