// SPDX-License-Identifier: BSD-3-Clause
// Throughput of `geaware identify flight` (issue 11: 10⁶ rows ≤ 1 s): 10⁶ flight-log rows in
// identify flight's CSV format, parsed and fitted. BM_IdentifyFlight: the drag table (5 height
// bands, robust linear fits of d_x, d_y); BM_IdentifyHover: a hover descent's k_T, g1, g2
// (Ceres, robust). The logs are generated once, in the temporary directory, from the
// controller-side model of the built-in vehicle with Gaussian noise. Results: docs/identification.md.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include <benchmark/benchmark.h>

#include "geaware/ident/identify.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/ground_effect.hpp"
#include "geaware/model/rotor_drag.hpp"

namespace {

constexpr std::size_t kRows = 1'000'000;

const geaware::model::VehicleParams& vehicle() {
  static const geaware::model::VehicleParams p = geaware::io::builtinVehicle();
  return p;
}

/// Level flight at 0.1–2 m with a random horizontal velocity: m·a_ext = −D(h)·v + noise.
const std::filesystem::path& flightCsv() {
  static const std::filesystem::path file = [] {
    const auto path = std::filesystem::temp_directory_path() / "geaware_ident_bench_flight.csv";
    const auto& p = vehicle();
    const geaware::model::RotorDragModel drag(p.drag);
    std::mt19937_64 rng(2);
    std::normal_distribution<double> noise(0.0, 1.0);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::FILE* f = std::fopen(path.c_str(), "w");
    std::fprintf(f, "t_s,h_m,vx_mps,vy_mps,vz_mps,qw,qx,qy,qz,ax_ext_mps2,ay_ext_mps2,az_ext_mps2,"
                    "n1_rpm,n2_rpm,n3_rpm,n4_rpm\n");
    for (std::size_t i = 0; i < kRows; ++i) {
      const double h = 0.1 + 1.9 * unit(rng);
      const double vx = 4.0 * unit(rng) - 2.0;
      const double vy = 4.0 * unit(rng) - 2.0;
      const Eigen::Vector2d d = drag.coefficients(h);
      const double ax = -d.x() * vx / p.mass_kg + 0.05 * noise(rng);
      const double ay = -d.y() * vy / p.mass_kg + 0.05 * noise(rng);
      const double n = 10000.0 + 200.0 * noise(rng);
      std::fprintf(f, "%.3f,%.4f,%.4f,%.4f,0,1,0,0,0,%.5f,%.5f,%.5f,%.1f,%.1f,%.1f,%.1f\n",
                   0.002 * static_cast<double>(i), h, vx, vy, ax, ay, 0.05 * noise(rng), n, n, n, n);
    }
    std::fclose(f);
    return path;
  }();
  return file;
}

/// A hover descent from 2 m to 0.08 m: m·a_ext,z + k_T·Σn² = k_T·Σn²·(1 + F_G(h)) + noise.
const std::filesystem::path& hoverCsv() {
  static const std::filesystem::path file = [] {
    const auto path = std::filesystem::temp_directory_path() / "geaware_ident_bench_hover.csv";
    const auto& p = vehicle();
    const geaware::model::GroundEffectModel ge(p);
    std::mt19937_64 rng(3);
    std::normal_distribution<double> noise(0.0, 1.0);
    std::FILE* f = std::fopen(path.c_str(), "w");
    std::fprintf(f, "t_s,h_m,az_ext_mps2,n1_rpm,n2_rpm,n3_rpm,n4_rpm\n");
    for (std::size_t i = 0; i < kRows; ++i) {
      const double h = 2.0 - 1.92 * static_cast<double>(i) / static_cast<double>(kRows);
      const double n = 10000.0 + 300.0 * noise(rng);
      const double T = p.rotor.k_T_N_per_rpm2 * 4.0 * n * n;
      const double az = T * ge.thrustRatio(h) / p.mass_kg + 0.1 * noise(rng);
      std::fprintf(f, "%.4f,%.5f,%.5f,%.1f,%.1f,%.1f,%.1f\n", 0.001 * static_cast<double>(i), h, az, n, n, n, n);
    }
    std::fclose(f);
    return path;
  }();
  return file;
}

/// The parse alone (every column of identify flight's log), for the split.
void BM_ReadFlightCsv(benchmark::State& state) {
  const auto& file = flightCsv();
  for (auto _ : state) {
    const auto log = geaware::ident::readFlightLog(file);
    benchmark::DoNotOptimize(log.a_ext_W[0].data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kRows));
}
BENCHMARK(BM_ReadFlightCsv)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_ReadHoverCsv(benchmark::State& state) {
  const auto& file = hoverCsv();
  for (auto _ : state) {
    const auto log = geaware::ident::readHoverLog(file);
    benchmark::DoNotOptimize(log.a_ext_W[2].data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kRows));
}
BENCHMARK(BM_ReadHoverCsv)->Unit(benchmark::kMillisecond)->Iterations(3);

/// `geaware identify flight LOG` as a library call: parse, then the drag table.
void BM_IdentifyFlight(benchmark::State& state) {
  const auto& file = flightCsv();
  for (auto _ : state) {
    const auto log = geaware::ident::readFlightLog(file);
    geaware::ident::IdentifyOptions o;
    o.height_bands = 5;
    const auto r = geaware::ident::identifyFlight(log, vehicle(), o);
    benchmark::DoNotOptimize(r.parameters.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kRows));
}
BENCHMARK(BM_IdentifyFlight)->Unit(benchmark::kMillisecond)->Iterations(3);

/// `geaware identify flight --hover LOG`: parse, then k_T, g1, g2 (Ceres, robust).
void BM_IdentifyHover(benchmark::State& state) {
  const auto& file = hoverCsv();
  for (auto _ : state) {
    const auto log = geaware::ident::readHoverLog(file);
    const auto r = geaware::ident::identifyHover(log, vehicle(), {});
    benchmark::DoNotOptimize(r.parameters.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kRows));
}
BENCHMARK(BM_IdentifyHover)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
