// SPDX-License-Identifier: BSD-3-Clause
// The DataFlash reader against the published format, not against a real log (none is in the
// repository): a small writer here builds .bin bytes field by field from ArduPilot's description
// (AP_Logger/LogStructure.h: A3 95 header, FMT = type 128 "BBnNZ" of 89 bytes, FMTU "QBNN",
// UNIT "QbZ", MULT "Qbd", PARM "QNf"; the format characters and their sizes), independently of
// the reader's tables. Every format character is logged with a known raw value and checked,
// with FMTU multipliers and units applied, text fields left out, instances split.

#include "geaware/io/log_channels.hpp"
#include "geaware/io/log_map.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace {

using geaware::io::FieldType;
using geaware::io::LogData;
using geaware::io::LogError;
using geaware::io::readDataFlash;

class Writer {
 public:
  template <typename T>
  Writer& put(T v) {
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    bytes.insert(bytes.end(), p, p + sizeof v);
    return *this;
  }
  Writer& text(const std::string& s, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) bytes.push_back(i < s.size() ? static_cast<std::byte>(s[i]) : std::byte{0});
    return *this;
  }
  Writer& head(std::uint8_t type) { return put<std::uint8_t>(0xa3).put<std::uint8_t>(0x95).put(type); }
  Writer& fmt(std::uint8_t type, std::uint8_t length, const std::string& name, const std::string& format,
              const std::string& labels) {
    return head(128).put(type).put(length).text(name, 4).text(format, 16).text(labels, 64);
  }
  Writer& fmtu(std::uint64_t t_us, std::uint8_t type, const std::string& units, const std::string& mults) {
    return head(131).put(t_us).put(type).text(units, 16).text(mults, 16);
  }
  std::vector<std::byte> bytes;
};

// Sizes by hand: b B M 1, h H c C 2, i I f e E L 4, d q Q 8, n 4, N 16, Z 64, a 64.
Writer sampleLog() {
  Writer w;
  w.fmt(128, 89, "FMT", "BBnNZ", "Type,Length,Name,Format,Columns");
  w.fmt(129, 3 + 8 + 1 + 64, "UNIT", "QbZ", "TimeUS,Id,Label");
  w.fmt(130, 3 + 8 + 1 + 8, "MULT", "Qbd", "TimeUS,Id,Mult");
  w.fmt(131, 3 + 8 + 1 + 16 + 16, "FMTU", "QBNN", "TimeUS,FmtType,UnitIds,MultIds");
  w.fmt(132, 3 + 8 + 16 + 4, "PARM", "QNf", "TimeUS,Name,Value");
  w.fmt(134, 3 + 8 + 1 + 1 + 2 + 2 + 4 + 4 + 4 + 8 + 2 + 2 + 4 + 4, "TSA", "QbBhHiIfdcCeE",
        "TimeUS,B1,UB,H1,UH,I1,UI,F,D,C1,UC,E1,UE");
  w.fmt(135, 3 + 8 + 4 + 16 + 64 + 4 + 1 + 8 + 8 + 64, "TSB", "QnNZLMqQa", "TimeUS,Nm,Nn,Zz,Lat,Mode,Q1,UQ,Arr");
  w.fmt(136, 3 + 8 + 1 + 4 + 4, "IMU", "QBff", "TimeUS,I,GyrX,AccZ");
  for (const auto& [id, label] : std::vector<std::pair<char, std::string>>{
           {'s', "s"}, {'#', "instance"}, {'E', "rad/s"}, {'o', "m/s/s"}, {'d', "deg"}, {'D', "deglatitude"}, {'m', "m"}}) {
    w.head(129).put<std::uint64_t>(0).put(static_cast<std::int8_t>(id)).text(label, 64);
  }
  for (const auto& [id, mult] : std::vector<std::pair<char, double>>{{'F', 1e-6}, {'0', 1.0}, {'B', 1e-2}, {'C', 1e-3}, {'G', 1e-7}}) {
    w.head(130).put<std::uint64_t>(0).put(static_cast<std::int8_t>(id)).put(mult);
  }
  w.fmtu(0, 134, "s-------dd--m", "F--C-----B-0?");
  w.fmtu(0, 135, "s---D----", "F---G----");
  w.fmtu(0, 136, "s#Eo", "F-00");
  w.head(132).put<std::uint64_t>(5).text("MOT_PWM_MIN", 16).put(1000.0f);
  for (int i = 0; i < 3; ++i) {
    w.head(134).put<std::uint64_t>(1000000 + 2500 * static_cast<std::uint64_t>(i));
    w.put<std::int8_t>(-5).put<std::uint8_t>(250).put<std::int16_t>(-1234).put<std::uint16_t>(60000);
    w.put<std::int32_t>(-100000 - i).put<std::uint32_t>(4000000000u).put(1.5f).put(0.1);
    w.put<std::int16_t>(-4512).put<std::uint16_t>(65000).put<std::int32_t>(-123456).put<std::uint32_t>(4000000000u);
    w.put<std::uint8_t>(0x00).put<std::uint8_t>(0x13).put<std::uint8_t>(0x37);  // junk between messages
  }
  w.head(135).put<std::uint64_t>(2000000).text("ab", 4).text("name", 16).text("a longer text", 64);
  w.put<std::int32_t>(473977418).put<std::uint8_t>(5).put<std::int64_t>(-(std::int64_t{1} << 40));
  w.put<std::uint64_t>(std::uint64_t{1} << 53);
  for (int k = 0; k < 32; ++k) w.put<std::int16_t>(static_cast<std::int16_t>(-3 * k));
  for (int i = 0; i < 4; ++i) {
    for (std::uint8_t inst = 0; inst < 2; ++inst) {
      w.head(136).put<std::uint64_t>(3000000 + 1000 * static_cast<std::uint64_t>(i)).put(inst);
      w.put(static_cast<float>(0.25 * i + inst)).put(-9.75f);
    }
  }
  return w;
}

TEST(DataFlashReader, ReadsEveryFormatCharacterAsThePublishedFormatSays) {
  const LogData log = readDataFlash(sampleLog().bytes, "sample.bin");
  EXPECT_EQ(log.format, "dataflash");
  const auto* a = log.topic("TSA");
  ASSERT_NE(a, nullptr);
  ASSERT_EQ(a->size(), 3u);
  const auto v = [&](const char* name, std::size_t row = 0) {
    const auto* c = a->channel(name);
    EXPECT_NE(c, nullptr) << name;
    return c == nullptr ? NAN : c->values.at(row);
  };
  EXPECT_DOUBLE_EQ(a->time_s[1], 1.0025);
  EXPECT_EQ(v("TimeUS", 2), 1.005);          // FMTU 'F': µs → s, divided by 10^6
  EXPECT_EQ(a->channel("TimeUS")->unit, "s");
  EXPECT_EQ(v("B1"), -5.0);
  EXPECT_EQ(v("UB"), 250.0);
  EXPECT_EQ(v("H1"), -1234.0 / 1000.0);      // 'C' = 1e-3
  EXPECT_EQ(v("UH"), 60000.0);
  EXPECT_EQ(v("I1", 2), -100002.0);
  EXPECT_EQ(v("UI"), 4000000000.0);
  EXPECT_EQ(v("F"), 1.5);
  EXPECT_EQ(v("D"), 0.1);
  EXPECT_EQ(v("C1"), -4512.0 / 100.0);        // 'c' with FMTU 'B': scaled once, not twice
  EXPECT_EQ(a->channel("C1")->unit, "deg");
  EXPECT_EQ(v("UC"), 650.0);                  // 'C' without a multiplier: the ·100 of the format
  EXPECT_EQ(v("E1"), -123456.0);              // FMTU '0' (×1) replaces the format's ·100
  EXPECT_EQ(v("UE"), 40000000.0);             // '?' (unknown): the format's ·100
  EXPECT_EQ(a->channel("UE")->unit, "m");
  EXPECT_EQ(a->channel("H1")->type, FieldType::kInt16);
  EXPECT_EQ(a->channel("UE")->type, FieldType::kUInt32);

  const auto* b = log.topic("TSB");
  ASSERT_NE(b, nullptr);
  ASSERT_EQ(b->size(), 1u);
  EXPECT_EQ(b->channel("Nm"), nullptr);  // text fields are not channels
  EXPECT_EQ(b->channel("Zz"), nullptr);
  EXPECT_EQ(b->channel("Lat")->values[0], 473977418.0 / 1e7);
  EXPECT_EQ(b->channel("Lat")->unit, "deglatitude");
  EXPECT_EQ(b->channel("Mode")->values[0], 5.0);
  EXPECT_EQ(b->channel("Q1")->values[0], -1099511627776.0);
  EXPECT_EQ(b->channel("UQ")->values[0], 9007199254740992.0);
  for (int k = 0; k < 32; ++k) EXPECT_EQ(b->channel("Arr[" + std::to_string(k) + "]")->values[0], -3.0 * k);

  // The instance field (unit '#') splits IMU into two topic instances.
  for (unsigned inst = 0; inst < 2; ++inst) {
    const auto* imu = log.topic("IMU", inst);
    ASSERT_NE(imu, nullptr) << inst;
    ASSERT_EQ(imu->size(), 4u);
    EXPECT_EQ(imu->channel("GyrX")->values[2], 0.5 + inst);
    EXPECT_EQ(imu->channel("GyrX")->unit, "rad/s");
    EXPECT_EQ(imu->channel("AccZ")->values[3], -9.75);
    EXPECT_DOUBLE_EQ(imu->time_s[3], 3.003);
  }
  EXPECT_EQ(log.parameters.at("MOT_PWM_MIN"), 1000.0);
  // The junk between messages is skipped and reported with its offset.
  ASSERT_EQ(log.warnings.size(), 3u);
  EXPECT_NE(log.warnings[0].find("3 bytes that start no known message"), std::string::npos) << log.warnings[0];
}

TEST(DataFlashReader, ACutOffLastMessageIsAWarning) {
  auto bytes = sampleLog().bytes;
  bytes.resize(bytes.size() - 5);
  const LogData log = readDataFlash(bytes, "cut.bin");
  EXPECT_EQ(log.topic("IMU", 1)->size(), 3u);
  EXPECT_NE(log.warnings.back().find("cut off"), std::string::npos) << log.warnings.back();
}

TEST(DataFlashReader, BadFilesAreErrorsNamingTheFileAndOffset) {
  const auto expectError = [](const std::vector<std::byte>& bytes, std::uint64_t offset, const std::string& what) {
    try {
      (void)readDataFlash(bytes, "bad.bin");
      FAIL() << "no error for " << what;
    } catch (const LogError& e) {
      EXPECT_EQ(e.file(), "bad.bin");
      EXPECT_EQ(e.offset(), offset) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  Writer text;
  text.text("TimeUS,Alt\n1,2\n", 15);
  expectError(text.bytes, 0, "not a DataFlash log");

  Writer w;
  w.fmt(128, 89, "FMT", "BBnNZ", "Type,Length,Name,Format,Columns");
  const auto at = w.bytes.size();
  w.fmt(140, 20, "BAD", "Qf", "TimeUS,X");  // 3 + 8 + 4 = 15, not 20
  expectError(w.bytes, at, "its length says 20");

  Writer u;
  u.fmt(128, 89, "FMT", "BBnNZ", "Type,Length,Name,Format,Columns");
  u.fmt(141, 12, "UNK", "Qx", "TimeUS,X");
  expectError(u.bytes, 89, "unknown format character 'x'");

  Writer l;
  l.fmt(128, 89, "FMT", "BBnNZ", "Type,Length,Name,Format,Columns");
  l.fmt(142, 15, "LBL", "Qf", "TimeUS");
  expectError(l.bytes, 89, "2 format characters");
}

TEST(DataFlashReader, AnInstanceFieldWithManyValuesIsNotSplit) {
  Writer w;
  w.fmt(128, 89, "FMT", "BBnNZ", "Type,Length,Name,Format,Columns");
  w.fmt(129, 3 + 8 + 1 + 64, "UNIT", "QbZ", "TimeUS,Id,Label");
  w.fmt(131, 3 + 8 + 1 + 16 + 16, "FMTU", "QBNN", "TimeUS,FmtType,UnitIds,MultIds");
  w.fmt(136, 3 + 8 + 4, "INS", "QI", "TimeUS,I");
  w.head(129).put<std::uint64_t>(0).put(static_cast<std::int8_t>('#')).text("instance", 64);
  w.fmtu(0, 136, "-#", "--");
  for (std::uint32_t i = 0; i < 40; ++i) w.head(136).put<std::uint64_t>(i).put(i * 1000u);
  const LogData log = readDataFlash(w.bytes, "ins.bin");
  ASSERT_NE(log.topic("INS"), nullptr);
  EXPECT_EQ(log.topic("INS")->size(), 40u);
  ASSERT_EQ(log.warnings.size(), 1u);
  EXPECT_NE(log.warnings[0].find("40 distinct instance numbers"), std::string::npos) << log.warnings[0];
}

// A log may declare UNIT, MULT and FMTU with any format: a hostile or corrupt one puts an 8-byte
// float or integer where ArduPilot puts one byte (the fuzz target found Id = 8.3e18, whose
// conversion to char was undefined behaviour). Such ids name nothing: each message is a warning
// and the rest of the log is read as before.
TEST(DataFlashReader, MetadataIdsOutsideOneByteAreWarningsNotConversions) {
  Writer w;
  w.fmt(128, 89, "FMT", "BBnNZ", "Type,Length,Name,Format,Columns");
  w.fmt(129, 3 + 8 + 8 + 64, "UNIT", "QdZ", "TimeUS,Id,Label");
  w.fmt(130, 3 + 8 + 8 + 8, "MULT", "QQd", "TimeUS,Id,Mult");
  w.fmt(131, 3 + 8 + 8 + 16 + 16, "FMTU", "QdNN", "TimeUS,FmtType,UnitIds,MultIds");
  w.fmt(136, 3 + 8 + 4, "ALT", "Qf", "TimeUS,Alt");
  w.head(129).put<std::uint64_t>(0).put(8.28662e18).text("huge", 64);
  w.head(129).put<std::uint64_t>(0).put(std::nan("")).text("nan", 64);
  w.head(129).put<std::uint64_t>(0).put(-1.0).text("negative", 64);
  w.head(129).put<std::uint64_t>(0).put(static_cast<double>('m')).text("m", 64);
  w.head(130).put<std::uint64_t>(0).put(std::uint64_t{1} << 63).put(1e-3);
  w.head(130).put<std::uint64_t>(0).put(std::uint64_t{'C'}).put(1e-3);
  w.head(131).put<std::uint64_t>(0).put(1e300).text("-m", 16).text("-C", 16);
  w.head(131).put<std::uint64_t>(0).put(136.5).text("-m", 16).text("-C", 16);
  w.head(131).put<std::uint64_t>(0).put(136.0).text("-m", 16).text("-C", 16);
  w.head(136).put<std::uint64_t>(1000).put(2500.0f);
  const LogData log = readDataFlash(w.bytes, "ids.bin");
  ASSERT_EQ(log.warnings.size(), 6u);
  for (const std::string expected :
       {"UNIT with id 8.28662e+18", "UNIT with id nan", "UNIT with id -1", "MULT with id 9.22337204e+18",
        "FMTU for type 1e+300", "FMTU for type 136.5"}) {
    bool found = false;
    for (const auto& message : log.warnings) found = found || message.find(expected) != std::string::npos;
    EXPECT_TRUE(found) << "no warning containing '" << expected << "'";
  }
  const auto* alt = log.topic("ALT");
  ASSERT_NE(alt, nullptr);
  ASSERT_EQ(alt->size(), 1u);
  const auto* metres = alt->channel("Alt");
  ASSERT_NE(metres, nullptr);
  EXPECT_EQ(metres->unit, "m");
  EXPECT_DOUBLE_EQ(metres->values[0], 2.5);  // 2500 with multiplier C = 1e-3
}

// The whole chain on a log laid out as ArduPilot writes these messages (ATT's centidegree 'c'/'C'
// fields with multiplier B, ESC's 'e' RPM, one ESC instance per motor, FMTU instance fields):
// the reader splits and scales, the ardupilot map converts NED/FRD Euler angles to ENU/FLU.
TEST(DataFlashReader, ThroughTheArduPilotMap) {
  Writer w;
  w.fmt(128, 89, "FMT", "BBnNZ", "Type,Length,Name,Format,Columns");
  w.fmt(129, 3 + 8 + 1 + 64, "UNIT", "QbZ", "TimeUS,Id,Label");
  w.fmt(130, 3 + 8 + 1 + 8, "MULT", "Qbd", "TimeUS,Id,Mult");
  w.fmt(131, 3 + 8 + 1 + 16 + 16, "FMTU", "QBNN", "TimeUS,FmtType,UnitIds,MultIds");
  w.fmt(140, 3 + 8 + 1 + 24, "IMU", "QBffffff", "TimeUS,I,GyrX,GyrY,GyrZ,AccX,AccY,AccZ");
  w.fmt(141, 3 + 8 + 4 * 2 + 2 * 2, "ATT", "QccccCC", "TimeUS,DesRoll,Roll,DesPitch,Pitch,DesYaw,Yaw");
  w.fmt(142, 3 + 8 + 1 + 4, "RFND", "QBf", "TimeUS,Instance,Dist");
  w.fmt(143, 3 + 8 + 1 + 4 + 4 + 4, "ESC", "QBeef", "TimeUS,Instance,RPM,RawRPM,Volt");
  for (const auto& [id, label] : std::vector<std::pair<char, std::string>>{
           {'s', "s"}, {'#', "instance"}, {'E', "rad/s"}, {'o', "m/s/s"}, {'d', "deg"}, {'m', "m"}, {'q', "rpm"}, {'v', "V"}}) {
    w.head(129).put<std::uint64_t>(0).put(static_cast<std::int8_t>(id)).text(label, 64);
  }
  for (const auto& [id, mult] : std::vector<std::pair<char, double>>{{'F', 1e-6}, {'0', 1.0}, {'B', 1e-2}}) {
    w.head(130).put<std::uint64_t>(0).put(static_cast<std::int8_t>(id)).put(mult);
  }
  w.fmtu(0, 140, "s#EEEooo", "F-000000");
  w.fmtu(0, 141, "sdddddd", "FBBBBBB");
  w.fmtu(0, 142, "s#m", "F-0");
  w.fmtu(0, 143, "s#qqv", "F-BB0");
  for (std::uint64_t i = 0; i < 40; ++i) {
    const std::uint64_t t = 1000000 + 25000 * i;  // 40 Hz
    w.head(140).put(t).put<std::uint8_t>(0).put(0.0f).put(0.0f).put(0.0f).put(0.0f).put(0.0f).put(-9.81f);
    w.head(141).put(t).put<std::int16_t>(0).put<std::int16_t>(0).put<std::int16_t>(0).put<std::int16_t>(0);
    w.put<std::uint16_t>(9000).put<std::uint16_t>(9000);  // yaw 90.00°: nose east
    w.head(142).put(t).put<std::uint8_t>(0).put(0.3f);
    for (std::uint8_t m = 0; m < 4; ++m) {
      w.head(143).put(t + m).put(m).put<std::int32_t>(450000 + 100 * m).put<std::int32_t>(0).put(15.9f);
    }
  }
  const LogData log = readDataFlash(w.bytes, "ap.bin");
  ASSERT_TRUE(log.warnings.empty()) << log.warnings.front();
  ASSERT_NE(log.topic("ESC", 3), nullptr);
  const auto map = geaware::io::loadLogMap("ardupilot");
  const auto f = geaware::io::mapFlight(log, map, {"height", "specific_force", "attitude", "rotor_speed"});
  ASSERT_GE(f.size(), 38u);
  EXPECT_NEAR(f.n_rpm[0][5], 4500.0, 1e-9);  // 'e' with multiplier B: ÷100 once
  EXPECT_NEAR(f.n_rpm[3][5], 4503.0, 1e-9);
  EXPECT_NEAR(f.h_m[5], 0.3, 1e-6);
  EXPECT_NEAR(f.f_B_mps2[2][5], 9.81, 1e-6);
  EXPECT_NEAR(std::abs(f.q_WB[0][5]), 1.0, 1e-9);  // nose east in NED = yaw 0 in ENU
}

}  // namespace
