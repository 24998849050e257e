// SPDX-License-Identifier: BSD-3-Clause
// The ULog reader against PX4's own reader: tests/fixtures/px4/ holds two real logs from pyulog's
// test data and oracle/ what pyulog reads from them (one CSV per topic instance, values printed
// with full precision). Every topic instance, field and value of the oracle must come back:
// timestamps exactly, integers exactly, floats bitwise (a float32 widened to double is exact, so
// pyulog's double and ours are the same bits; NaN matches NaN). Then the ways a file goes bad.

#include "geaware/io/log_channels.hpp"
#include "geaware/io/log_inspect.hpp"

#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace {

namespace fs = std::filesystem;
using geaware::io::LogData;
using geaware::io::LogError;
using geaware::io::readULog;

fs::path fixtures() {
  const char* dir = std::getenv("GEAWARE_SOURCE_DIR");
  return fs::path(dir != nullptr ? dir : ".") / "tests" / "fixtures" / "px4";
}

std::vector<std::byte> bytesOf(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  const std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::byte> b(s.size());
  std::memcpy(b.data(), s.data(), s.size());
  return b;
}

struct OracleTable {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
};

OracleTable readOracle(const fs::path& f) {
  OracleTable t;
  std::ifstream in(f);
  std::string line;
  std::getline(in, line);
  std::stringstream header(line);
  for (std::string cell; std::getline(header, cell, ',');) t.names.push_back(cell);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::strtod(cell.c_str(), nullptr));
    EXPECT_EQ(row.size(), t.names.size()) << f << ": " << line;
    t.rows.push_back(std::move(row));
  }
  return t;
}

bool sameValue(double a, double b) {
  if (std::isnan(a) && std::isnan(b)) return true;
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// Every oracle file of `log` (FILE.TOPIC_INSTANCE.csv) against what readULog reads.
void agreeWithOracle(const std::string& log_name, std::size_t expected_tables) {
  const LogData log = readULog(fixtures() / (log_name + ".ulg"));
  EXPECT_EQ(log.format, "ulog");
  std::size_t tables = 0;
  std::size_t values = 0;
  for (const auto& entry : fs::directory_iterator(fixtures() / "oracle")) {
    const std::string file = entry.path().filename().string();
    if (!file.starts_with(log_name + ".")) continue;
    const std::string stem = file.substr(log_name.size() + 1, file.size() - log_name.size() - 5);
    const auto us = stem.rfind('_');
    const std::string topic_name = stem.substr(0, us);
    const auto instance = static_cast<unsigned>(std::stoul(stem.substr(us + 1)));
    SCOPED_TRACE(file);
    const auto* topic = log.topic(topic_name, instance);
    ASSERT_NE(topic, nullptr) << "topic " << topic_name << " instance " << instance << " not read";
    const OracleTable oracle = readOracle(entry.path());
    ++tables;
    // The same fields, no more and no fewer (trailing padding dropped as pyulog drops it).
    ASSERT_EQ(topic->channels.size(), oracle.names.size());
    ASSERT_EQ(topic->size(), oracle.rows.size());
    for (std::size_t c = 0; c < oracle.names.size(); ++c) {
      const auto* channel = topic->channel(oracle.names[c]);
      ASSERT_NE(channel, nullptr) << "field " << oracle.names[c] << " not read";
      ASSERT_EQ(channel->values.size(), oracle.rows.size());
      for (std::size_t r = 0; r < oracle.rows.size(); ++r) {
        ASSERT_TRUE(sameValue(channel->values[r], oracle.rows[r][c]))
            << oracle.names[c] << " row " << r << ": read " << channel->values[r] << ", pyulog "
            << oracle.rows[r][c];
        ++values;
      }
    }
    // The time axis is the timestamp [µs] in seconds.
    const auto* ts = topic->channel("timestamp");
    ASSERT_NE(ts, nullptr);
    EXPECT_EQ(ts->type, geaware::io::FieldType::kUInt64);
    EXPECT_EQ(ts->unit, "us");
    for (std::size_t r = 0; r < topic->size(); ++r) ASSERT_EQ(topic->time_s[r], ts->values[r] * 1e-6);
  }
  EXPECT_EQ(tables, expected_tables);
  EXPECT_GT(values, 1000u);
}

TEST(ULogReader, AgreesWithPyulogOnARecentPx4Log) { agreeWithOracle("sample_px4_events", 8); }

TEST(ULogReader, AgreesWithPyulogOnAnOlderLogWithMultiInstanceTopics) {
  agreeWithOracle("sample_log_small", 10);
}

TEST(ULogReader, KeepsFieldTypesInfoParametersAndMessages) {
  const LogData log = readULog(fixtures() / "sample_px4_events.ulg");
  const auto* esc = log.topic("esc_status");
  ASSERT_NE(esc, nullptr);
  EXPECT_EQ(esc->channel("esc[0].esc_rpm")->type, geaware::io::FieldType::kInt32);
  EXPECT_EQ(esc->channel("esc[0].esc_voltage")->type, geaware::io::FieldType::kFloat);
  EXPECT_EQ(log.topic("sensor_combined")->channel("gyro_rad[2]")->type, geaware::io::FieldType::kFloat);
  EXPECT_FALSE(log.parameters.empty());
  EXPECT_TRUE(log.info.contains("sys_name"));
  EXPECT_TRUE(log.warnings.empty()) << log.warnings.front();
}

TEST(ULogReader, MemoryAndFileGiveTheSameLog) {
  const auto file = fixtures() / "sample_log_small.ulg";
  const auto bytes = bytesOf(file);
  const LogData a = readULog(file);
  const LogData b = readULog(bytes, "memory");
  ASSERT_EQ(a.topics.size(), b.topics.size());
  for (std::size_t i = 0; i < a.topics.size(); ++i) {
    ASSERT_EQ(a.topics[i].channels.size(), b.topics[i].channels.size());
    EXPECT_EQ(a.topics[i].time_s, b.topics[i].time_s);
    for (std::size_t c = 0; c < a.topics[i].channels.size(); ++c) {
      const auto& x = a.topics[i].channels[c].values;
      const auto& y = b.topics[i].channels[c].values;
      ASSERT_EQ(x.size(), y.size());
      for (std::size_t k = 0; k < x.size(); ++k) ASSERT_TRUE(sameValue(x[k], y[k]));
    }
  }
  EXPECT_EQ(a.parameters, b.parameters);
}

TEST(ULogReader, ReadsOnlyTheTopicsAskedFor) {
  geaware::io::LogReadOptions o;
  o.topics = {"vehicle_imu"};
  const LogData log = readULog(fixtures() / "sample_log_small.ulg", o);
  ASSERT_EQ(log.topics.size(), 3u);  // three instances
  for (const auto& t : log.topics) EXPECT_EQ(t.name, "vehicle_imu");
}

TEST(ULogReader, ATruncatedLogIsReadUpToTheCutWithAWarning) {
  auto bytes = bytesOf(fixtures() / "sample_px4_events.ulg");
  const LogData whole = readULog(bytes, "whole");
  bytes.resize(bytes.size() * 2 / 3 + 1);
  const LogData cut = readULog(bytes, "cut.ulg");
  ASSERT_FALSE(cut.warnings.empty());
  EXPECT_NE(cut.warnings.front().find("cut off"), std::string::npos) << cut.warnings.front();
  const auto* a = whole.topic("sensor_combined");
  const auto* b = cut.topic("sensor_combined");
  ASSERT_NE(b, nullptr);
  EXPECT_LT(b->size(), a->size());
  EXPECT_GT(b->size(), a->size() / 3);
  for (std::size_t i = 0; i < b->size(); ++i) ASSERT_EQ(a->time_s[i], b->time_s[i]);
}

TEST(ULogReader, NotAULogFileNamesTheFileAndOffset) {
  const std::string text = "t_s,h_m\n0,1\n";
  std::vector<std::byte> b(text.size());
  std::memcpy(b.data(), text.data(), text.size());
  try {
    (void)readULog(b, "flight.csv");
    FAIL() << "no error";
  } catch (const LogError& e) {
    EXPECT_EQ(e.file(), "flight.csv");
    EXPECT_TRUE(e.hasOffset());
    EXPECT_EQ(e.offset(), 0u);
    EXPECT_NE(std::string(e.what()).find("not a ULog file"), std::string::npos) << e.what();
  }
}

TEST(ULogReader, ADataMessageOfTheWrongSizeIsAnErrorAtItsOffset) {
  auto bytes = bytesOf(fixtures() / "sample_px4_events.ulg");
  // Find the first data message by walking the framing, then grow its declared size by one
  // and shift the rest: the payload no longer matches its format.
  std::size_t at = 16;
  for (;;) {
    std::uint16_t size = 0;
    std::memcpy(&size, bytes.data() + at, 2);
    if (static_cast<char>(bytes[at + 2]) == 'D') {
      ++size;
      std::memcpy(bytes.data() + at, &size, 2);
      bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(at + 3), std::byte{0});
      break;
    }
    at += 3 + size;
  }
  try {
    (void)readULog(bytes, "grown.ulg");
    FAIL() << "no error";
  } catch (const LogError& e) {
    EXPECT_EQ(e.offset(), at);
    EXPECT_NE(std::string(e.what()).find("its format"), std::string::npos) << e.what();
  }
}

TEST(ULogReader, AnUnknownMessageTypeSkipsToTheNextSyncMarker) {
  auto bytes = bytesOf(fixtures() / "sample_px4_events.ulg");
  const LogData whole = readULog(bytes, "whole");
  // Corrupt the type byte of a message in the middle.
  std::size_t at = 16;
  while (at < bytes.size() / 2) {
    std::uint16_t size = 0;
    std::memcpy(&size, bytes.data() + at, 2);
    at += 3 + size;
  }
  bytes[at + 2] = std::byte{'~'};
  const LogData bad = readULog(bytes, "corrupt.ulg");
  ASSERT_FALSE(bad.warnings.empty());
  EXPECT_NE(bad.warnings.front().find("byte " + std::to_string(at)), std::string::npos) << bad.warnings.front();
  // What follows the next sync marker is read again.
  EXPECT_GT(bad.topic("sensor_combined")->size(), whole.topic("sensor_combined")->size() / 2 + 100);
}

TEST(ULogReader, ALogLargerThanAllowedIsRefusedUnread) {
  geaware::io::LogReadOptions o;
  o.max_bytes = 1000;
  try {
    (void)readULog(fixtures() / "sample_log_small.ulg", o);
    FAIL() << "no error";
  } catch (const LogError& e) {
    EXPECT_NE(std::string(e.what()).find("sample_log_small.ulg"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("refused unread"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)readULog(fixtures() / "no_such.ulg"), LogError);
  EXPECT_THROW((void)readULog(fixtures()), LogError);  // a directory
}

}  // namespace

namespace {

// Data appended after a cut (PX4 writes it after a crash, flag bit DATA_APPENDED): the message
// cut short at the appended offset is skipped and reading resumes there.
TEST(ULogReader, DataAppendedAfterACutMessageIsRead) {
  const auto bytes = bytesOf(fixtures() / "sample_px4_events.ulg");
  const LogData whole = readULog(bytes, "whole");
  ASSERT_EQ(static_cast<char>(bytes[18]), 'B');  // flag bits first, as the format requires
  std::size_t at = 16;
  while (at < bytes.size() / 2) {
    std::uint16_t size = 0;
    std::memcpy(&size, bytes.data() + at, 2);
    at += 3 + size;
  }
  // The first 5 bytes of the message at `at`, cut; then the rest of the file again from `at`.
  std::vector<std::byte> cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(at + 5));
  cut.insert(cut.end(), bytes.begin() + static_cast<std::ptrdiff_t>(at), bytes.end());
  cut[16 + 3 + 8] = std::byte{1};  // incompat_flags[0]: data appended
  const std::uint64_t appended = at + 5;
  std::memcpy(cut.data() + 16 + 3 + 16, &appended, 8);
  const LogData read = readULog(cut, "appended.ulg");
  ASSERT_EQ(read.warnings.size(), 1u);
  EXPECT_NE(read.warnings[0].find("appended data at byte " + std::to_string(appended)), std::string::npos)
      << read.warnings[0];
  ASSERT_EQ(read.topics.size(), whole.topics.size());
  for (std::size_t i = 0; i < whole.topics.size(); ++i) EXPECT_EQ(read.topics[i].time_s, whole.topics[i].time_s);
  // Without the flag bit the same bytes are corrupt, and other incompatible bits are refused.
  cut[16 + 3 + 8] = std::byte{2};
  EXPECT_THROW((void)readULog(cut, "unknown-flags.ulg"), LogError);
}

}  // namespace

namespace {

void message(std::vector<std::byte>& b, char type, const std::string& payload) {
  const auto size = static_cast<std::uint16_t>(payload.size());
  b.push_back(static_cast<std::byte>(size & 0xff));
  b.push_back(static_cast<std::byte>(size >> 8));
  b.push_back(static_cast<std::byte>(type));
  for (const char c : payload) b.push_back(static_cast<std::byte>(c));
}

// Memory is bounded: each 4-byte subscription of a 65,001-field format would cost ~5 MB.
TEST(ULogReader, SubscriptionsOfMoreThanAMillionFieldsAreRefused) {
  std::vector<std::byte> b;
  for (const int c : {0x55, 0x4c, 0x6f, 0x67, 0x01, 0x12, 0x35, 0x01}) b.push_back(static_cast<std::byte>(c));
  for (int i = 0; i < 8; ++i) b.push_back(std::byte{0});
  message(b, 'B', std::string(40, '\0'));
  message(b, 'F', "big:uint64_t timestamp;uint8_t[65000] x;");
  for (int id = 0; id < 20; ++id) {
    std::string sub = {'\0', static_cast<char>(id), '\0'};
    message(b, 'A', sub + "big");
  }
  try {
    (void)readULog(b, "many.ulg");
    FAIL() << "no error";
  } catch (const LogError& e) {
    EXPECT_NE(std::string(e.what()).find("fields subscribed in all"), std::string::npos) << e.what();
  }
}

}  // namespace

namespace {

std::string bytesOfValue(const auto& v) {
  std::string out(sizeof v, '\0');
  std::memcpy(out.data(), &v, sizeof v);
  return out;
}

// A dropout message ('O', its uint16 duration in ms; ULog format specification) is kept with the
// time of the last message before it, the data around it is read, and `logs inspect` lists it.
TEST(ULogReader, DropoutsAreKeptWithTheirTimeAndDuration) {
  std::vector<std::byte> b;
  for (const int c : {0x55, 0x4c, 0x6f, 0x67, 0x01, 0x12, 0x35, 0x01}) b.push_back(static_cast<std::byte>(c));
  for (int i = 0; i < 8; ++i) b.push_back(std::byte{0});
  message(b, 'B', std::string(40, '\0'));
  message(b, 'F', "t:uint64_t timestamp;float x;");
  message(b, 'A', std::string{'\0', '\0', '\0'} + "t");
  const auto data = [&](std::uint64_t t_us, float x) {
    message(b, 'D', std::string(2, '\0') + bytesOfValue(t_us) + bytesOfValue(x));
  };
  data(1'000'000, 1.0f);
  data(1'010'000, 2.0f);
  message(b, 'O', bytesOfValue(std::uint16_t{250}));  // 250 ms lost
  data(1'270'000, 3.0f);
  message(b, 'O', bytesOfValue(std::uint16_t{65535}));
  const LogData log = readULog(b, "dropouts.ulg");
  ASSERT_EQ(log.dropouts.size(), 2u);
  EXPECT_DOUBLE_EQ(log.dropouts[0].time_s, 1.01);
  EXPECT_DOUBLE_EQ(log.dropouts[0].duration_s, 0.25);
  EXPECT_DOUBLE_EQ(log.dropouts[1].time_s, 1.27);
  EXPECT_DOUBLE_EQ(log.dropouts[1].duration_s, 65.535);
  ASSERT_EQ(log.topics.size(), 1u);
  EXPECT_EQ(log.topics[0].time_s, (std::vector<double>{1.0, 1.01, 1.27}));
  EXPECT_EQ(log.topics[0].channel("x")->values, (std::vector<double>{1.0, 2.0, 3.0}));
  const std::string text = geaware::io::summaryText(geaware::io::inspectLog(log));
  EXPECT_NE(text.find("2 dropouts"), std::string::npos) << text;
  EXPECT_NE(text.find("dropout at t = 0.010 s for 0.25 s"), std::string::npos) << text;
  // A dropout message of the wrong size is an error at its offset, not a value read past it.
  const std::uint64_t offset = b.size();
  message(b, 'O', "x");
  try {
    (void)readULog(b, "short-dropout.ulg");
    FAIL() << "no error";
  } catch (const LogError& e) {
    EXPECT_TRUE(e.hasOffset());
    EXPECT_EQ(e.offset(), offset) << e.what();
  }
}

}  // namespace
