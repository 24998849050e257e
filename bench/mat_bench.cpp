// SPDX-License-Identifier: BSD-3-Clause
// Throughput of the MATLAB .mat reader (issue 11, ≤ 0.5 s per 10⁶ rows): BM_ReadMat reads a v5
// file written once by libmatio, a struct `flight` of 10⁶ samples × 8 double fields (time, z,
// acc x y z, four rotor speeds), into the channel model.
#include <benchmark/benchmark.h>
#include <matio.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "geaware/io/log_channels.hpp"

namespace {

constexpr std::size_t kRows = 1'000'000;

const std::filesystem::path& matFile() {
  static const std::filesystem::path path = [] {
    const auto p = std::filesystem::temp_directory_path() / "geaware_bench_read.mat";
    const char* fields[] = {"time", "z", "acc_x", "acc_y", "acc_z", "n1", "n2", "n3", "n4"};
    std::size_t one[2] = {1, 1};
    mat_t* mat = Mat_CreateVer(p.c_str(), nullptr, MAT_FT_MAT5);
    matvar_t* s = Mat_VarCreateStruct("flight", 2, one, fields, 9);
    std::size_t dims[2] = {kRows, 1};
    for (std::size_t f = 0; f < 9; ++f) {
      std::vector<double> v(kRows);
      for (std::size_t i = 0; i < kRows; ++i)
        v[i] = f == 0 ? 1e-3 * static_cast<double>(i) : static_cast<double>(f + i % 97);
      Mat_VarSetStructFieldByName(
          s, fields[f], 0,
          Mat_VarCreate(fields[f], MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, v.data(), 0));
    }
    Mat_VarWrite(mat, s, MAT_COMPRESSION_NONE);
    Mat_VarFree(s);
    Mat_Close(mat);
    return p;
  }();
  return path;
}

void BM_ReadMat(benchmark::State& state) {
  const auto& file = matFile();
  for (auto _ : state) {
    const auto log = geaware::io::readMat(file);
    const auto* t = log.topic("flight");
    if (t == nullptr || t->size() != kRows || t->channels.size() != 9)
      state.SkipWithError("wrong rows or fields");
    benchmark::DoNotOptimize(log.topics.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kRows));
}
BENCHMARK(BM_ReadMat)->Unit(benchmark::kMillisecond);

}  // namespace
