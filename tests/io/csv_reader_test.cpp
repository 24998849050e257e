// SPDX-License-Identifier: BSD-3-Clause
// The streaming CSV reader: values come back in the requested order, and every kind of bad
// log is an error naming the file, the line and the column.

#include "geaware/io/csv_reader.hpp"
#include "geaware/io/input_file.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

namespace {

using geaware::io::CsvError;
using geaware::io::CsvReadOptions;
using geaware::io::readCsv;

CsvReadOptions threeColumns() {
  CsvReadOptions o;
  o.columns = {{"t_s"}, {"b"}, {"a", -10.0, 10.0}};
  o.time_column = "t_s";
  o.min_rows = 2;
  return o;
}

class CsvReading : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) /
           (std::string("geaware_csv_reader_") +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  std::filesystem::path file(const std::string& text) {
    const auto f = dir_ / "log.csv";
    std::ofstream(f, std::ios::binary) << text;
    return f;
  }
  /// Reads `text` and expects a CsvError at `line`, `column`, with `fragment` in the message.
  void expectError(const std::string& text, std::size_t line, const std::string& column,
                   const std::string& fragment, const CsvReadOptions& o = threeColumns()) {
    const auto f = file(text);
    try {
      (void)readCsv(f, o);
      ADD_FAILURE() << "no error for:\n" << text;
    } catch (const CsvError& e) {
      EXPECT_EQ(e.file(), f.string());
      EXPECT_EQ(e.line(), line) << e.what();
      EXPECT_EQ(e.column(), column) << e.what();
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      const std::string where =
          f.string() + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": ";
      EXPECT_EQ(std::string(e.what()).rfind(where, 0), 0u) << e.what();
    }
  }
  std::filesystem::path dir_;
};

TEST_F(CsvReading, ReadsTheRequestedColumnsInTheRequestedOrder) {
  // A comment and a blank line before the header, an unused column, spaces, a '+', CRLF and no
  // final newline.
  const auto t = readCsv(file("# rig v1\n\nt_s, a ,skip,b\r\n0, 1.5,x,+2\r\n0.1,-3e-1,y, 4\r\n0.2,2,z,6"),
                         threeColumns());
  ASSERT_EQ(t.rows(), 3u);
  EXPECT_EQ(t.first_data_line, 4u);
  EXPECT_EQ(t.column("a"), (std::vector<double>{1.5, -0.3, 2.0}));
  EXPECT_EQ(t.column("b"), (std::vector<double>{2.0, 4.0, 6.0}));
  EXPECT_EQ(t.names, (std::vector<std::string>{"t_s", "b", "a"}));
  EXPECT_THROW((void)t.column("skip"), std::out_of_range);
}

TEST_F(CsvReading, SmallBuffersGrowForLongLines) {
  std::string text = "t_s,a,b," + std::string(300, 'x') + "\n";
  for (int i = 0; i < 100; ++i) text += std::to_string(i) + ",1,2,0\n";
  CsvReadOptions o = threeColumns();
  o.buffer_bytes = 16;
  const auto t = readCsv(file(text), o);
  EXPECT_EQ(t.rows(), 100u);
  EXPECT_EQ(t.column("t_s").back(), 99.0);
}

// A line over 1 MiB is refused at its line, echoing at most 80 characters: /dev/zero and a
// 300 MB file without a newline (sparse) fail within a second, reading about 1 MiB.
TEST_F(CsvReading, LinesOverOneMebibyteAreRefusedQuickly) {
  expectError("t_s,a,b\n0,1,2\n" + std::string(geaware::io::kMaxLineBytes + 10, '7') + "\n", 3, "",
              "line longer than 1 MiB (starts '7777");
  const auto huge = dir_ / "huge.csv";
  { std::ofstream(huge) << "t_s,a,b\n"; }
  std::filesystem::resize_file(huge, 300'000'000);
  for (const std::filesystem::path& f : {std::filesystem::path("/dev/zero"), huge}) {
    const auto start = std::chrono::steady_clock::now();
    try {
      (void)readCsv(f, threeColumns());
      ADD_FAILURE() << f;
    } catch (const CsvError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("line longer than 1 MiB (starts '\\x00\\x00"), std::string::npos) << what;
      EXPECT_LT(what.size(), 500u) << "the line is not echoed whole";
    }
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1)) << f;
  }
}

// A cell of a hostile file (up to a line's 1 MiB) is echoed as at most 80 bytes, and a header
// of thousands of names is listed as its first 40.
TEST_F(CsvReading, LongCellsAndHeadersAreNotEchoedWhole) {
  const auto f = file("t_s,a,b\n0,1,2\n1," + std::string(500'000, '7') + "x,2\n");
  try {
    (void)readCsv(f, threeColumns());
    ADD_FAILURE();
  } catch (const CsvError& e) {
    EXPECT_LT(std::string(e.what()).size(), f.string().size() + 200) << e.what();
  }
  std::string header = "t_s,b";
  for (int i = 0; i < 5000; ++i) header += ",c" + std::to_string(i);
  const auto g = file(header + "\n");
  try {
    (void)readCsv(g, threeColumns());
    ADD_FAILURE();
  } catch (const CsvError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("(4962 more)"), std::string::npos) << what.substr(0, 300);
    EXPECT_LT(what.size(), 1000u);
  }
}

TEST_F(CsvReading, StreamsRowByRow) {
  geaware::io::CsvReader reader(file("t_s,a,b\n0,1,2\n1,3,4\n"), threeColumns());
  std::vector<double> row(3);
  double sum = 0.0;
  while (reader.next(row)) sum += row[2];
  EXPECT_EQ(sum, 4.0);
  EXPECT_EQ(reader.rowsRead(), 2u);
}

TEST_F(CsvReading, MissingColumnListsTheFoundOnesAndSuggestsTheMisnamedOne) {
  expectError("t_s,A,b\n0,1,2\n1,1,2\n", 1, "a", "missing column 'a' (did you mean 'A'?); found: t_s, A, b");
  expectError("t_s,b\n0,1\n1,1\n", 1, "a", "missing column 'a'; found: t_s, b");
  // A platform log with one force column misspelt: the near miss is suggested, and a column
  // that is itself requested is never suggested for another.
  geaware::io::CsvReadOptions o;
  o.columns = {{"t_s"}, {"fz_N"}, {"ty_Nm"}, {"tz_Nm"}};
  expectError("t_s,fz_n,tz_Nm,tyNm\n0,1,2,3\n", 1, "fz_N",
              "missing columns 'fz_N' (did you mean 'fz_n'?), 'ty_Nm' (did you mean 'tyNm'?); "
              "found: t_s, fz_n, tz_Nm, tyNm", o);
}

TEST_F(CsvReading, DuplicatedHeaderName) { expectError("t_s,a,b,a\n0,1,2,3\n", 1, "a", "appears twice"); }

TEST_F(CsvReading, NonNumericCell) { expectError("t_s,a,b\n0,1,2\n1,1.2.3,2\n", 3, "a", "expected a number, got '1.2.3'"); }

TEST_F(CsvReading, EmptyCell) { expectError("t_s,a,b\n0,1,2\n1,1,\n", 3, "b", "empty cell"); }

TEST_F(CsvReading, NaNAndInfinity) {
  expectError("t_s,a,b\n0,1,2\n1,nan,2\n", 3, "a", "'nan' is not finite");
  expectError("t_s,a,b\n0,1,2\n1,1,-inf\n", 3, "b", "'-inf' is not finite");
  expectError("t_s,a,b\n0,1,2\n1,1,1e999\n", 3, "b", "out of the range of a double");
}

TEST_F(CsvReading, ValueOutsideTheColumnsRange) {
  expectError("t_s,a,b\n0,1,2\n1,50,2\n", 3, "a", "value 50 is outside the plausible range [-10, 10]");
}

TEST_F(CsvReading, DuplicatedTimestamp) {
  expectError("t_s,a,b\n0,1,2\n0.5,1,2\n0.5,1,2\n", 4, "t_s", "duplicated timestamp 0.5 (also on line 3)");
}

TEST_F(CsvReading, DecreasingTimestamp) {
  expectError("t_s,a,b\n0,1,2\n0.5,1,2\n0.4,1,2\n", 4, "t_s", "timestamp 0.4 is earlier than 0.5 on line 3");
}

TEST_F(CsvReading, TooFewRows) {
  CsvReadOptions o = threeColumns();
  o.min_rows = 3;
  expectError("t_s,a,b\n0,1,2\n1,1,2\n", 3, "", "only 2 data rows, at least 3 are needed", o);
}

TEST_F(CsvReading, WrongCellCount) {
  expectError("t_s,a,b\n0,1,2\n1,1\n", 3, "b", "row has 2 cells, the header 3");
  expectError("t_s,a,b\n0,1,2\n1,1,2,3\n", 3, "", "more cells than the header's 3");
}

TEST_F(CsvReading, EmptyLineInsideTheData) { expectError("t_s,a,b\n0,1,2\n\n1,1,2\n", 3, "", "empty line inside the data"); }

TEST_F(CsvReading, EmptyFileAndMissingFile) {
  expectError("", 0, "", "no header line");
  try {
    (void)readCsv(dir_ / "nothere.csv", threeColumns());
    ADD_FAILURE();
  } catch (const CsvError& e) {
    EXPECT_NE(std::string(e.what()).find("nothere.csv: cannot open"), std::string::npos) << e.what();
  }
}

}  // namespace
