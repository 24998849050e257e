// SPDX-License-Identifier: BSD-3-Clause
// Benchmarks of the closed-loop flight runner (experiments/flight.hpp), 60 s of simulated time
// at the plant's 1 kHz with every sensor (IMU 200 Hz, motion capture 100 Hz, rotor telemetry
// 200 Hz, 16×16 lattice ranger at 100 Hz) over flat ground, the log streamed to a temporary
// CSV file (one row per 200 Hz control tick):
//  - BM_FlightSensorsAndPlant: the plant and the sensors only, throttles held at the truth's
//    hover throttle at 1 m (battery sag and turbulence off, so that the open-loop hover holds
//    for the whole minute). Target: ≥ 1000× real time.
//  - BM_FlightClosedLoop: the full loop (ESKF, lattice height, controller) flying four laps of
//    the ±1.5 m × ±0.8 m lemniscate at 0.5 m and 1 m/s peak, turbulence and battery on.
// The counter "x_real_time" is simulated seconds per wall second of the loop (set-up and
// validation excluded), "x_real_time_cpu" per CPU second of the whole iteration. Argument 1: with
// the log (the figure to quote); 0: without, to show what the log costs. BM_FlightClosedLoop's
// second argument: 0 the ideal world (the vehicle file's own), 1 the as-built world. Run:
// build/bench/geaware_bench --benchmark_filter=Flight --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "geaware/experiments/world_setup.hpp"
#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/flight_log.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/traj/lemniscate.hpp"
#include "geaware/traj/min_snap.hpp"

namespace {

using geaware::experiments::CsvFlightLog;
using geaware::experiments::FlightResult;
using geaware::experiments::FlightScenario;

constexpr double kSimulatedSeconds = 60.0;

std::filesystem::path logFile() {
  return std::filesystem::temp_directory_path() /
         ("geaware_flight_bench_" + std::to_string(::getpid()) + ".csv");
}

/// Flies `s` once per iteration; with the log when state.range(0) is 1.
void fly(benchmark::State& state, const FlightScenario& s) {
  const auto file = logFile();
  const bool with_log = state.range(0) != 0;
  double simulated = 0.0;
  double wall = 0.0;
  for (auto _ : state) {
    std::unique_ptr<CsvFlightLog> log;
    if (with_log) log = std::make_unique<CsvFlightLog>(file, s.vehicle);
    const FlightResult r = geaware::experiments::runFlight(s, log.get());
    if (r.crash) {
      state.SkipWithError(("crashed: " + r.crash_description).c_str());
      break;
    }
    simulated += r.simulated_s;
    wall += r.wall_s;
    benchmark::DoNotOptimize(r.tracking.rmse_all_m);
  }
  std::filesystem::remove(file);
  state.counters["x_real_time"] = wall > 0.0 ? simulated / wall : 0.0;
  // The same per CPU second of the whole iteration (set-up included): steadier than the wall
  // clock on a machine shared with other jobs.
  state.counters["x_real_time_cpu"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
}

void BM_FlightSensorsAndPlant(benchmark::State& state) {
  FlightScenario s;
  s.vehicle = geaware::io::builtinVehicle();
  geaware::sim::TruthParams truth = geaware::sim::fromNominal(s.vehicle);
  truth.battery.enabled = false;  // the ESC curve holds exactly: the hover throttle holds
  s.truth = truth;
  s.disturbances.turbulence = false;
  s.loop = geaware::experiments::LoopMode::kOpenLoopHover;
  s.start_hover_s = 0.0;
  const Eigen::Vector3d p(0.0, 0.0, 1.0);
  s.trajectory = std::make_shared<geaware::traj::MinSnapTrajectory>(
      std::vector<geaware::traj::Waypoint>{{p, 0.0}, {p, 0.0}},
      std::vector<double>{kSimulatedSeconds});
  fly(state, s);
}
BENCHMARK(BM_FlightSensorsAndPlant)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

/// Argument 1 of BM_FlightClosedLoop: the world flown in.
enum World : std::int64_t { kIdealWorld = 0, kAsBuiltWorld = 1 };

void BM_FlightClosedLoop(benchmark::State& state) {
  FlightScenario s;
  s.vehicle = geaware::io::builtinVehicle();
  // model:model with a yaw rate gain of 2/s: the incremental torque variants diverge in yaw
  // until the controller models the rotor-inertia reaction (docs/closed-loop.md).
  s.controller.acceleration = geaware::control::AccelerationCompensation::kModel;
  s.controller.torque = geaware::control::TorqueCompensation::kModel;
  s.controller.k_w_per_s.z() = 2.0;
  geaware::traj::LemniscateParams lp;
  lp.half_extent_x_m = 1.5;
  lp.half_extent_y_m = 0.8;
  lp.height_m = 0.5;
  lp.peak_speed_mps = 1.0;
  lp.laps = 4;
  s.trajectory = std::make_shared<geaware::traj::Lemniscate>(lp);
  // Hover at the start for whatever the four laps leave of the minute.
  s.start_hover_s = std::max(0.0, kSimulatedSeconds - s.trajectory->duration());
  // The ideal world is the vehicle file's own (sim::fromNominal, the runner's default for a
  // scenario without a truth); the as-built world adds every effect of docs/world.md.
  if (state.range(1) == kAsBuiltWorld) {
    geaware::experiments::applyWorld(
        s, geaware::experiments::defaultWorld(s.vehicle, true, "built-in"));
  }
  state.SetLabel(state.range(1) == kAsBuiltWorld ? "as-built world" : "ideal world");
  fly(state, s);
}
BENCHMARK(BM_FlightClosedLoop)
    ->Args({1, kIdealWorld})
    ->Args({0, kIdealWorld})
    ->Args({1, kAsBuiltWorld})
    ->Args({0, kAsBuiltWorld})
    ->Unit(benchmark::kMillisecond);

}  // namespace
