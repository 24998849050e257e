// SPDX-License-Identifier: BSD-3-Clause
// The CSV writer: shortest round-trip numbers that the CSV reader reads back exactly, float32
// cells, buffering across many rows, streams it does not own, and write errors.
#include "geaware/io/csv_writer.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "geaware/io/csv_reader.hpp"

namespace {

using geaware::io::CsvWriter;

std::filesystem::path tempFile(const std::string& name) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / "geaware_csv_writer";
  std::filesystem::create_directories(dir);
  return dir / name;
}

std::string slurp(const std::filesystem::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(CsvWriter, HeaderAndShortestRoundTripCells) {
  const auto f = tempFile("cells.csv");
  {
    CsvWriter w(f, {"t_s", "x_m", "flag"});
    w.exact(0.1);
    w.single(0.1);
    w.integer(3);
    w.endRow();
    w.row({1e-300, -2.5, 7.0});
    EXPECT_EQ(w.rows(), 2u);
    EXPECT_EQ(w.columns(), 3u);
    w.close();
  }
  EXPECT_EQ(slurp(f), "t_s,x_m,flag\n0.1,0.1,3\n1e-300,-2.5,7\n");
}

TEST(CsvWriter, ReadsBackBitExactThroughTheReaderAcrossBufferFlushes) {
  const auto f = tempFile("many.csv");
  const int rows = 40000;  // several times the writer's buffer
  const auto value = [](int i) { return std::sin(0.37 * i) * std::exp(0.001 * i) / 3.0; };
  {
    CsvWriter w(f, {"t_s", "v"});
    for (int i = 0; i < rows; ++i) w.row({0.001 * i, value(i)});
    w.close();
  }
  geaware::io::CsvReadOptions o;
  o.columns = {{"t_s"}, {"v"}};
  o.time_column = "";
  const auto t = geaware::io::readCsv(f, o);
  ASSERT_EQ(t.rows(), static_cast<std::size_t>(rows));
  for (int i = 0; i < rows; ++i) {
    ASSERT_EQ(t.column("v")[static_cast<std::size_t>(i)], value(i)) << "row " << i;
    ASSERT_EQ(t.column("t_s")[static_cast<std::size_t>(i)], 0.001 * i) << "row " << i;
  }
}

TEST(CsvWriter, SingleCellsReadBackToTheSameFloat) {
  const auto f = tempFile("single.csv");
  {
    CsvWriter w(f, {"v"});
    for (double v : {1.0 / 3.0, 12345.678901234, -9.80665e-7}) {
      w.single(v);
      w.endRow();
    }
    w.close();
  }
  std::istringstream in(slurp(f));
  std::string line;
  std::getline(in, line);
  for (double v : {1.0 / 3.0, 12345.678901234, -9.80665e-7}) {
    std::getline(in, line);
    EXPECT_EQ(std::stof(line), static_cast<float>(v)) << line;
    EXPECT_LE(line.size(), 13u) << line;  // float precision, not a double's 17 digits
  }
}

TEST(CsvWriter, WritesToAStreamItDoesNotOwn) {
  const auto f = tempFile("stream.csv");
  std::FILE* s = std::fopen(f.c_str(), "wb");
  ASSERT_NE(s, nullptr);
  {
    CsvWriter w(s, "the table", {"a", "b"});
    w.row({1.0, 2.0});
    w.close();
  }
  std::fputs("# after\n", s);  // still open: the writer did not close it
  std::fclose(s);
  EXPECT_EQ(slurp(f), "a,b\n1,2\n# after\n");
}

TEST(CsvWriter, ErrorsNameTheFile) {
  try {
    CsvWriter w(tempFile("no/such/dir.csv"), {"a"});
    ADD_FAILURE();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("dir.csv"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
  // A device is refused before anything is written (io::AtomicFile).
  EXPECT_THROW(CsvWriter(std::filesystem::path("/dev/full"), {"a"}), std::runtime_error);
}

// A writer destroyed before close() (a refused or failed run) leaves the existing file as it was;
// close() replaces it whole.
TEST(CsvWriter, ReplacesAFileOnlyWhenClosed) {
  const auto f = tempFile("existing.csv");
  { std::ofstream(f) << "precious\n"; }
  {
    CsvWriter w(f, {"a"});
    w.row({1.0});
  }
  EXPECT_EQ(slurp(f), "precious\n");
  CsvWriter w(f, {"a"});
  w.row({1.0});
  w.close();
  EXPECT_EQ(slurp(f), "a\n1\n");
}

}  // namespace
