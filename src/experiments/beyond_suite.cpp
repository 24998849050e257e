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

BeyondScenario describe(const SweepScenario& s) {
  BeyondScenario b;
  b.sweep = s;
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

int BeyondCell::strikes() const noexcept {
  return static_cast<int>(std::count_if(flights.begin(), flights.end(),
                                        [](const BeyondFlight& f) { return f.suite.struck; }));
}

double BeyondCell::meanFinished(double SuiteFlight::*metric) const noexcept {
  double sum = 0.0;
  int n = 0;
  for (const auto& f : flights) {
    if (f.suite.struck) continue;
    sum += f.suite.*metric;
    ++n;
  }
  return n == 0 ? kNaN : sum / n;
}

const BeyondCell* BeyondResult::cell(const std::string& scenario,
                                     const std::string& controller) const noexcept {
  for (const auto& c : cells) {
    if (c.scenario == scenario && c.controller == controller) return &c;
  }
  return nullptr;
}

BeyondComparison compareBeyond(const BeyondCell& first, const BeyondCell& second,
                               double SuiteFlight::*metric) {
  BeyondComparison c;
  double a = 0.0, b = 0.0;
  for (const auto& f : first.flights) {
    const auto g = std::find_if(second.flights.begin(), second.flights.end(),
                                [&](const BeyondFlight& x) { return x.suite.seed == f.suite.seed; });
    if (g == second.flights.end()) continue;
    if (f.suite.struck && !g->suite.struck) ++c.only_first_struck;
    if (!f.suite.struck && g->suite.struck) ++c.only_second_struck;
    if (f.suite.struck || g->suite.struck) continue;
    a += f.suite.*metric;
    b += g->suite.*metric;
    ++c.both_finished;
  }
  c.first_rmse_cm = c.both_finished == 0 ? kNaN : a / c.both_finished;
  c.second_rmse_cm = c.both_finished == 0 ? kNaN : b / c.both_finished;
  return c;
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
  const auto scenario_idx = pickIndices(spec.scenarios, o.scenarios, "scenario",
                                        [](const SweepScenario& s) { return s.name; });
  const auto controller_idx = pickIndices(spec.controllers, o.controllers, "controller",
                                          [](const SuiteController& c) { return c.name; });
  for (std::size_t i : scenario_idx) r.scenarios.push_back(describe(spec.scenarios[i]));
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
      BeyondCell cell{scn.sweep.name, ctl, {}};
      for (std::uint64_t seed : r.seeds) {
        const FlightResult& fr = results[j];
        BeyondFlight f;
        f.suite = toSuiteFlight(seed, fr);
        f.last_lap_rmse_cm = observers[j]->lastLapRmseCm();
        f.contact = fr.ground_contact;
        f.min_obstacle_clearance_m = fr.min_obstacle_clearance_m;
        if (SeriesCollector* s = observers[j]->series()) r.series[{scn.sweep.name, ctl}] = s->take();
        r.simulated_s += fr.simulated_s;
        cell.flights.push_back(std::move(f));
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

// --- The checks ----------------------------------------------------------------------

namespace {

std::string ratioText(double v) { return std::isnan(v) ? "-" : fmt::format("{:.2f}×", v); }

/// `recommended` against `other` in one scenario: it passes when it struck on no seed where the
/// other finished and, on the seeds both finished, its mean all-RMSE is at most `bar` × the
/// other's. The text says why.
std::pair<bool, std::string> against(const BeyondCell& rec, const BeyondCell& other, double bar) {
  const BeyondComparison c = compareBeyond(rec, other);
  std::string why;
  bool pass = c.only_first_struck == 0;
  if (c.both_finished > 0) {
    pass = pass && c.ratio() <= bar;
    why = fmt::format("{} on {} seed{}", ratioText(c.ratio()), c.both_finished, c.both_finished == 1 ? "" : "s");
  }
  if (c.only_second_struck > 0) {
    why += fmt::format("{}{} struck on {} seed{} where recommended finished", why.empty() ? "" : "; ",
                       other.controller, c.only_second_struck, c.only_second_struck == 1 ? "" : "s");
  }
  if (c.only_first_struck > 0) {
    why += fmt::format("{}recommended struck on {} seed{} where {} finished", why.empty() ? "" : "; ",
                       c.only_first_struck, c.only_first_struck == 1 ? "" : "s", other.controller);
  }
  if (why.empty()) why = "no seed to compare";
  return {pass, why};
}

/// One check over the scenarios: passes when every scenario passes; the value lists each.
template <class PerScenario>
SuiteCheck overScenarios(const BeyondResult& r, std::string name, std::string criterion, PerScenario per) {
  SuiteCheck chk{std::move(name), std::move(criterion), {}, true};
  int counted = 0;
  for (const auto& scn : r.scenarios) {
    const auto v = per(scn);
    if (!v) continue;
    ++counted;
    chk.pass = chk.pass && v->first;
    chk.value += fmt::format("{}{} {}{}", chk.value.empty() ? "" : "; ", scn.sweep.name, v->second,
                             v->first ? "" : " (FAIL)");
  }
  if (counted == 0) {
    chk.pass = false;
    chk.value = "not flown (the scenarios or controllers it needs were left out)";
  }
  return chk;
}

}  // namespace

std::vector<SuiteCheck> beyondChecks(const BeyondResult& r) {
  using Verdict = std::optional<std::pair<bool, std::string>>;
  std::vector<SuiteCheck> checks;
  checks.push_back(overScenarios(r, "no strike", "recommended strikes on no seed of any scenario",
                                 [&](const BeyondScenario& s) -> Verdict {
                                   const BeyondCell* rec = r.cell(s.sweep.name, kBeyondRecommended);
                                   if (rec == nullptr) return std::nullopt;
                                   return std::pair{rec->strikes() == 0,
                                                    fmt::format("{}/{}", rec->strikes(), rec->flights.size())};
                                 }));
  const auto versus = [&](const char* other, double bar) {
    return [&r, other, bar](const BeyondScenario& s) -> Verdict {
      const BeyondCell* rec = r.cell(s.sweep.name, kBeyondRecommended);
      const BeyondCell* o = r.cell(s.sweep.name, other);
      if (rec == nullptr || o == nullptr) return std::nullopt;
      return against(*rec, *o, bar);
    };
  };
  checks.push_back(overScenarios(
      r, "vs the paper's configuration",
      "all-RMSE of recommended ≤ 0.7× model:model_indi's in every scenario (a struck flight ranks "
      "below every finished one; RMSE on the seeds both finished)",
      versus(kBeyondPaper, 0.7)));
  checks.push_back(overScenarios(r, "vs INDI",
                                 "all-RMSE of recommended ≤ indi:none's in every scenario (same ranking)",
                                 versus(kBeyondIndi, 1.0)));
  checks.push_back(overScenarios(
      r, "landing", "recommended touches down at ≤ 0.15 m/s with no bounce above 1 cm, every seed",
      [&](const BeyondScenario& s) -> Verdict {
        const BeyondCell* rec = r.cell(s.sweep.name, kBeyondRecommended);
        if (s.kind != BeyondKind::kLanding || rec == nullptr) return std::nullopt;
        double worst_speed = 0.0, worst_bounce = 0.0;
        bool pass = true;
        for (const auto& f : rec->flights) {
          const bool touched = f.contact && f.contact->touched && std::isfinite(f.contact->touchdown_speed_mps);
          pass = pass && touched && !f.suite.struck && f.contact->touchdown_speed_mps <= 0.15 &&
                 f.contact->bounce_m <= 0.01;
          if (touched) {
            worst_speed = std::max(worst_speed, f.contact->touchdown_speed_mps);
            worst_bounce = std::max(worst_bounce, f.contact->bounce_m);
          }
        }
        return std::pair{pass, fmt::format("touchdown ≤ {:.3f} m/s, bounce ≤ {:.1f} mm", worst_speed,
                                           1e3 * worst_bounce)};
      }));
  checks.push_back(overScenarios(
      r, "take-off", "recommended leaves the ground on every seed, without a strike or a return to the ground",
      [&](const BeyondScenario& s) -> Verdict {
        const BeyondCell* rec = r.cell(s.sweep.name, kBeyondRecommended);
        if (s.kind != BeyondKind::kTakeOff || rec == nullptr) return std::nullopt;
        int lifted = 0, back = 0;
        double tilt = 0.0;
        for (const auto& f : rec->flights) {
          if (!f.contact) continue;
          lifted += std::isfinite(f.contact->liftoff_t_s) && !f.suite.struck ? 1 : 0;
          back += f.contact->recontacts;
          tilt = std::max(tilt, f.contact->max_tilt_on_ground_deg);
        }
        const bool pass = lifted == static_cast<int>(rec->flights.size()) && back == 0;
        return std::pair{pass, fmt::format("lifted off {}/{}, back down {}, tilt on the ground ≤ {:.1f}°", lifted,
                                           rec->flights.size(), back, tilt)};
      }));
  checks.push_back(overScenarios(
      r, "adaptation from no model",
      "last-lap all-RMSE of recommended+learn0 ≤ 1.2× recommended's (the vehicle file's F_G), on the "
      "seeds both finished, in every scenario of two or more laps",
      [&](const BeyondScenario& s) -> Verdict {
        const BeyondCell* learn = r.cell(s.sweep.name, kBeyondLearning);
        const BeyondCell* rec = r.cell(s.sweep.name, kBeyondRecommended);
        if (s.laps < 2 || learn == nullptr || rec == nullptr) return std::nullopt;
        double a = 0.0, b = 0.0;
        int n = 0, struck = 0;
        for (std::size_t i = 0; i < learn->flights.size() && i < rec->flights.size(); ++i) {
          const BeyondFlight& x = learn->flights[i];
          const BeyondFlight& y = rec->flights[i];
          struck += x.suite.struck ? 1 : 0;
          if (x.suite.struck || y.suite.struck) continue;
          a += x.last_lap_rmse_cm;
          b += y.last_lap_rmse_cm;
          ++n;
        }
        const double ratio = n == 0 ? kNaN : a / b;
        return std::pair{struck == 0 && n > 0 && ratio <= 1.2,
                         fmt::format("{} ({:.2f} against {:.2f} cm on {} seeds){}", ratioText(ratio), a / n,
                                     b / n, n, struck ? fmt::format(", {} struck", struck) : "")};
      }));
  return checks;
}

}  // namespace geaware::experiments
