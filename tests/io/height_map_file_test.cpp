// SPDX-License-Identifier: BSD-3-Clause
// The height-map file: a grid read with its header keys, and every kind of bad file an error
// naming the file, the line and the column.
#include "geaware/io/height_map_file.hpp"

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace {

using geaware::io::HeightMapFileError;
using geaware::io::readHeightMapFile;
using geaware::model::HeightGrid;

class HeightMapFile : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = ::testing::TempDir() + "geaware_" + name;
    std::ofstream(path) << text;
    return path;
  }
  static constexpr const char* kHeader =
      "# geaware height map\n# origin_x_m: -1.0\n# origin_y_m: 2.0\n# cell_m: 0.5\n";
};

TEST_F(HeightMapFile, LoadsAGrid) {
  const std::string path = write(
      "good.csv", std::string(kHeader) + "0.0, 0.1, 0.2\n\n0.5, 0.6, 0.7\n# a comment\n1, 1, +1\n");
  const HeightGrid g = readHeightMapFile(path);
  const HeightGrid m = geaware::io::parseHeightMapText(
      std::string(kHeader) + "0.0, 0.1, 0.2\n\n0.5, 0.6, 0.7\n# a comment\n1, 1, +1\n", "memory");
  EXPECT_EQ(m.heights, g.heights);
  EXPECT_EQ(m.cell_m, g.cell_m);
  EXPECT_EQ(g.origin_x_m, -1.0);
  EXPECT_EQ(g.origin_y_m, 2.0);
  EXPECT_EQ(g.cell_m, 0.5);
  const std::vector<std::vector<double>> expected = {{0.0, 0.1, 0.2}, {0.5, 0.6, 0.7}, {1, 1, 1}};
  EXPECT_EQ(g.heights, expected);
}

/// Expects readHeightMapFile(path) to throw a HeightMapFileError at line/column whose message
/// names the file, and parseHeightMapText (the fuzz target's entry point) on the file's bytes the
/// same error.
void expectFileError(const std::string& path, int line, int column, const std::string& fragment) {
  try {
    (void)readHeightMapFile(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const HeightMapFileError& e) {
    if (std::ifstream in{path}) {
      const std::string bytes{std::istreambuf_iterator<char>(in), {}};
      try {
        (void)geaware::io::parseHeightMapText(bytes, path);
        ADD_FAILURE() << "no error from memory for " << path;
      } catch (const HeightMapFileError& m) {
        EXPECT_STREQ(m.what(), e.what());
      }
    }
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.column(), column) << e.what();
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
    if (line > 0) {
      EXPECT_NE(what.find(path + ":" + std::to_string(line)), std::string::npos) << what;
    }
  }
}

TEST_F(HeightMapFile, RejectsARaggedRowNamingFileAndLine) {
  const std::string path = write("ragged.csv", std::string(kHeader) + "0, 0, 0\n0, 0\n0, 0, 0\n");
  expectFileError(path, 6, 0, "row has 2 values, the first row (line 5) has 3");
}

TEST_F(HeightMapFile, RejectsBadValuesNamingLineAndColumn) {
  expectFileError(write("word.csv", std::string(kHeader) + "0, 0, 0\n0, abc, 0\n"), 6, 2,
                  "'abc' is not a number");
  expectFileError(write("nan.csv", std::string(kHeader) + "0, 0, nan\n0, 0, 0\n"), 5, 3,
                  "not finite");
  expectFileError(write("empty.csv", std::string(kHeader) + "0, , 0\n0, 0, 0\n"), 5, 2,
                  "is not a number");
}

TEST_F(HeightMapFile, RejectsBadHeaders) {
  expectFileError(write("nocell.csv", "# origin_x_m: 0\n# origin_y_m: 0\n0, 0\n0, 0\n"), 0, 0,
                  "missing header key 'cell_m'");
  expectFileError(
      write("negcell.csv", "# origin_x_m: 0\n# origin_y_m: 0\n# cell_m: -1\n0, 0\n0, 0\n"), 3, 0,
      "must be positive");
  expectFileError(write("twice.csv", std::string(kHeader) + "# cell_m: 0.5\n0, 0\n0, 0\n"), 5, 0,
                  "given twice");
  expectFileError(write("late.csv", "# origin_x_m: 0\n# origin_y_m: 0\n0, 0\n# cell_m: 1\n0, 0\n"),
                  4, 0, "after the first data row");
  expectFileError(write("small.csv", std::string(kHeader) + "0, 0, 0\n"), 0, 0,
                  "at least 2 rows of 2");
  expectFileError(::testing::TempDir() + "geaware_does_not_exist.csv", 0, 0, "no such height-map file");
}

TEST_F(HeightMapFile, FormatVersionIsOptionalAndChecked) {
  const std::string grid = "0, 0\n0, 0\n";
  // Absent or 1: today's format, the same grid.
  const HeightGrid v1 =
      readHeightMapFile(write("v1.csv", "# format_version: 1\n" + std::string(kHeader) + grid));
  EXPECT_EQ(v1.heights, readHeightMapFile(write("v0.csv", std::string(kHeader) + grid)).heights);
  EXPECT_EQ(v1.cell_m, 0.5);
  // Another version, a word, twice or after the data: errors at the key's line.
  expectFileError(write("v2.csv", std::string(kHeader) + "# format_version: 2\n" + grid), 5, 0,
                  "header key 'format_version': '2' is not a format version this geaware reads "
                  "(it reads 1)");
  expectFileError(write("vx.csv", "# format_version: one\n" + std::string(kHeader) + grid), 1, 0,
                  "'one' is not a format version");
  expectFileError(
      write("vtwice.csv", "# format_version: 1\n# format_version: 1\n" + std::string(kHeader) + grid),
      2, 0, "given twice");
  expectFileError(write("vlate.csv", std::string(kHeader) + "0, 0\n# format_version: 1\n0, 0\n"),
                  6, 0, "after the first data row");
}

}  // namespace
