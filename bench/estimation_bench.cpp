// SPDX-License-Identifier: BSD-3-Clause
// Estimation layer: one ESKF IMU propagation, one delayed mocap update (fused at its capture
// time and re-propagated to now), and one lattice fit of a 16×16 frame.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "geaware/estimation/disturbance_observer.hpp"
#include "geaware/estimation/eskf.hpp"
#include "geaware/estimation/lattice_height.hpp"
#include "geaware/io/vehicle_file.hpp"

namespace {

using namespace geaware::estimation;
using Eigen::Quaterniond;
using Eigen::Vector3d;
using geaware::model::ImuSample;
using geaware::model::MocapSample;
using geaware::model::RangerFrame;

constexpr double kDt = 0.005;

/// A filter that has run 1 s of hover with poses `latency` old, so its buffer is full; the last
/// pose fused was captured at 0.99 s − latency.
Eskf& warmFilter(Eskf& f, double latency) {
  EskfState s;
  s.p_W = {0.0, 0.0, 1.0};
  f.initialise(s, 0.0);
  for (int k = 1; k <= 200; ++k) {
    ImuSample imu;
    imu.t_s = k * kDt;
    imu.accel_B = {0.01, -0.02, geaware::model::kGravity + 0.03};
    imu.gyro_B = {0.001, 0.002, -0.001};
    (void)f.addImu(imu);
    if (k % 2 == 0 && k < 200) {
      MocapSample m;
      m.t_s = imu.t_s - latency;
      m.p_W = s.p_W;
      (void)f.addMocap(m);
    }
  }
  return f;
}

void BM_EskfImuPropagation(benchmark::State& state) {
  Eskf f{EskfParams{}};
  warmFilter(f, 0.02);
  ImuSample imu;
  imu.t_s = f.output().t_s;
  imu.accel_B = {0.01, -0.02, geaware::model::kGravity + 0.03};
  imu.gyro_B = {0.001, 0.002, -0.001};
  for (auto _ : state) {
    imu.t_s += kDt;
    benchmark::DoNotOptimize(f.addImu(imu));
  }
}
BENCHMARK(BM_EskfImuPropagation);

/// One pose captured `latency` ago: propagate the buffered state to the capture time, gate,
/// update, re-propagate the latency's IMU samples. Capture times creep forward by 1 ns per
/// iteration so they stay increasing and inside the same IMU interval.
void BM_EskfMocapUpdate(benchmark::State& state) {
  const double latency = static_cast<double>(state.range(0)) * 1e-3;
  Eskf f{EskfParams{}};
  warmFilter(f, latency);
  const auto fused_before = f.counters().mocap_fused;
  MocapSample m;
  m.p_W = {0.0, 0.0, 1.0};
  m.t_s = f.output().t_s - latency - 0.0025;
  for (auto _ : state) {
    m.t_s += 1e-9;
    benchmark::DoNotOptimize(f.addMocap(m));
  }
  // Every iteration must be a real update (not an early rejection).
  if (f.counters().mocap_fused - fused_before != static_cast<std::uint64_t>(state.iterations())) {
    state.SkipWithError("a pose was not fused");
  }
}
BENCHMARK(BM_EskfMocapUpdate)->Arg(0)->Arg(20)->Arg(100);

/// 16×16 frame over flat ground with 1 cm noise and 20 % garbage zones, tilted vehicle.
RangerFrame frame(bool step) {
  RangerFrame f;
  f.side = 16;
  f.fov_rad = 45.0 * std::acos(-1.0) / 180.0;
  f.mount_B = {0.04, 0.0, -0.05};
  std::mt19937_64 rng(1);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::uniform_real_distribution<double> garbage(0.05, 3.0);
  std::bernoulli_distribution bad(0.2);
  const Quaterniond q(Eigen::AngleAxisd(0.1, Vector3d::UnitX()));
  const Vector3d o = Vector3d(-0.05, 0.0, 0.6) + q * f.mount_B;
  for (int i = 0; i < 16; ++i) {
    for (int j = 0; j < 16; ++j) {
      const Vector3d d = q * f.zoneDirection_B(i, j);
      double r = -o.z() / d.z();
      if (step && o.x() + r * d.x() > 0.0) r = (0.3 - o.z()) / d.z();  // table top beyond x = 0
      const auto k = static_cast<std::size_t>(f.index(i, j));
      f.valid[k] = true;
      f.range_m[k] = bad(rng) ? garbage(rng) : r + noise(rng);
    }
  }
  return f;
}

void BM_LatticeFit16x16(benchmark::State& state) {
  LatticeHeightParams p;
  p.diagonal_rotor_distance_m = 0.35;
  const LatticeHeightEstimator est(p);
  const RangerFrame f = frame(state.range(0) != 0);
  const Quaterniond q(Eigen::AngleAxisd(0.1, Vector3d::UnitX()));
  for (auto _ : state) benchmark::DoNotOptimize(est.estimate(f, q));
}
BENCHMARK(BM_LatticeFit16x16)->Arg(0)->Arg(1);  // 0: flat ground, 1: table edge

void BM_DisturbanceObserver(benchmark::State& state) {
  static const geaware::model::VehicleModel vehicle(geaware::io::builtinVehicle());
  DisturbanceObserver obs(vehicle, {});
  DisturbanceObserverInput in;
  in.accel_B = {0.1, 0.0, 9.8};
  in.gyro_B = {0.01, 0.02, 0.03};
  in.rotor_speeds_rpm = {10100, 10050, 9980, 10020};
  for (auto _ : state) {
    in.t_s += kDt;
    benchmark::DoNotOptimize(obs.update(in));
  }
}
BENCHMARK(BM_DisturbanceObserver);

}  // namespace
