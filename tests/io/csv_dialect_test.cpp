// SPDX-License-Identifier: BSD-3-Clause
// CSV dialects of lab and autopilot exports: a header line starting with '#', delimiters other
// than the comma (detected), units in the header (`z[mm]`, `z (mm)`); and readLog on CSV.

#include "geaware/io/csv_reader.hpp"
#include "geaware/io/log_channels.hpp"

#include <filesystem>
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
