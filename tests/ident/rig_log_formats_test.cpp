// SPDX-License-Identifier: BSD-3-Clause
// Rig logs in the formats identify flight reads (issue 11): `identify rotor` and `identify
// platform` read a MATLAB .mat file (written here by libmatio) as they read the CSV of the same
// samples, with --column definitions on its fields; a missing field is an error naming it.

#include <matio.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "geaware/ident/identify.hpp"
#include "geaware/ident/rig_logs.hpp"
#include "geaware/io/column_expression.hpp"
#include "geaware/io/csv_reader.hpp"
#include "geaware/io/log_channels.hpp"
#include "synthetic.hpp"

namespace {

namespace ident = geaware::ident;

/// A .mat file of column vectors, and the CSV of the same values (17 significant digits).
struct Columns {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;
  void add(const std::string& name, const std::vector<double>& v) {
    names.push_back(name);
    values.push_back(v);
  }
  void writeMat(const std::filesystem::path& file) {
    mat_t* mat = Mat_CreateVer(file.c_str(), nullptr, MAT_FT_MAT5);
    ASSERT_NE(mat, nullptr);
    for (std::size_t k = 0; k < names.size(); ++k) {
      std::size_t dims[2] = {values[k].size(), 1};
      matvar_t* var = Mat_VarCreate(names[k].c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, values[k].data(), 0);
      Mat_VarWrite(mat, var, MAT_COMPRESSION_ZLIB);
      Mat_VarFree(var);
    }
    Mat_Close(mat);
  }
  void writeCsv(const std::filesystem::path& file) {
    std::ofstream os(file);
    for (std::size_t k = 0; k < names.size(); ++k) os << (k > 0 ? "," : "") << names[k];
    os << '\n';
    char cell[32];
    for (std::size_t i = 0; i < values.front().size(); ++i) {
      for (std::size_t k = 0; k < names.size(); ++k) {
        std::snprintf(cell, sizeof cell, "%.17g", values[k][i]);
        os << (k > 0 ? "," : "") << cell;
      }
      os << '\n';
    }
  }
};

TEST(RigLogFormats, ARotorStandFromAMatFileFitsAsItsCsv) {
  ident_test::StandSpec spec;
  spec.duration_s = 8.0;
  spec.dt_s = 0.002;
  const ident::RotorStandLog stand = ident_test::syntheticStand(spec, 3);
  Columns c;
  c.add("t_s", stand.t_s);
  c.add("throttle", stand.throttle);
  c.add("rpm", stand.rpm);
  c.add("thrust_N", stand.thrust_N);
  c.add("torque_Nm", stand.torque_Nm);
  const auto dir = ident_test::tempDir("rig_log_formats_rotor");
  c.writeMat(dir / "stand.mat");
  c.writeCsv(dir / "stand.csv");
  ASSERT_EQ(geaware::io::detectLogFormat(dir / "stand.mat"), geaware::io::LogFormat::kMat);
  const auto m = ident::readRotorStandLog(dir / "stand.mat");
  const auto v = ident::readRotorStandLog(dir / "stand.csv");
  EXPECT_EQ(m.t_s, v.t_s);
  EXPECT_EQ(m.rpm, v.rpm);
  EXPECT_EQ(m.thrust_N, v.thrust_N);
  EXPECT_EQ(m.torque_Nm, v.torque_Nm);
  EXPECT_EQ(m.source, (dir / "stand.mat").string());
  const auto a = ident::identifyRotorStand(m, {});
  const auto b = ident::identifyRotorStand(v, {});
  ASSERT_EQ(a.parameters.size(), b.parameters.size());
  ASSERT_FALSE(a.parameters.empty());
  for (std::size_t k = 0; k < a.parameters.size(); ++k) {
    EXPECT_EQ(a.parameters[k].estimate.value, b.parameters[k].estimate.value) << a.parameters[k].name;
  }
}

TEST(RigLogFormats, APlatformFromAMatFileWithColumnDefinitions) {
  ident_test::PlatformSpec spec;
  spec.level_samples = 3000;
  spec.tilted_samples = 3000;
  const ident::PlatformLog log = ident_test::syntheticPlatform(spec, 4);
  // The height logged in mm under another name, defined on the command line as h_m.
  std::vector<double> z_mm(log.h_m);
  for (double& z : z_mm) z *= 1000.0;
  Columns c;
  c.add("t_s", log.t_s);
  c.add("z", z_mm);
  c.add("tilt_deg", log.tilt_deg);
  const char* n[] = {"n1_rpm", "n2_rpm", "n3_rpm", "n4_rpm"};
  for (std::size_t k = 0; k < 4; ++k) c.add(n[k], log.n_rpm[k]);
  const char* f[] = {"fx_N", "fy_N", "fz_N"};
  const char* t[] = {"tx_Nm", "ty_Nm", "tz_Nm"};
  for (std::size_t k = 0; k < 3; ++k) c.add(f[k], log.f_N[k]);
  for (std::size_t k = 0; k < 3; ++k) c.add(t[k], log.tau_Nm[k]);
  const auto dir = ident_test::tempDir("rig_log_formats_platform");
  c.writeMat(dir / "platform.mat");
  const ident::ColumnDefinitions d = {geaware::io::parseColumnDefinition("h_m=z[mm]", "--column")};
  const auto m = ident::readPlatformLog(dir / "platform.mat", {}, d);
  ASSERT_EQ(m.size(), log.size());
  for (std::size_t i = 0; i < log.size(); ++i) ASSERT_NEAR(m.h_m[i], log.h_m[i], 1e-12) << i;
  EXPECT_EQ(m.f_N[2], log.f_N[2]);
  EXPECT_EQ(m.tau_Nm[1], log.tau_Nm[1]);
  // Without the definition: the missing field is named, with the fields the file has.
  try {
    (void)ident::readPlatformLog(dir / "platform.mat");
    FAIL() << "no error";
  } catch (const std::exception& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find((dir / "platform.mat").string()), std::string::npos) << what;
    EXPECT_NE(what.find("'h_m'"), std::string::npos) << what;
  }
}

}  // namespace
