// SPDX-License-Identifier: BSD-3-Clause
// Throughput of the flight-log readers (issue 11): 10⁶ rows of each format, generated once in the
// temporary directory, read whole into the channel model. Target: ≤ 0.5 s per format.
//   BM_ReadULog       10⁶ data messages of a sensor_combined-like topic (timestamp + 9 floats +
//                     2 uint32 + 2 uint8), written as PX4's logger writes them (format, subscription,
//                     data messages);
//   BM_ReadDataFlash  10⁶ IMU-like messages (QBffffff + FMT/FMTU/UNIT/MULT);
//   BM_ReadCsv        10⁶ rows × 8 columns of a CSV log, every column parsed;
//   BM_ReadCrazyflieUsd       10⁶ events of a uSD event log (version 2: uint16 id, uint64 µs,
//                             12 floats and 5 uint16, as the deck's fixedFrequency event), CRC-32;
//   BM_ReadCrazyflieUsdFixed  10⁶ records of the older fixed-frequency format (tick + 12 floats
//                             + 5 uint16), in blocks of 100 records with their CRCs.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "geaware/io/csv_reader.hpp"
#include "geaware/io/log_channels.hpp"

namespace {

constexpr std::size_t kRows = 1'000'000;

class Bytes {
 public:
  template <typename T>
  Bytes& put(T v) {
    const auto* p = reinterpret_cast<const char*>(&v);
    data.append(p, sizeof v);
    return *this;
  }
  Bytes& text(const std::string& s, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) data.push_back(i < s.size() ? s[i] : '\0');
    return *this;
  }
  std::string data;
};

std::filesystem::path writeOnce(const std::string& name, const std::string& bytes) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

void ulogMessage(Bytes& b, char type, const std::string& payload) {
  b.put(static_cast<std::uint16_t>(payload.size())).put(type);
  b.data += payload;
}

const std::filesystem::path& ulogFile() {
  static const std::filesystem::path path = [] {
    Bytes b;
    b.text("ULog", 4).put<std::uint8_t>(0x01).put<std::uint8_t>(0x12).put<std::uint8_t>(0x35);
    b.put<std::uint8_t>(1).put<std::uint64_t>(0);
    ulogMessage(b, 'B', std::string(40, '\0'));
    ulogMessage(b, 'F', "sensor_combined:uint64_t timestamp;float[3] gyro_rad;uint32_t gyro_integral_dt;"
                        "int32_t accelerometer_timestamp_relative;float[3] accelerometer_m_s2;"
                        "uint32_t accelerometer_integral_dt;uint8_t accelerometer_clipping;uint8_t gyro_clipping;"
                        "float[3] mag;uint8_t[2] _padding0;");
    Bytes sub;
    sub.put<std::uint8_t>(0).put<std::uint16_t>(7).text("sensor_combined", 15);
    ulogMessage(b, 'A', sub.data);
    for (std::size_t i = 0; i < kRows; ++i) {
      Bytes d;
      d.put<std::uint16_t>(7).put<std::uint64_t>(1000000 + 4000 * i);
      for (int k = 0; k < 3; ++k) d.put(0.01f * static_cast<float>(k + i % 7));
      d.put<std::uint32_t>(4000).put<std::int32_t>(0);
      for (int k = 0; k < 3; ++k) d.put(-9.81f + 0.001f * static_cast<float>(k + i % 11));
      d.put<std::uint32_t>(4000).put<std::uint8_t>(0).put<std::uint8_t>(0);
      for (int k = 0; k < 3; ++k) d.put(0.2f * static_cast<float>(k));
      ulogMessage(b, 'D', d.data);  // trailing padding not written, as PX4's logger does
    }
    return writeOnce("geaware_bench_read.ulg", b.data);
  }();
  return path;
}

const std::filesystem::path& dataflashFile() {
  static const std::filesystem::path path = [] {
    Bytes b;
    const auto head = [&](std::uint8_t id) { b.put<std::uint8_t>(0xa3).put<std::uint8_t>(0x95).put(id); };
    const auto fmt = [&](std::uint8_t id, std::uint8_t len, const char* name, const char* f, const char* labels) {
      head(128);
      b.put(id).put(len).text(name, 4).text(f, 16).text(labels, 64);
    };
    fmt(128, 89, "FMT", "BBnNZ", "Type,Length,Name,Format,Columns");
    fmt(129, 76, "UNIT", "QbZ", "TimeUS,Id,Label");
    fmt(130, 20, "MULT", "Qbd", "TimeUS,Id,Mult");
    fmt(131, 44, "FMTU", "QBNN", "TimeUS,FmtType,UnitIds,MultIds");
    fmt(132, 3 + 8 + 1 + 24, "IMU", "QBffffff", "TimeUS,I,GyrX,GyrY,GyrZ,AccX,AccY,AccZ");
    head(129), b.put<std::uint64_t>(0).put<std::int8_t>('s').text("s", 64);
    head(130), b.put<std::uint64_t>(0).put<std::int8_t>('F').put(1e-6);
    head(131), b.put<std::uint64_t>(0).put<std::uint8_t>(132).text("s#EEEooo", 16).text("F-000000", 16);
    for (std::size_t i = 0; i < kRows; ++i) {
      head(132);
      b.put<std::uint64_t>(1000000 + 2500 * i).put<std::uint8_t>(static_cast<std::uint8_t>(i % 2));
      for (int k = 0; k < 6; ++k) b.put(0.01f * static_cast<float>(k + i % 13));
    }
    return writeOnce("geaware_bench_read.bin", b.data);
  }();
  return path;
}

const std::filesystem::path& csvFile() {
  static const std::filesystem::path path = [] {
    std::string text = "t_s,h_m,vz_mps,qw,qz,n1_rpm,n2_rpm,vbat_V\n";
    char line[256];
    for (std::size_t i = 0; i < kRows; ++i) {
      const auto x = static_cast<double>(i);
      const auto k = static_cast<int>(i % 500);
      std::snprintf(line, sizeof line, "%.4f,%.6g,%.6g,%.7g,%.7g,%.1f,%.1f,%.3f\n", 0.002 * x, 0.1 + 0.001 * k,
                    -0.01 * (k % 7), 0.9999, 0.01 * (k % 3), 9000.0 + k % 100, 9100.0 - k % 50, 16.2 - 1e-6 * x);
      text += line;
    }
    return writeOnce("geaware_bench_read.csv", text);
  }();
  return path;
}

// A CRC-32 (zlib's) for the uSD files.
std::uint32_t crc32(const std::string& bytes, std::size_t from = 0) {
  static const auto table = [] {
    std::vector<std::uint32_t> t(256);
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1U) != 0 ? 0xEDB88320U ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xFFFFFFFFU;
  for (std::size_t i = from; i < bytes.size(); ++i) {
    c = table[(c ^ static_cast<unsigned char>(bytes[i])) & 0xffU] ^ (c >> 8);
  }
  return c ^ 0xFFFFFFFFU;
}

constexpr const char* kUsdVariables[] = {"stateEstimate.x(f)", "stateEstimate.y(f)", "stateEstimate.z(f)",
                                         "acc.x(f)", "acc.y(f)", "acc.z(f)", "gyro.x(f)", "gyro.y(f)", "gyro.z(f)",
                                         "stateEstimate.qw(f)", "stateEstimate.qx(f)", "stateEstimate.qy(f)",
                                         "rpm.m1(H)", "rpm.m2(H)", "rpm.m3(H)", "rpm.m4(H)", "pm.vbatMV(H)"};

void usdRecord(Bytes& b, std::size_t i) {
  const auto x = static_cast<float>(i % 1000);
  for (int k = 0; k < 12; ++k) b.put(0.001f * x + static_cast<float>(k));
  for (int k = 0; k < 4; ++k) b.put(static_cast<std::uint16_t>(15000 + i % 100 + static_cast<std::size_t>(k)));
  b.put(static_cast<std::uint16_t>(3900 - i % 10));
}

const std::filesystem::path& usdFile() {
  static const std::filesystem::path path = [] {
    Bytes b;
    b.put(std::uint8_t{0xBC}).put(std::uint16_t{2}).put(std::uint16_t{1});
    b.put(std::uint16_t{0});
    b.data += std::string("fixedFrequency") + '\0';
    b.put(static_cast<std::uint16_t>(std::size(kUsdVariables)));
    for (const char* v : kUsdVariables) b.data += std::string(v) + '\0';
    for (std::size_t i = 0; i < kRows; ++i) {
      b.put(std::uint16_t{0}).put(static_cast<std::uint64_t>(1000 * i));
      usdRecord(b, i);
    }
    b.put(crc32(b.data));
    return writeOnce("geaware_bench_read_usd.bin", b.data);
  }();
  return path;
}

const std::filesystem::path& usdFixedFile() {
  static const std::filesystem::path path = [] {
    Bytes b;
    b.put(static_cast<std::uint8_t>(1 + std::size(kUsdVariables)));
    b.data += "tick(I),";
    for (const char* v : kUsdVariables) b.data += std::string(v) + ',';
    b.put(crc32(b.data) ^ 0xFFFFFFFFU);
    for (std::size_t i = 0; i < kRows; i += 100) {
      const std::size_t start = b.data.size();
      b.put(std::uint8_t{100});
      for (std::size_t k = i; k < i + 100; ++k) {
        b.put(static_cast<std::uint32_t>(k));
        usdRecord(b, k);
      }
      b.put(crc32(b.data, start) ^ 0xFFFFFFFFU);
    }
    return writeOnce("geaware_bench_read_usd_fixed.bin", b.data);
  }();
  return path;
}

void BM_ReadULog(benchmark::State& state) {
  const auto& file = ulogFile();
  for (auto _ : state) {
    const auto log = geaware::io::readULog(file);
    if (log.topics.at(0).size() != kRows) state.SkipWithError("wrong row count");
    benchmark::DoNotOptimize(log.topics.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kRows));
}
BENCHMARK(BM_ReadULog)->Unit(benchmark::kMillisecond);

void BM_ReadDataFlash(benchmark::State& state) {
  const auto& file = dataflashFile();
  for (auto _ : state) {
    const auto log = geaware::io::readDataFlash(file);
    const auto* a = log.topic("IMU", 0);
    const auto* b = log.topic("IMU", 1);
    if (a == nullptr || b == nullptr || a->size() + b->size() != kRows) state.SkipWithError("wrong row count");
    benchmark::DoNotOptimize(log.topics.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kRows));
}
BENCHMARK(BM_ReadDataFlash)->Unit(benchmark::kMillisecond);

void BM_ReadCsv(benchmark::State& state) {
  const auto& file = csvFile();
  geaware::io::CsvReadOptions o;
  for (const char* c : {"t_s", "h_m", "vz_mps", "qw", "qz", "n1_rpm", "n2_rpm", "vbat_V"}) o.columns.push_back({c});
  for (auto _ : state) {
    const auto table = geaware::io::readCsv(file, o);
    if (table.rows() != kRows) state.SkipWithError("wrong row count");
    benchmark::DoNotOptimize(table.columns.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kRows));
}
BENCHMARK(BM_ReadCsv)->Unit(benchmark::kMillisecond);

void readUsd(benchmark::State& state, const std::filesystem::path& file) {
  for (auto _ : state) {
    const auto log = geaware::io::readCrazyflieUsd(file);
    if (log.topics.size() != 1 || log.topics[0].size() != kRows || !log.warnings.empty()) {
      state.SkipWithError("wrong row count or a warning");
    }
    benchmark::DoNotOptimize(log.topics.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kRows));
}
void BM_ReadCrazyflieUsd(benchmark::State& state) { readUsd(state, usdFile()); }
BENCHMARK(BM_ReadCrazyflieUsd)->Unit(benchmark::kMillisecond);
void BM_ReadCrazyflieUsdFixed(benchmark::State& state) { readUsd(state, usdFixedFile()); }
BENCHMARK(BM_ReadCrazyflieUsdFixed)->Unit(benchmark::kMillisecond);

}  // namespace
