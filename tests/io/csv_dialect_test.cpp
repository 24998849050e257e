// SPDX-License-Identifier: BSD-3-Clause
// CSV dialects of lab and autopilot exports: a header line starting with '#', delimiters other
// than the comma (detected), units in the header (`z[mm]`, `z (mm)`); and readLog on CSV.

#include "geaware/io/csv_reader.hpp"
#include "geaware/io/log_channels.hpp"

#include <charconv>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

namespace {

using geaware::io::CsvError;
using geaware::io::CsvReadOptions;
using geaware::io::readCsv;

class CsvDialect : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) /
           (std::string("geaware_csv_dialect_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  std::filesystem::path file(const std::string& text) {
    const auto f = dir_ / "log.csv";
    std::ofstream(f, std::ios::binary) << text;
    return f;
  }
  static CsvReadOptions tz() {
    CsvReadOptions o;
    o.columns = {{"t_s"}, {"z"}};
    return o;
  }
  std::filesystem::path dir_;
};

TEST_F(CsvDialect, AHashLineFollowedByDataIsTheHeader) {
  // The lab export: the first data row used to become the header.
  const auto t = readCsv(file("# t_s,z\n-2.29e-02,0.5\n0.1,0.25\n"), tz());
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.first_data_line, 2u);
  EXPECT_EQ(t.column("t_s")[0], -2.29e-02);
  EXPECT_EQ(t.column("z")[1], 0.25);
  // Comments before it stay comments; the last '#' line before the data is the header.
  const auto u = readCsv(file("# exported by rig v2\n#t_s;z\n0;1\n1;2\n"), tz());
  EXPECT_EQ(u.column("z")[1], 2.0);
}

TEST_F(CsvDialect, AHashLineFollowedByAHeaderStaysAComment) {
  const auto t = readCsv(file("# t_s,q\nt_s,z\n0,1\n1,3\n"), tz());
  EXPECT_EQ(t.column("z")[1], 3.0);
  EXPECT_EQ(t.first_data_line, 3u);
}

TEST_F(CsvDialect, DelimitersAreDetected) {
  for (const std::string text : {"t_s;z\n0;1\n1;2\n", "t_s\tz\n0\t1\n1\t2\n", "  t_s   z\n 0  1 \n1\t\t2\n",
                                 "t_s, z\n0, 1\n1, 2\n"}) {
    SCOPED_TRACE(text);
    const auto t = readCsv(file(text), tz());
    ASSERT_EQ(t.rows(), 2u);
    EXPECT_EQ(t.column("z")[1], 2.0);
    EXPECT_EQ(t.column("t_s")[1], 1.0);
  }
  CsvReadOptions o = tz();
  o.delimiter = ';';
  EXPECT_EQ(readCsv(file("t_s;z\n0;1\n1;2\n"), o).column("z")[0], 1.0);
  // The wrong delimiter given explicitly: the header is one name, the columns are missing.
  o.delimiter = ',';
  EXPECT_THROW((void)readCsv(file("t_s;z\n0;1\n1;2\n"), o), CsvError);
}

TEST_F(CsvDialect, UnitsInTheHeaderAreReportedAndTheBareNameMatches) {
  geaware::io::CsvReader r(file("t_s,z[mm],vz (mm/s),w\n0,1,2,3\n1,2,3,4\n"), tz());
  EXPECT_EQ(r.header()[1], "z[mm]");
  ASSERT_EQ(r.units().size(), 4u);
  EXPECT_EQ(r.units()[0], "");
  EXPECT_EQ(r.units()[1], "mm");
  EXPECT_EQ(r.units()[2], "mm/s");
  CsvReadOptions o;
  o.columns = {{"t_s"}, {"z[mm]"}, {"vz"}};
  const auto t = readCsv(file("t_s,z[mm],vz (mm/s)\n0,1,2\n1,2,3\n"), o);
  EXPECT_EQ(t.column("z[mm]")[1], 2.0);
  EXPECT_EQ(t.column("vz")[1], 3.0);
}

TEST_F(CsvDialect, ReadLogTakesEveryColumnAndItsUnits) {
  const auto f = file("# time[s];z[mm];rpm\n0;10;5000\n0.5;20;5100\n1.0;30;5200\n");
  ASSERT_EQ(geaware::io::detectLogFormat(f), geaware::io::LogFormat::kCsv);
  const auto log = geaware::io::readLog(f);
  EXPECT_EQ(log.format, "csv");
  ASSERT_EQ(log.topics.size(), 1u);
  const auto& t = log.topics[0];
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t.time_s[2], 1.0);
  ASSERT_NE(t.channel("z"), nullptr);
  EXPECT_EQ(t.channel("z")->unit, "mm");
  EXPECT_EQ(t.channel("rpm")->values[1], 5100.0);
}

}  // namespace

namespace {

TEST(CsvFromMemory, ReadsAsAFileDoes) {
  CsvReadOptions o;
  o.columns = {{"t_s"}, {"z"}};
  geaware::io::CsvReader r(std::string_view("# t_s;z[mm]\n0;1\n1;2\n"), "memory", o);
  std::vector<double> row(2);
  ASSERT_TRUE(r.next(row));
  ASSERT_TRUE(r.next(row));
  EXPECT_EQ(row[1], 2.0);
  EXPECT_FALSE(r.next(row));
  EXPECT_THROW(geaware::io::CsvReader(std::string_view(""), "empty", o), CsvError);
}

}  // namespace

namespace {

TEST(CsvNumbers, EveryCellParsesToTheDoubleFromCharsGives) {
  // The reader parses plain decimals itself (a fast path) and anything else with
  // std::from_chars: both must give the same double, bit for bit, for every kind of cell.
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> digits(1, 18);
  std::uniform_int_distribution<int> digit(0, 9);
  std::uniform_int_distribution<int> kind(0, 9);
  std::vector<std::string> cells = {"0", "-0", "0.0", "-0.000", "+1.5", "007.250", "1e3", "-2.5E-3", "123456789012345",
                                    "1234567890123456", "0.1234567890123456789", "9007199254740993", "4.9e-324",
                                    "1.7976931348623157e308", "0.30000000000000004"};
  for (int i = 0; i < 20000; ++i) {
    std::string c;
    if (kind(rng) < 3) c.push_back('-');
    const int n = digits(rng);
    const int point = std::uniform_int_distribution<int>(0, n)(rng);
    for (int d = 0; d < n; ++d) {
      if (d == point && d > 0) c.push_back('.');
      c.push_back(static_cast<char>('0' + digit(rng)));
    }
    if (kind(rng) == 0) {
      c.push_back('e');
      c.append(std::to_string(digit(rng) - 4));
    }
    cells.push_back(c);
  }
  std::string text = "t_s,x\n";
  for (std::size_t i = 0; i < cells.size(); ++i) text += std::to_string(i) + "," + cells[i] + "\n";
  CsvReadOptions o;
  o.columns = {{"t_s"}, {"x", -std::numeric_limits<double>::max(), std::numeric_limits<double>::max()}};
  geaware::io::CsvReader r(std::string_view(text), "numbers", o);
  std::vector<double> row(2);
  for (const auto& c : cells) {
    ASSERT_TRUE(r.next(row)) << c;
    const char* first = c.data() + (c.front() == '+' ? 1 : 0);
    double expected = 0.0;
    ASSERT_EQ(std::from_chars(first, c.data() + c.size(), expected).ec, std::errc()) << c;
    std::uint64_t a = 0;
    std::uint64_t b = 0;
    std::memcpy(&a, &row[1], 8);
    std::memcpy(&b, &expected, 8);
    EXPECT_EQ(a, b) << c << ": " << row[1] << " vs " << expected;
  }
}

}  // namespace
