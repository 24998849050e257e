// SPDX-License-Identifier: BSD-3-Clause
// Micro-benchmarks of the controller-side model functions. Inputs vary per iteration (a sweep
// over heights) so the compiler cannot hoist the work out of the loop.
#include <Eigen/Geometry>
#include <benchmark/benchmark.h>

#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace {

const geaware::model::VehicleModel& vehicle() {
  static const geaware::model::VehicleModel v(geaware::io::builtinVehicle());
  return v;
}

/// Heights cycling through 0.05–2.05 m, so table look-ups take every branch.
double heightAt(std::size_t i) { return 0.05 + 0.001 * static_cast<double>(i % 2000); }

void BM_ThrustRatio(benchmark::State& state) {
  const auto& ge = vehicle().groundEffect();
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(ge.thrustRatio(heightAt(i++)));
}
BENCHMARK(BM_ThrustRatio);

void BM_LevelingInertia(benchmark::State& state) {
  const auto& ge = vehicle().groundEffect();
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(ge.levelingInertiaDiagonal(heightAt(i++)));
}
BENCHMARK(BM_LevelingInertia);

void BM_LevelingTorque(benchmark::State& state) {
  const auto& ge = vehicle().groundEffect();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.2, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(ge.levelingTorque_B(R, heightAt(i++), 16.0));
}
BENCHMARK(BM_LevelingTorque);

void BM_DragTable(benchmark::State& state) {
  const auto& drag = vehicle().drag();
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(drag.coefficients(heightAt(i++)));
}
BENCHMARK(BM_DragTable);

void BM_MixerInverse(benchmark::State& state) {
  const auto& mixer = vehicle().mixer();
  Eigen::Vector4d w(16.6, 0.01, -0.02, 0.003);
  for (auto _ : state) {
    w.x() += 1e-9;
    benchmark::DoNotOptimize(mixer.squaredSpeeds(w));
  }
}
BENCHMARK(BM_MixerInverse);

void BM_ThrottleInverse(benchmark::State& state) {
  const auto& curve = vehicle().throttleCurve();
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(curve.throttle(5000.0 + static_cast<double>(i++ % 14000)));
}
BENCHMARK(BM_ThrottleInverse);

}  // namespace
