// SPDX-License-Identifier: BSD-3-Clause
// Neural-Lander residual network: one predict_W (the controller calls it neural_iterations
// times per update) and one training epoch. Inputs cycle through 1024 samples of the synthetic
// ground-effect residual below (as in tests/neural), so the ReLU pattern varies as in flight.
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include <cmath>

#include <Eigen/Geometry>

#include "geaware/neural/trainer.hpp"

namespace {

using namespace geaware::neural;

/// Random flight condition near the ground (h 0.1–1.5 m, |v| ≤ 1 m/s, tilt ≤ 15°, 8–13 krpm).
geaware::control::ResidualFeatures sample(std::mt19937_64& rng) {
  const auto u = [&rng](double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
  };
  geaware::control::ResidualFeatures f;
  f.height_m = u(0.1, 1.5);
  f.v_W = {u(-1, 1), u(-1, 1), u(-1, 1)};
  f.q_WB = Eigen::AngleAxisd(u(0.0, 0.26), Eigen::Vector3d(u(-1, 1), u(-1, 1), 0).normalized());
  for (int i = 0; i < 4; ++i) f.rotor_speeds_rpm(i) = u(8000.0, 13000.0);
  return f;
}

/// Ground-effect thrust along z_B plus linear drag (paper vehicle's F_G and k_T).
TrainingSet makeSet(int rows, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  TrainingSet set;
  for (int i = 0; i < rows; ++i) {
    const auto f = sample(rng);
    const double thrust = 4.0083e-8 * f.rotor_speeds_rpm.squaredNorm();
    const double ratio = 7.339e-3 / (f.height_m * f.height_m + 1.804e-2);
    const Eigen::Vector3d force = ratio * thrust * (f.q_WB * Eigen::Vector3d::UnitZ()) -
                                  0.35 * Eigen::Vector3d(f.v_W.x(), f.v_W.y(), 0.0);
    static_cast<void>(set.add(f, force));
  }
  return set;
}

const std::vector<geaware::control::ResidualFeatures>& samples() {
  static const std::vector<geaware::control::ResidualFeatures> s = [] {
    std::mt19937_64 rng(1);
    std::vector<geaware::control::ResidualFeatures> out;
    for (int i = 0; i < 1024; ++i) out.push_back(sample(rng));
    return out;
  }();
  return s;
}

ResidualNetwork trained(std::vector<int> widths) {
  TrainOptions o;
  o.hidden_widths = std::move(widths);
  o.epochs = 2;
  o.lipschitz_gamma = 30.0;
  return ResidualNetwork(train(makeSet(1000, 1), o).weights);
}

void predict(benchmark::State& state, const std::vector<int>& widths) {
  const ResidualNetwork net = trained(widths);
  const auto& in = samples();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(net.predict_W(in[i++ & 1023]));
  }
}

void BM_PredictW_32x32(benchmark::State& state) { predict(state, {32, 32}); }
void BM_PredictW_64x64(benchmark::State& state) { predict(state, {64, 64}); }
BENCHMARK(BM_PredictW_32x32);
BENCHMARK(BM_PredictW_64x64);

void BM_TrainEpoch_3000Rows(benchmark::State& state) {
  const TrainingSet set = makeSet(3000, 2);
  TrainOptions o;
  o.epochs = 1;
  o.batch_size = 32;
  o.lipschitz_gamma = 30.0;
  for (auto _ : state) benchmark::DoNotOptimize(train(set, o));
}
BENCHMARK(BM_TrainEpoch_3000Rows)->Unit(benchmark::kMillisecond);

}  // namespace
