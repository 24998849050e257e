// SPDX-License-Identifier: BSD-3-Clause
// Crazyflie uSD logs (io::readCrazyflieUsd). No real uSD log is in the repository: every file
// here is built byte by byte in the test from the published format (the firmware's
// src/deck/drivers/src/usddeck.c and its decoders tools/usdlog/cfusdlog.py, CF_functions.py),
// field by field, with the CRC-32 computed bit by bit here (checked on the standard's check
// value), independent of the reader's table-driven one.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geaware/io/log_channels.hpp"
#include "geaware/io/log_map.hpp"

namespace {

using geaware::io::FieldType;
using geaware::io::LogData;
using geaware::io::LogError;
using geaware::io::readCrazyflieUsd;

// CRC-32 as zlib computes it, one bit at a time.
std::uint32_t crc32(const std::vector<std::byte>& bytes, std::size_t from = 0,
                    std::size_t to = SIZE_MAX) {
  std::uint32_t c = 0xFFFFFFFFU;
  for (std::size_t i = from; i < std::min(to, bytes.size()); ++i) {
    c ^= static_cast<std::uint32_t>(bytes[i]);
    for (int k = 0; k < 8; ++k) c = (c & 1U) != 0 ? (c >> 1) ^ 0xEDB88320U : c >> 1;
  }
  return c ^ 0xFFFFFFFFU;
}

struct Bytes {
  std::vector<std::byte> b;
  template <typename T>
  Bytes& put(T v) {
    std::byte raw[sizeof v];
    std::memcpy(raw, &v, sizeof v);
    b.insert(b.end(), raw, raw + sizeof v);
    return *this;
  }
  Bytes& text(const std::string& s, char end) {
    for (const char c : s) b.push_back(static_cast<std::byte>(c));
    b.push_back(static_cast<std::byte>(end));
    return *this;
  }
  std::size_t size() const { return b.size(); }
};

TEST(CrazyflieUsd, TheTestsCrcIsTheStandardOne) {
  Bytes b;
  for (const char c : std::string("123456789")) b.put(c);
  EXPECT_EQ(crc32(b.b), 0xCBF43926U);  // the CRC-32 check value
}

// An event-based log: two event types logged, one defined but never logged.
Bytes eventLog(std::uint16_t version) {
  Bytes f;
  f.put(std::uint8_t{0xBC}).put(version).put(std::uint16_t{3});
  f.put(std::uint16_t{1}).text("fixedFrequency", '\0').put(std::uint16_t{4});
  f.text("stateEstimate.z(f)", '\0')
      .text("acc.z(f)", '\0')
      .text("rpm.m1(H)", '\0')
      .text("pm.vbatMV(H)", '\0');
  f.put(std::uint16_t{7}).text("estTDOA", '\0').put(std::uint16_t{5});
  f.text("idA(B)", '\0')
      .text("distanceDiff(f)", '\0')
      .text("x(h)", '\0')
      .text("y(i)", '\0')
      .text("w(e)", '\0');
  f.put(std::uint16_t{9}).text("unused", '\0').put(std::uint16_t{1}).text("a(b)", '\0');
  const auto stamp = [&](std::uint64_t us) {
    if (version == 1) {
      f.put(static_cast<std::uint32_t>(us / 1000));
    } else {
      f.put(us);
    }
  };
  f.put(std::uint16_t{1});
  stamp(1000000);
  f.put(0.5f).put(1.0f).put(std::uint16_t{15000}).put(std::uint16_t{3900});
  f.put(std::uint16_t{7});
  stamp(1005000);
  f.put(std::uint8_t{3})
      .put(-0.25f)
      .put(std::int16_t{-300})
      .put(std::int32_t{-70000})
      .put(std::uint16_t{0x3E00});
  f.put(std::uint16_t{1});
  stamp(1010000);
  f.put(0.75f).put(0.5f).put(std::uint16_t{16000}).put(std::uint16_t{3850});
  f.put(crc32(f.b));
  return f;
}

LogData read(const Bytes& f, const std::string& name = "mem.bin") {
  return readCrazyflieUsd(f.b, name);
}

TEST(CrazyflieUsd, EventLogsAreReadFieldByField) {
  for (const std::uint16_t version : {std::uint16_t{1}, std::uint16_t{2}}) {
    const LogData log = read(eventLog(version));
    EXPECT_EQ(log.format, "crazyflie_usd");
    EXPECT_TRUE(log.warnings.empty()) << log.warnings.front();
    ASSERT_EQ(log.topics.size(), 2u);  // "unused" never logged: left out
    const auto* ff = log.topic("fixedFrequency");
    ASSERT_NE(ff, nullptr);
    ASSERT_EQ(ff->size(), 2u);
    EXPECT_DOUBLE_EQ(ff->time_s[0], 1.0);  // v1: 1000 ms; v2: 1,000,000 µs
    EXPECT_DOUBLE_EQ(ff->time_s[1], 1.01);
    EXPECT_EQ(ff->channels[0].name, "stateEstimate.z");
    EXPECT_EQ(ff->channels[0].type, FieldType::kFloat);
    EXPECT_EQ(ff->channel("stateEstimate.z")->values, (std::vector<double>{0.5, 0.75}));
    EXPECT_EQ(ff->channel("rpm.m1")->type, FieldType::kUInt16);
    EXPECT_EQ(ff->channel("rpm.m1")->values, (std::vector<double>{15000.0, 16000.0}));
    EXPECT_EQ(ff->channel("pm.vbatMV")->values[1], 3850.0);
    const auto* tdoa = log.topic("estTDOA");
    ASSERT_NE(tdoa, nullptr);
    ASSERT_EQ(tdoa->size(), 1u);
    EXPECT_DOUBLE_EQ(tdoa->time_s[0], 1.005);
    EXPECT_EQ(tdoa->channel("idA")->values[0], 3.0);
    EXPECT_EQ(tdoa->channel("distanceDiff")->values[0], -0.25);
    EXPECT_EQ(tdoa->channel("x")->values[0], -300.0);
    EXPECT_EQ(tdoa->channel("y")->values[0], -70000.0);
    EXPECT_EQ(tdoa->channel("w")->values[0], 1.5);  // half float 0x3E00
  }
}

TEST(CrazyflieUsd, ABadCrcIsNamedAndTheValuesKept) {
  Bytes f = eventLog(2);
  f.b[f.size() - 6] ^= std::byte{0x01};  // one bit of the last event's vbat
  const LogData log = read(f);
  ASSERT_EQ(log.warnings.size(), 1u);
  EXPECT_NE(log.warnings[0].find("byte " + std::to_string(f.size() - 4) +
                                 ": CRC-32 of the bytes before it is 0x"),
            std::string::npos)
      << log.warnings[0];
  EXPECT_NE(log.warnings[0].find("the file is damaged or was cut"), std::string::npos);
  EXPECT_EQ(log.topic("fixedFrequency")->channel("pm.vbatMV")->values[1], 3851.0);
}

TEST(CrazyflieUsd, ACutLogIsReadUpToTheCutAndEveryLengthIsHandled) {
  const Bytes full = eventLog(2);
  const std::size_t header =
      5 + 2 + 15 + 2 + 19 + 9 + 10 + 13 + 2 + 8 + 2 + 7 + 16 + 5 + 5 + 5 + 2 + 7 + 2 + 5;
  // Cut inside the second event: the first is read, a warning names the cut.
  const std::size_t first_event = 2 + 8 + 12;
  Bytes cut;
  cut.b.assign(full.b.begin(),
               full.b.begin() + static_cast<std::ptrdiff_t>(header + first_event + 6));
  const LogData log = read(cut);
  ASSERT_EQ(log.topic("fixedFrequency")->size(), 1u);
  ASSERT_FALSE(log.warnings.empty());
  EXPECT_NE(log.warnings[0].find("a cut file"), std::string::npos) << log.warnings[0];
  // Every length: an error naming a byte inside the header, or a log with warnings.
  for (std::size_t n = 0; n < full.size(); ++n) {
    Bytes part;
    part.b.assign(full.b.begin(), full.b.begin() + static_cast<std::ptrdiff_t>(n));
    try {
      const LogData l = read(part);
      EXPECT_GE(n, header) << n;
      EXPECT_FALSE(l.warnings.empty()) << n;
    } catch (const LogError& e) {
      EXPECT_LT(n, header) << n;
      EXPECT_EQ(e.file(), "mem.bin");
    }
  }
}

TEST(CrazyflieUsd, BadFramingIsAnErrorAtItsByte) {
  Bytes f;
  f.put(std::uint8_t{0xBC}).put(std::uint16_t{2}).put(std::uint16_t{1});
  f.put(std::uint16_t{1}).text("ev", '\0').put(std::uint16_t{1}).text("x(z)", '\0');
  try {
    (void)read(f);
    FAIL() << "no error";
  } catch (const LogError& e) {
    EXPECT_STREQ(
        e.what(),
        "mem.bin: byte 12: variable 'x(z)': expected NAME(T), T one of b B h H i I q Q f d e");
  }
  // An event id the header does not define: the rest is not read, with a warning.
  Bytes g;
  g.put(std::uint8_t{0xBC}).put(std::uint16_t{2}).put(std::uint16_t{1});
  g.put(std::uint16_t{1}).text("ev", '\0').put(std::uint16_t{1}).text("x(f)", '\0');
  g.put(std::uint16_t{1}).put(std::uint64_t{5000}).put(2.0f);
  g.put(std::uint16_t{4}).put(std::uint64_t{6000}).put(3.0f);
  g.put(crc32(g.b));
  const LogData log = read(g);
  EXPECT_EQ(log.topic("ev")->size(), 1u);
  ASSERT_FALSE(log.warnings.empty());
  EXPECT_NE(log.warnings[0].find("byte 31: unknown event type id 4"), std::string::npos)
      << log.warnings[0];
}

// The older fixed-frequency format: a header of "name(T)," entries and blocks of records, each
// followed by the CRC register (the zlib CRC-32 inverted).
Bytes fixedLog(bool bad_block_crc = false) {
  Bytes f;
  f.put(std::uint8_t{3})
      .text("tick(I)", ',')
      .text("stateEstimate.z(f)", ',')
      .text("motor.m1(H)", ',');
  f.put(crc32(f.b) ^ 0xFFFFFFFFU);
  const std::size_t block1 = f.size();
  f.put(std::uint8_t{2});
  f.put(std::uint32_t{2000}).put(0.25f).put(std::uint16_t{30000});
  f.put(std::uint32_t{2010}).put(0.26f).put(std::uint16_t{30100});
  f.put((crc32(f.b, block1) ^ 0xFFFFFFFFU) ^ (bad_block_crc ? 1U : 0U));
  const std::size_t block2 = f.size();
  f.put(std::uint8_t{1});
  f.put(std::uint32_t{2020}).put(0.27f).put(std::uint16_t{30200});
  f.put(crc32(f.b, block2) ^ 0xFFFFFFFFU);
  return f;
}

TEST(CrazyflieUsd, FixedFrequencyLogsAreReadFieldByField) {
  const Bytes f = fixedLog();
  // The stored CRC makes the zlib CRC-32 of a header or block with it 0xFFFFFFFF, as the
  // reference decoder checks.
  EXPECT_EQ(crc32(f.b, 0, 1 + 8 + 19 + 12 + 4), 0xFFFFFFFFU);
  const LogData log = read(f);
  EXPECT_TRUE(log.warnings.empty()) << log.warnings.front();
  ASSERT_EQ(log.topics.size(), 1u);
  const auto& t = log.topics[0];
  EXPECT_EQ(t.name, "fixedFrequency");
  ASSERT_EQ(t.size(), 3u);
  EXPECT_DOUBLE_EQ(t.time_s[0], 2.0);  // tick in ms
  EXPECT_DOUBLE_EQ(t.time_s[2], 2.02);
  EXPECT_EQ(t.channel("tick")->type, FieldType::kUInt32);
  EXPECT_EQ(t.channel("stateEstimate.z")->values[1], static_cast<double>(0.26f));
  EXPECT_EQ(t.channel("motor.m1")->values, (std::vector<double>{30000.0, 30100.0, 30200.0}));
  // A block whose CRC does not match is named; a log cut inside a block keeps its whole records.
  const LogData bad = read(fixedLog(true));
  ASSERT_EQ(bad.warnings.size(), 1u);
  EXPECT_NE(bad.warnings[0].find("the block at byte 44's CRC is"), std::string::npos)
      << bad.warnings[0];
  Bytes cut = fixedLog();
  cut.b.resize(cut.size() - 6);
  const LogData c = read(cut);
  EXPECT_EQ(c.topics[0].size(), 2u);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(
      c.warnings[0].find("ends inside a block of 1 records (a cut file): 0 whole records read"),
      std::string::npos)
      << c.warnings[0];
}

TEST(CrazyflieUsd, ReadLogDetectsBothFormatsAndTheCrazyflieMapReadsThem) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / "geaware_cfusd";
  std::filesystem::create_directories(dir);
  // A flight's variables in the event log, the rpm deck's motors m1-m4.
  Bytes f;
  f.put(std::uint8_t{0xBC}).put(std::uint16_t{2}).put(std::uint16_t{1});
  f.put(std::uint16_t{0}).text("fixedFrequency", '\0').put(std::uint16_t{12});
  for (const char* v :
       {"stateEstimate.z(f)", "acc.x(f)", "acc.y(f)", "acc.z(f)", "stateEstimate.qw(f)",
        "stateEstimate.qx(f)", "stateEstimate.qy(f)", "stateEstimate.qz(f)", "rpm.m1(H)",
        "rpm.m2(H)", "rpm.m3(H)", "rpm.m4(H)"}) {
    f.text(v, '\0');
  }
  for (int i = 0; i < 50; ++i) {
    f.put(std::uint16_t{0}).put(static_cast<std::uint64_t>(2000000 + 10000 * i));
    f.put(0.1f + 0.001f * static_cast<float>(i))
        .put(0.0f)
        .put(0.0f)
        .put(1.0f)
        .put(1.0f)
        .put(0.0f)
        .put(0.0f)
        .put(0.0f);
    f.put(std::uint16_t{15000})
        .put(std::uint16_t{15100})
        .put(std::uint16_t{15200})
        .put(std::uint16_t{15300});
  }
  f.put(crc32(f.b));
  const auto file = dir / "log00";
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(f.b.data()), static_cast<std::streamsize>(f.size()));
  EXPECT_EQ(geaware::io::detectLogFormat(file), geaware::io::LogFormat::kCrazyflieUsd);
  const LogData log = geaware::io::readLog(file);
  EXPECT_EQ(log.source, file.string());
  const auto map = geaware::io::loadLogMap("crazyflie");
  const auto m =
      geaware::io::mapFlight(log, map, {"height", "specific_force", "attitude", "rotor_speed"});
  ASSERT_EQ(m.size(), 50u);
  EXPECT_DOUBLE_EQ(m.t_s[1], 2.01);  // the log's own time, not a CSV's ms timestamp
  EXPECT_NEAR(m.h_m[2], 0.102, 1e-7);
  EXPECT_DOUBLE_EQ(m.f_B_mps2[2][0], 9.80665);
  EXPECT_DOUBLE_EQ(m.n_rpm[3][0], 15100.0);  // rotor 4 (rear-right) is the Crazyflie's m2
  const auto fixed = dir / "log01";
  const Bytes g = fixedLog();
  std::ofstream(fixed, std::ios::binary)
      .write(reinterpret_cast<const char*>(g.b.data()), static_cast<std::streamsize>(g.size()));
  EXPECT_EQ(geaware::io::detectLogFormat(fixed), geaware::io::LogFormat::kCrazyflieUsd);
  EXPECT_EQ(geaware::io::readLog(fixed).topics[0].size(), 3u);
  // A CSV stays a CSV.
  const auto csv = dir / "log.csv";
  std::ofstream(csv) << "t_s,z\n0,1\n";
  EXPECT_EQ(geaware::io::detectLogFormat(csv), geaware::io::LogFormat::kCsv);
}

}  // namespace
