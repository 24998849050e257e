// SPDX-License-Identifier: BSD-3-Clause
// Micro-benchmarks of the flat map (issue target: full map with ground-effect terms, to rotor
// speeds, ≤ 150 ns median). Inputs are 1024 precomputed samples of the paper's 3 m/s
// lemniscate, so trajectory evaluation is not part of the measurement.
#include <vector>

#include <benchmark/benchmark.h>

#include "geaware/flatness/flat_map.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/traj/lemniscate.hpp"

namespace {

using geaware::flatness::FlatMap;
using geaware::flatness::GroundEffectTerms;

const geaware::model::VehicleModel& vehicle() {
  static const geaware::model::VehicleModel v(geaware::io::builtinVehicle());
  return v;
}

const std::vector<geaware::traj::FlatOutput>& samples() {
  static const std::vector<geaware::traj::FlatOutput> s = [] {
    const geaware::traj::Lemniscate traj{geaware::traj::LemniscateParams{}};
    std::vector<geaware::traj::FlatOutput> out;
    for (int i = 0; i < 1024; ++i) out.push_back(traj.sample(traj.duration() * i / 1024.0));
    return out;
  }();
  return s;
}

void runFlatMap(benchmark::State& state, GroundEffectTerms terms) {
  const FlatMap map(vehicle(), terms);
  const auto& refs = samples();
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& r = refs[i++ & 1023];
    benchmark::DoNotOptimize(map.evaluate(r, r.p_W.z()));
  }
}

void BM_FlatMapGroundEffect(benchmark::State& state) { runFlatMap(state, GroundEffectTerms::all()); }
BENCHMARK(BM_FlatMapGroundEffect);

void BM_FlatMapPlainDragAware(benchmark::State& state) { runFlatMap(state, GroundEffectTerms::none()); }
BENCHMARK(BM_FlatMapPlainDragAware);

void BM_LemniscateSample(benchmark::State& state) {
  const geaware::traj::Lemniscate traj{geaware::traj::LemniscateParams{}};
  double t = 0.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(traj.sample(t));
    t = t > 12.0 ? 0.0 : t + 1e-3;
  }
}
BENCHMARK(BM_LemniscateSample);

}  // namespace
