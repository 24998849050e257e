// SPDX-License-Identifier: BSD-3-Clause
// Throughput of identification: 10⁶ quadrotor-platform samples (half level board with mixing
// experiments, half tilted board) parsed from CSV and fitted. Targets: parse + fit in ≤ 3 s
// (issue 5), ≤ 0.5 s (issue 15; met with --ground-effect table only). The log is generated once, in the temporary directory, from the controller-side model
// of the built-in vehicle with Gaussian sensor noise. Results: docs/identification.md.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include <benchmark/benchmark.h>

#include "geaware/ident/fits.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/ground_effect.hpp"
#include "geaware/model/mixer.hpp"
#include "geaware/model/units.hpp"

namespace {

constexpr std::size_t kSamples = 1'000'000;

const geaware::model::VehicleParams& vehicle() {
  static const geaware::model::VehicleParams p = geaware::io::builtinVehicle();
  return p;
}

/// Writes the platform log once and returns its path.
const std::filesystem::path& platformCsv() {
  static const std::filesystem::path file = [] {
    const auto path = std::filesystem::temp_directory_path() / "geaware_ident_bench_platform.csv";
    const auto& p = vehicle();
    const geaware::model::Mixer mixer(p);
    const geaware::model::GroundEffectModel ge(p);
    std::mt19937_64 rng(1);
    std::normal_distribution<double> noise(0.0, 1.0);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double level_h[] = {0.075, 0.09, 0.11, 0.13, 0.16, 0.2, 0.25, 0.3, 0.4, 0.5, 0.7, 1.0, 1.5, 2.0};
    const double tilts[] = {2.0, 4.0, 6.0, 8.0, 10.0, 15.0};
    std::FILE* f = std::fopen(path.c_str(), "w");
    std::fprintf(f, "t_s,h_m,tilt_deg,n1_rpm,n2_rpm,n3_rpm,n4_rpm,fx_N,fy_N,fz_N,tx_Nm,ty_Nm,tz_Nm\n");
    for (std::size_t i = 0; i < kSamples; ++i) {
      const bool level = i % 2 == 0;
      const double h = level ? level_h[i / 2 % 14] : 0.08 + 0.02 * static_cast<double>(i / 2 % 17);
      const double tilt = level ? 0.0 : tilts[i / 34 % 6];
      const double base = 8000.0 + 8000.0 * unit(rng);
      Eigen::Vector4d n;
      for (int k = 0; k < 4; ++k) n(k) = base + (level ? 1500.0 : 300.0) * (2.0 * unit(rng) - 1.0);
      const Eigen::Vector4d w = mixer.wrench(n.cwiseAbs2());
      const double fz = w(0) * (1.0 + ge.thrustRatio(h)) + 0.05 * noise(rng);
      const double ty = w(2) - ge.levelingCoefficient(h) * w(0) * std::sin(tilt * geaware::model::kDegToRad) +
                        0.002 * noise(rng);
      std::fprintf(f, "%.3f,%.4f,%.2f,%.2f,%.2f,%.2f,%.2f,%.5f,%.5f,%.5f,%.6f,%.6f,%.6f\n",
                   0.005 * static_cast<double>(i), h, tilt, n(0), n(1), n(2), n(3), 0.05 * noise(rng),
                   0.05 * noise(rng), fz, w(1) + 0.002 * noise(rng), ty, w(3) + 0.002 * noise(rng));
    }
    std::fclose(f);
    return path;
  }();
  return file;
}

void BM_ReadPlatformCsv(benchmark::State& state) {
  const auto& file = platformCsv();
  for (auto _ : state) {
    const auto log = geaware::ident::readPlatformLog(file);
    benchmark::DoNotOptimize(log.f_N[2].data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kSamples));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(std::filesystem::file_size(file)));
}
BENCHMARK(BM_ReadPlatformCsv)->Unit(benchmark::kMillisecond)->Iterations(3);

/// Everything `geaware identify platform` does: parse, k_T + F_G (Ceres, robust), the mixing
/// coefficients overall and per height band, the leveling torque (Ceres, robust).
void BM_IdentifyPlatform(benchmark::State& state) {
  const auto& file = platformCsv();
  const auto& p = vehicle();
  for (auto _ : state) {
    const auto log = geaware::ident::readPlatformLog(file);
    const auto thrust = geaware::ident::fitAdditionalThrust(log);
    const auto mixing = geaware::ident::fitMixing(log, p.diagonal_rotor_distance_m);
    const auto leveling = geaware::ident::fitLeveling(
        log, {thrust.k_T_N_per_rpm2.value, mixing.k_TY_N_per_rpm2->value, p.diagonal_rotor_distance_m});
    benchmark::DoNotOptimize(leveling.scale_m4.value);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kSamples));
}
BENCHMARK(BM_IdentifyPlatform)->Unit(benchmark::kMillisecond)->Iterations(3);

/// The same with both curves as tables (`--ground-effect table`): sparse robust linear fits
/// over the knots (the synthetic log's distinct heights up to 0.5 m for F_G, every tilted height
/// for M_G) instead of the closed forms' Ceres fits.
void BM_IdentifyPlatformTables(benchmark::State& state) {
  const auto& file = platformCsv();
  const auto& p = vehicle();
  std::size_t knots = 0;
  for (auto _ : state) {
    const auto log = geaware::ident::readPlatformLog(file);
    const auto thrust = geaware::ident::fitAdditionalThrustTable(log);
    const auto mixing = geaware::ident::fitMixing(log, p.diagonal_rotor_distance_m);
    const auto leveling = geaware::ident::fitLevelingTable(
        log, {thrust.k_T_N_per_rpm2.value, mixing.k_TY_N_per_rpm2->value, p.diagonal_rotor_distance_m});
    knots = thrust.F_G.heights_m.size() + leveling.M_G.heights_m.size();
    benchmark::DoNotOptimize(leveling.M_G.values.data());
  }
  state.counters["knots"] = static_cast<double>(knots);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kSamples));
}
BENCHMARK(BM_IdentifyPlatformTables)->Unit(benchmark::kMillisecond)->Iterations(3);

/// The supplementary correlation table (11 rank transforms of up to 10⁶ samples).
void BM_PlatformCorrelations(benchmark::State& state) {
  const auto log = geaware::ident::readPlatformLog(platformCsv());
  for (auto _ : state) {
    const auto table = geaware::ident::platformCorrelations(log, vehicle());
    benchmark::DoNotOptimize(table.r.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kSamples));
}
BENCHMARK(BM_PlatformCorrelations)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
