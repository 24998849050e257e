// SPDX-License-Identifier: BSD-3-Clause
// Micro-benchmarks of the simulated sensors (issue 3, "Performance"): one 16×16 lattice-ranger
// frame over flat ground and over a height map, one sample of each other sensor, and one
// SensorSuite step at the plant rate (what the 1 kHz loop pays on average per step).
// Run: build/bench/geaware_bench --benchmark_filter='Ranger|Sensor|Imu|Mocap|Telemetry|Normal'
//      --benchmark_repetitions=5 --benchmark_report_aggregates_only=true

#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>
#include <Eigen/Geometry>

#include "geaware/sim/sensors.hpp"
#include "geaware/sim/terrains.hpp"

namespace {

using geaware::sim::PlantState;

/// Hovering at 0.18 m (the paper's exp 7), slightly tilted, so the rays are not symmetric.
PlantState hover(double t_s = 0.0) {
  PlantState s;
  s.t_s = t_s;
  s.p_W = Eigen::Vector3d(0.4, -0.3, 0.18);
  s.q_WB = Eigen::AngleAxisd(0.05, Eigen::Vector3d(1.0, 1.0, 0.0).normalized());
  s.n_rpm = {10'000.0, 10'000.0, 10'000.0, 10'000.0};
  return s;
}

/// A 4 m × 4 m height map with 5 cm cells and a few centimetres of bumps.
geaware::sim::HeightMap bumpyMap() {
  const int n = 81;
  std::vector<std::vector<double>> z(n, std::vector<double>(n));
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) z[j][i] = 0.03 * std::sin(0.7 * i) * std::cos(0.5 * j);
  }
  return geaware::sim::HeightMap(-2.0, -2.0, 0.05, z);
}

void BM_RangerFrameFlatGround(benchmark::State& st) {
  const geaware::sim::FlatGround ground(0.0);
  geaware::sim::LatticeRanger ranger(geaware::sim::RangerParams{}, 1);
  const PlantState s = hover();
  for (auto _ : st) benchmark::DoNotOptimize(ranger.measure(s, &ground));
}
BENCHMARK(BM_RangerFrameFlatGround);

void BM_RangerFrameTiltedPlane(benchmark::State& st) {
  const auto plane = geaware::sim::TiltedPlane::fromTilt(Eigen::Vector3d::Zero(), 0.0, 0.2);
  geaware::sim::LatticeRanger ranger(geaware::sim::RangerParams{}, 1);
  const PlantState s = hover();
  for (auto _ : st) benchmark::DoNotOptimize(ranger.measure(s, &plane));
}
BENCHMARK(BM_RangerFrameTiltedPlane);

void BM_RangerFrameHeightMap(benchmark::State& st) {
  const geaware::sim::HeightMap map = bumpyMap();
  geaware::sim::LatticeRanger ranger(geaware::sim::RangerParams{}, 1);
  const PlantState s = hover();
  for (auto _ : st) benchmark::DoNotOptimize(ranger.measure(s, &map));
}
BENCHMARK(BM_RangerFrameHeightMap);

/// Times `sample(hover(t))` with t advancing by `dt_s` per iteration, so that a sensor whose
/// rate is 1/dt_s is due at every call.
template <typename Sample>
void sampleAlongHover(benchmark::State& st, double dt_s, Sample&& sample) {
  double t = 0.0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(sample(hover(t)));
    t += dt_s;
  }
}

void BM_ImuSample(benchmark::State& st) {
  geaware::sim::ImuParams p;
  p.rate_Hz = 1e5;
  geaware::sim::Imu imu(p, 1);
  sampleAlongHover(st, 1e-5, [&imu](const PlantState& s) { return imu.sample(s); });
}
BENCHMARK(BM_ImuSample);

void BM_MocapStep(benchmark::State& st) {
  geaware::sim::MocapParams p;
  p.rate_Hz = 1000.0;  // a capture and a delivery at every call
  geaware::sim::Mocap mocap(p, 1);
  sampleAlongHover(st, 1e-3, [&mocap](const PlantState& s) { return mocap.step(s); });
}
BENCHMARK(BM_MocapStep);

void BM_RotorTelemetrySample(benchmark::State& st) {
  geaware::sim::RotorTelemetryParams p;
  p.rate_Hz = 1e5;
  geaware::sim::RotorTelemetrySensor tel(p, 1);
  sampleAlongHover(st, 1e-5, [&tel](const PlantState& s) { return tel.sample(s); });
}
BENCHMARK(BM_RotorTelemetrySample);

/// The average cost per 1 kHz plant step of all sensors at their default rates (IMU 200 Hz,
/// mocap 100 Hz, telemetry 200 Hz, 16×16 ranger 100 Hz) over flat ground.
void BM_SensorSuiteStepAt1kHz(benchmark::State& st) {
  const geaware::sim::FlatGround ground(0.0);
  geaware::sim::SensorSuite suite(geaware::sim::SensorSuiteParams{}, 1);
  long k = 0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(suite.step(hover(static_cast<double>(k) * 1e-3), &ground));
    ++k;
  }
}
BENCHMARK(BM_SensorSuiteStepAt1kHz);

void BM_NormalDraw(benchmark::State& st) {
  geaware::sim::NoiseSource noise(1, 2);
  for (auto _ : st) benchmark::DoNotOptimize(noise.normal());
}
BENCHMARK(BM_NormalDraw);

}  // namespace
