// SPDX-License-Identifier: BSD-3-Clause
// Micro-benchmarks of the truth plant (issue 3, "Performance"):
//  - one plant step: RK4, per-rotor aerodynamics with ground effect, motors/battery, ground-strike
//    check (target ≤ 0.5 µs median). Arg 1: the default plant (ground-effect factors once per
//    step, held over the RK4 stages); 2: the same with them evaluated at every stage
//    (PlantConfig::ground_effect_per_stage); 0: the floor without aerodynamics and gravity;
//  - 60 s of simulated time at 1 kHz, throttles at hover, the plant alone over flat ground and
//    over a height map (what a height map costs the plant: per-rotor heights, normals and strike
//    checks). The whole loop with every sensor and the log is BM_FlightSensorsAndPlant
//    (flight_bench.cpp, target ≥ 1000× real time);
//  - one lattice-ranger ray over flat ground and over a height map.
// Results and commands: docs/benchmarks-sim.md. Run:
// build/bench/geaware_bench --benchmark_filter='Plant|BareRk4|RayCast' --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true

#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "geaware/model/vehicle_params.hpp"
#include "geaware/sim/plant.hpp"
#include "geaware/sim/rigs.hpp"
#include "geaware/sim/rotor_aerodynamics.hpp"
#include "geaware/sim/terrains.hpp"
#include "geaware/sim/truth_params.hpp"

namespace {

using geaware::sim::Plant;
using geaware::sim::PlantConfig;
using geaware::sim::PlantState;
using geaware::sim::TruthParams;

/// The paper's quadrotor (config/vehicles/paper_quad.yaml), spelled out so that the benchmark
/// needs only the sim library.
geaware::model::VehicleParams paperQuad() {
  geaware::model::VehicleParams v;
  v.name = "paper_quad";
  v.mass_kg = 1.696;
  v.inertia_kgm2 = Eigen::Vector3d(0.00745220, 0.00792752, 0.01249522);
  v.diagonal_rotor_distance_m = 0.35;
  v.propeller_radius_m = 0.089;
  v.min_rotor_plane_height_m = 0.072;
  v.rotor = {4.0083e-8, 4.678e-8, 3.588e-8, 6.3859e-10, 1.0556e-4};
  v.throttle = {-1.448471e8, 5.228928e8, 1.033111e7};
  return v;
}

double hoverRpm(const TruthParams& p) {
  return std::sqrt(p.mass_kg * p.gravity_mps2 / (4.0 * p.k_T_N_per_rpm2));
}

Plant makePlant(std::shared_ptr<const geaware::sim::Terrain> terrain, double height_m,
                const PlantConfig& cfg = {}) {
  const TruthParams p = geaware::sim::fromNominal(paperQuad());
  PlantState s0;
  s0.p_W = Eigen::Vector3d(0.0, 0.0, height_m);
  const double n = hoverRpm(p);
  s0.n_rpm = {n, n, n, n};
  return Plant(p, std::move(terrain), cfg, s0);
}

/// A gently rolling 10 m × 10 m height map (5 cm cells), centred on the origin.
std::shared_ptr<const geaware::sim::Terrain> rollingHeightMap() {
  std::vector<std::vector<double>> rows(201, std::vector<double>(201));
  for (int j = 0; j < 201; ++j) {
    for (int i = 0; i < 201; ++i) {
      rows[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)] =
          0.05 * std::sin(0.7 * i * 0.05) * std::cos(0.4 * j * 0.05);
    }
  }
  return std::make_shared<geaware::sim::HeightMap>(-5.0, -5.0, 0.05, rows);
}

/// One step at 0.3 m over flat ground (ground effect active on every rotor). The vehicle is put
/// back every 1,000 steps (untimed) so that it stays near the ground.
void BM_PlantStep(benchmark::State& state) {
  const auto ground = std::make_shared<geaware::sim::FlatGround>(0.0);
  PlantConfig cfg;
  if (state.range(0) == 0) {
    // The floor: RK4 + motors + contribution plumbing, weightless so that it does not fall.
    cfg.rotor_aerodynamics = false;
    cfg.gravity = false;
  }
  cfg.ground_effect_per_stage = state.range(0) == 2;
  Plant plant = makePlant(ground, 0.3, cfg);
  double t = plant.throttleForSteadySpeed(hoverRpm(plant.params()));
  const std::array<double, 4> throttle{t, t, t, t};
  int k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(plant.step(throttle));
    if (++k == 1000) {
      state.PauseTiming();
      plant = makePlant(ground, 0.3, cfg);
      k = 0;
      state.ResumeTiming();
    }
  }
  state.SetLabel(!cfg.rotor_aerodynamics       ? "floor: no aerodynamics, no gravity"
                 : cfg.ground_effect_per_stage ? "full plant, ground effect per RK4 stage"
                                               : "full plant");
}
BENCHMARK(BM_PlantStep)->Arg(1)->Arg(2)->Arg(0);

/// One call of the rotor aerodynamics (ground effect per rotor, tilt, drag) with one rotor at
/// 0.12 m and the others near 0.15 m: the plant calls it four times per step (RK4). Budget
/// < 100 ns (formerly a timed unit test; timings belong here).
void BM_RotorAeroCompute(benchmark::State& state) {
  using namespace geaware::sim;
  const RotorAerodynamics aero(rigGeometry(paperQuad()), RotorAeroParams{});
  RotorSurroundings s;
  for (std::size_t i = 0; i < 4; ++i) {
    s.ground_distance_m[i] = i == 0 ? 0.12 : 0.15;
    s.ground_normal_W[i] = Eigen::Vector3d::UnitZ();
  }
  const Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  double h = 0.15;
  for (auto _ : state) {
    h = h < 0.16 ? h + 1e-7 : 0.15;
    s.ground_distance_m[1] = h;
    benchmark::DoNotOptimize(aero.compute({10000.0, 10100.0, 9900.0, 10050.0}, R,
                                          Eigen::Vector3d(1.0, 0.5, 0.0),
                                          Eigen::Vector3d(0.1, 0.2, 0.3), s));
  }
}
BENCHMARK(BM_RotorAeroCompute);

/// The reference floor the issue quotes: a bare 13-state RK4 step of a rigid body under
/// gravity and a constant body wrench (no motors, no terrain, no contributions).
void BM_BareRk4Step(benchmark::State& state) {
  const geaware::sim::MassProperties mass(1.696,
                                          Eigen::Vector3d(0.0075, 0.0079, 0.0125).asDiagonal());
  geaware::sim::RigidBodyState x;
  x.w_B = Eigen::Vector3d(0.1, 0.2, 0.3);
  geaware::sim::Wrench thrust;
  thrust.force_B.z() = 1.696 * 9.81;
  thrust.torque_B.x() = 1e-3;
  double t = 0.0;
  for (auto _ : state) {
    x = geaware::sim::rk4Step(x, t, 1e-3, [&](double, const geaware::sim::RigidBodyState& s) {
      const Eigen::Matrix3d R = s.q_WB.normalized().toRotationMatrix();
      geaware::sim::Wrench w = thrust;
      w.force_B -= R.row(2).transpose() * (1.696 * 9.81);
      return geaware::sim::rigidBodyDerivative(s, R, w, mass);
    });
    t += 1e-3;
    benchmark::DoNotOptimize(x);
  }
}
BENCHMARK(BM_BareRk4Step);

/// 60 s at 1 kHz at hover, 2 m over the terrain. The hover throttle is re-derived from the
/// battery's state every 100 ms (open loop: the throttle follows the battery, not the position).
void flySixtySeconds(benchmark::State& state,
                     const std::shared_ptr<const geaware::sim::Terrain>& terrain) {
  for (auto _ : state) {
    Plant plant = makePlant(terrain, 2.0);
    const double n = hoverRpm(plant.params());
    std::array<double, 4> throttle{};
    for (int k = 0; k < 60000; ++k) {
      if (k % 100 == 0) throttle.fill(plant.throttleForSteadySpeed(n));
      if (plant.step(throttle).crash) {
        state.SkipWithError("crashed during the hover benchmark");
        break;
      }
    }
    benchmark::DoNotOptimize(plant.state());
  }
  state.counters["x_real_time"] =
      benchmark::Counter(60.0, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_PlantHover60sFlat(benchmark::State& state) {
  flySixtySeconds(state, std::make_shared<geaware::sim::FlatGround>(0.0));
}
BENCHMARK(BM_PlantHover60sFlat)->Unit(benchmark::kMillisecond);

void BM_PlantHover60sHeightMap(benchmark::State& state) {
  flySixtySeconds(state, rollingHeightMap());
}
BENCHMARK(BM_PlantHover60sHeightMap)->Unit(benchmark::kMillisecond);

/// One downward ray (within a 45° cone, as a lattice ranger's) from 0.3 m: the closed form on
/// flat ground and the exact cell walk on the rolling height map.
void rayCasts(benchmark::State& state, const geaware::sim::Terrain& terrain) {
  std::vector<Eigen::Vector3d> dirs;
  for (int j = 0; j < 16; ++j) {
    for (int i = 0; i < 16; ++i) {
      const double ax = (i - 7.5) / 7.5 * 0.39;  // ±22.5° about each axis
      const double ay = (j - 7.5) / 7.5 * 0.39;
      dirs.push_back(Eigen::Vector3d(std::tan(ax), std::tan(ay), -1.0).normalized());
    }
  }
  const Eigen::Vector3d origin(0.3, -0.2, 0.3);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(terrain.rayCast(origin, dirs[k], 4.0));
    k = (k + 1) % dirs.size();
  }
}
void BM_RayCastFlat(benchmark::State& state) { rayCasts(state, geaware::sim::FlatGround(0.0)); }
BENCHMARK(BM_RayCastFlat);
void BM_RayCastHeightMap(benchmark::State& state) { rayCasts(state, *rollingHeightMap()); }
BENCHMARK(BM_RayCastHeightMap);

}  // namespace
