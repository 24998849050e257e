// SPDX-License-Identifier: BSD-3-Clause
// MATLAB .mat files (io::readMat): files written here by libmatio (v5, v7 compressed, v7.3
// HDF5) and read back, value for value; the size check before reading; errors naming the file.
// No .mat file made by another tool is in the repository (python3's scipy is not installed on
// the build machine, and is not a dependency).

#include <gtest/gtest.h>
#include <matio.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geaware/io/log_channels.hpp"
#include "geaware/io/log_map.hpp"

namespace {

using geaware::io::LogData;
using geaware::io::LogError;

std::filesystem::path dir() {
  const auto d = std::filesystem::path(::testing::TempDir()) / "geaware_mat";
  std::filesystem::create_directories(d);
  return d;
}

matvar_t* vec(const char* name, matio_classes c, matio_types t, std::vector<std::size_t> dims,
              void* data) {
  return Mat_VarCreate(name, c, t, static_cast<int>(dims.size()), dims.data(), data, 0);
}

// Writes and frees `var` (a struct with its fields).
void put(mat_t* mat, matvar_t* var, matio_compression compression) {
  Mat_VarWrite(mat, var, compression);
  Mat_VarFree(var);
}

// The test file: top-level t, z (single, a column), acc (N×3), a scalar, a text; a struct imu
// with its own time, an int16 field and a nested struct; a 3-D array.
struct Contents {
  std::vector<double> t{0.0, 0.01, 0.02, 0.03};
  std::vector<float> z{0.5F, 0.4F, 0.3F, 0.25F};
  std::vector<double> acc;  // 4×3, column-major
  double mass = 0.037;
  std::vector<double> imu_time{0.0, 0.005, 0.010, 0.015, 0.020, 0.025};
  std::vector<std::int16_t> gx{-3, -2, -1, 0, 1, 2};
  std::vector<double> inner_a{6, 5, 4, 3, 2, 1};
  std::vector<double> cube = std::vector<double>(8, 1.0);
  Contents() {
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 4; ++i) acc.push_back(10.0 * j + i);
    }
  }
};

// Writes the contents; false when libmatio cannot write this version (v7.3 without HDF5).
bool write(const std::filesystem::path& file, mat_ft version, matio_compression compression,
           Contents& c) {
  mat_t* mat = Mat_CreateVer(file.c_str(), nullptr, version);
  if (mat == nullptr) return false;
  const auto n = c.t.size();
  put(mat, vec("t", MAT_C_DOUBLE, MAT_T_DOUBLE, {1, n}, c.t.data()), compression);
  put(mat, vec("z", MAT_C_SINGLE, MAT_T_SINGLE, {n, 1}, c.z.data()), compression);
  put(mat, vec("acc", MAT_C_DOUBLE, MAT_T_DOUBLE, {n, 3}, c.acc.data()), compression);
  put(mat, vec("mass", MAT_C_DOUBLE, MAT_T_DOUBLE, {1, 1}, &c.mass), compression);
  char text[] = "crazyflie";
  put(mat, vec("name", MAT_C_CHAR, MAT_T_UINT8, {1, 9}, text), compression);
  put(mat, vec("cube", MAT_C_DOUBLE, MAT_T_DOUBLE, {2, 2, 2}, c.cube.data()), compression);
  const char* fields[] = {"time", "gx", "inner"};
  std::size_t one[2] = {1, 1};
  matvar_t* imu = Mat_VarCreateStruct("imu", 2, one, fields, 3);
  const auto m = c.imu_time.size();
  Mat_VarSetStructFieldByName(imu, "time", 0,
                              vec("time", MAT_C_DOUBLE, MAT_T_DOUBLE, {m, 1}, c.imu_time.data()));
  Mat_VarSetStructFieldByName(imu, "gx", 0,
                              vec("gx", MAT_C_INT16, MAT_T_INT16, {1, m}, c.gx.data()));
  const char* inner_fields[] = {"a"};
  matvar_t* inner = Mat_VarCreateStruct("inner", 2, one, inner_fields, 1);
  Mat_VarSetStructFieldByName(inner, "a", 0,
                              vec("a", MAT_C_DOUBLE, MAT_T_DOUBLE, {m, 1}, c.inner_a.data()));
  Mat_VarSetStructFieldByName(imu, "inner", 0, inner);
  put(mat, imu, compression);
  Mat_Close(mat);
  return true;
}

void expectContents(const LogData& log, const Contents& c) {
  EXPECT_EQ(log.format, "mat");
  const auto* top = log.topic("mat");
  ASSERT_NE(top, nullptr);
  EXPECT_EQ(top->time_s, c.t);
  EXPECT_EQ(top->channel("z")->values[1], static_cast<double>(0.4F));
  EXPECT_EQ(top->channel("z")->type, geaware::io::FieldType::kFloat);
  EXPECT_EQ(top->channel("acc[0]")->values, (std::vector<double>{0, 1, 2, 3}));
  EXPECT_EQ(top->channel("acc[2]")->values, (std::vector<double>{20, 21, 22, 23}));
  EXPECT_DOUBLE_EQ(log.parameters.at("mass"), 0.037);
  const auto* imu = log.topic("imu");
  ASSERT_NE(imu, nullptr);
  EXPECT_EQ(imu->time_s, c.imu_time);
  EXPECT_EQ(imu->channel("gx")->values, (std::vector<double>{-3, -2, -1, 0, 1, 2}));
  EXPECT_EQ(imu->channel("gx")->type, geaware::io::FieldType::kInt16);
  EXPECT_EQ(imu->channel("inner.a")->values, c.inner_a);
  // The text and the 3-D array are named as no channels.
  ASSERT_EQ(log.warnings.size(), 1u);
  EXPECT_NE(log.warnings[0].find("2 variables are no channels: "), std::string::npos)
      << log.warnings[0];
  EXPECT_NE(log.warnings[0].find("name (not numeric)"), std::string::npos) << log.warnings[0];
  EXPECT_NE(log.warnings[0].find("cube (3 dimensions)"), std::string::npos) << log.warnings[0];
}

TEST(MatReader, Version5AndCompressedVersion7RoundTrip) {
  Contents c;
  const auto v5 = dir() / "v5.mat";
  ASSERT_TRUE(write(v5, MAT_FT_MAT5, MAT_COMPRESSION_NONE, c));
  EXPECT_EQ(geaware::io::detectLogFormat(v5), geaware::io::LogFormat::kMat);
  expectContents(geaware::io::readLog(v5), c);
  const auto v7 = dir() / "v7.mat";
  ASSERT_TRUE(write(v7, MAT_FT_MAT5, MAT_COMPRESSION_ZLIB, c));
  expectContents(geaware::io::readMat(v7), c);
}

TEST(MatReader, Version73RoundTrip) {
  Contents c;
  const auto v73 = dir() / "v73.mat";
  if (!write(v73, MAT_FT_MAT73, MAT_COMPRESSION_NONE, c)) {
    GTEST_SKIP() << "this libmatio is built without HDF5: v7.3 cannot be written or read";
  }
  EXPECT_EQ(geaware::io::detectLogFormat(v73), geaware::io::LogFormat::kMat);
  expectContents(geaware::io::readLog(v73), c);
}

TEST(MatReader, SizesAreCheckedBeforeTheDataIsRead) {
  // 10^6 zeros compress to a few kB: the file passes the size check, its numbers do not.
  std::vector<double> zeros(1000000, 0.0);
  const auto f = dir() / "zeros.mat";
  mat_t* mat = Mat_CreateVer(f.c_str(), nullptr, MAT_FT_MAT5);
  ASSERT_NE(mat, nullptr);
  put(mat, vec("big", MAT_C_DOUBLE, MAT_T_DOUBLE, {1, zeros.size()}, zeros.data()),
      MAT_COMPRESSION_ZLIB);
  Mat_Close(mat);
  geaware::io::LogReadOptions o;
  o.max_bytes = 400000;  // 50,000 numbers
  ASSERT_LT(std::filesystem::file_size(f), o.max_bytes);
  try {
    (void)geaware::io::readMat(f, o);
    FAIL() << "no error";
  } catch (const LogError& e) {
    // Its dimensions claim more numbers than the limit allows: refused while the file is walked,
    // before libmatio reads (or allocates) anything.
    EXPECT_EQ(std::string(e.what()),
              f.string() +
                  ": byte 128: a variable whose dimensions claim more than 50000 "
                  "elements (doubles in the bytes a log may have): refused before "
                  "reading");
  }
}

TEST(MatReader, ErrorsNameTheFile) {
  const auto f = dir() / "fake.mat";
  std::ofstream(f) << "MATLAB 5.0 MAT-file, but nothing after it";
  try {
    (void)geaware::io::readMat(f);
    FAIL() << "no error";
  } catch (const LogError& e) {
    EXPECT_NE(std::string(e.what()).find(f.string() + ": not a MATLAB .mat file libmatio can open"),
              std::string::npos)
        << e.what();
  }
  // A file cut short: an error naming it and the byte (libmatio alone would read a cut struct's
  // remaining fields without a word).
  Contents c;
  const auto whole = dir() / "whole.mat";
  ASSERT_TRUE(write(whole, MAT_FT_MAT5, MAT_COMPRESSION_NONE, c));
  const auto size = std::filesystem::file_size(whole);
  for (const double keep : {0.2, 0.5, 0.8, 0.95}) {
    const auto cut = dir() / "cut.mat";
    std::filesystem::copy_file(whole, cut, std::filesystem::copy_options::overwrite_existing);
    std::filesystem::resize_file(cut,
                                 static_cast<std::uintmax_t>(keep * static_cast<double>(size)));
    try {
      (void)geaware::io::readMat(cut);
      ADD_FAILURE() << "no error at " << keep;
    } catch (const LogError& e) {
      EXPECT_EQ(e.file(), cut.string());
      EXPECT_TRUE(e.hasOffset()) << e.what();
    }
  }
  // An inner element whose size runs past its variable (libmatio would allocate what it says):
  // the first variable's array-flags element, at byte 136, claims 2^31 − 16 bytes.
  const auto huge = dir() / "huge.mat";
  std::filesystem::copy_file(whole, huge, std::filesystem::copy_options::overwrite_existing);
  {
    std::fstream io(huge, std::ios::binary | std::ios::in | std::ios::out);
    const std::uint32_t bytes = 0x7FFFFFF0U;
    io.seekp(140);
    io.write(reinterpret_cast<const char*>(&bytes), 4);
  }
  try {
    (void)geaware::io::readMat(huge);
    ADD_FAILURE() << "no error";
  } catch (const LogError& e) {
    EXPECT_NE(std::string(e.what()).find(huge.string() +
                                         ": byte 128: an element of 2147483632 bytes inside this "
                                         "variable runs past its end"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW((void)geaware::io::readMat(dir() / "missing.mat"), LogError);
}

TEST(MatReader, TheHeaderIsReadAsLibmatioReadsIt) {
  // libmatio takes the format from the header's version field and endian indicator, not from its
  // text. fuzz_mat found a v5 file whose text said "MATLAB 7.3": geaware took it for HDF5 and
  // skipped its walk, and libmatio read it as v5 and allocated 4 GiB from an unchecked element.
  Contents c;
  const auto whole = dir() / "whole73text.mat";
  ASSERT_TRUE(write(whole, MAT_FT_MAT5, MAT_COMPRESSION_NONE, c));
  const auto patched = [&](const char* name, std::streamoff at, const std::string& bytes) {
    const auto f = dir() / name;
    std::filesystem::copy_file(whole, f, std::filesystem::copy_options::overwrite_existing);
    std::fstream io(f, std::ios::binary | std::ios::in | std::ios::out);
    io.seekp(at);
    io.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return f;
  };
  const std::string text73 = "MATLAB 7.3 MAT-file";
  // The text alone changes nothing: the file is walked and read as the v5 file it is.
  expectContents(geaware::io::readMat(patched("text73.mat", 0, text73)), c);
  // … and so an element that runs past its variable is found before libmatio reads it.
  const auto f = patched("text73_huge.mat", 0, text73);
  {
    std::fstream io(f, std::ios::binary | std::ios::in | std::ios::out);
    const std::uint32_t bytes = 0x7FFFFFF0U;
    io.seekp(140);
    io.write(reinterpret_cast<const char*>(&bytes), 4);
  }
  const auto message = [](const std::filesystem::path& file) -> std::string {
    try {
      (void)geaware::io::readMat(file);
    } catch (const LogError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(message(f).find(f.string() + ": byte 128: an element of 2147483632 bytes inside this variable runs past its end"),
            std::string::npos)
      << message(f);
  // A version field or endian indicator that libmatio would take for a MATLAB v4 file (whose
  // headers it allocates by unchecked): refused at the header's byte.
  const auto v = patched("version1.mat", 124, std::string("\x01\x00", 2));
  EXPECT_EQ(message(v), v.string() + ": byte 124: the header's version field is 0x0001, expected 0x0100 (v5, v7) or "
                                     "0x0200 (v7.3) (MATLAB v4 files are not read)");
  // Inside a variable, a type MAT-File Format does not define, or dimensions of another type than
  // miINT32: libmatio would read the following tags from elsewhere than this walk (fuzz_mat: the
  // first variable's dimensions tag, at byte 152, of type 8 made it allocate a 1.4 GB name).
  const auto d = patched("dims8.mat", 152, std::string("\x08\x00\x00\x00", 4));
  EXPECT_EQ(message(d), d.string() + ": byte 128: an element of type 8 inside this variable, expected a MAT-File "
                                     "data type (1–7, 9, 12–18): a damaged .mat file");
  const auto i = patched("dims6.mat", 152, std::string("\x06\x00\x00\x00", 4));
  EXPECT_EQ(message(i), i.string() + ": byte 128: a matrix whose second element (its dimensions) has type 6, "
                                     "expected type 5 (miINT32) in a full tag: a damaged .mat file");
  // Dimensions of 2 bytes: libmatio reads no dimension and takes the padding's bytes for the
  // name tag (fuzz_mat: a 2.9 GB name). Refused, as any count not a multiple of 4 or under 8.
  const auto two = patched("dims2bytes.mat", 156, std::string("\x02\x00\x00\x00", 4));
  EXPECT_EQ(message(two), two.string() + ": byte 128: a matrix whose dimensions element has 2 bytes, expected two "
                                         "or more int32 (a multiple of 4 bytes, at least 8): a damaged .mat file");
  const auto e = patched("endian.mat", 126, "XY");
  EXPECT_EQ(message(e), e.string() + ": byte 126: the header's endian indicator is 0x5859, expected 'IM' or 'MI' "
                                     "(a v5, v7 or v7.3 .mat file; MATLAB v4 files are not read)");
}

TEST(MatReader, AMapReadsAStructsFieldsWithItsTime) {
  Contents c;
  const auto f = dir() / "flight.mat";
  ASSERT_TRUE(write(f, MAT_FT_MAT5, MAT_COMPRESSION_NONE, c));
  const auto map = geaware::io::parseLogMap(R"(family: test
frames: enu_flu
channels:
  height: {topic: imu, fields: ["inner.a[mm]"]}
  gyro: {topic: imu, fields: ["0", "0", "gx[deg/s]"], frame: body}
)",
                                            "map.yaml", "test");
  const auto m = geaware::io::mapFlight(geaware::io::readLog(f), map, {"height", "gyro"});
  ASSERT_EQ(m.size(), 6u);
  EXPECT_DOUBLE_EQ(m.t_s[1], 0.005);
  EXPECT_DOUBLE_EQ(m.h_m[0], 0.006);
  EXPECT_DOUBLE_EQ(m.gyro_B_radps[2][0], -3.0 * M_PI / 180.0);
}

}  // namespace
