// SPDX-License-Identifier: BSD-3-Clause
// The rig-log readers on top of the CSV reader: units checked by range, configurable column
// names, and a synthetic platform log read back through a file.

#include "geaware/ident/rig_logs.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "geaware/io/csv_reader.hpp"
#include "synthetic.hpp"

namespace {

using geaware::io::CsvError;

class RigLogs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = ident_test::tempDir(::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  std::filesystem::path file(const std::string& text) {
    const auto f = dir_ / "log.csv";
    ident_test::writeText(f, text);
    return f;
  }
  std::filesystem::path dir_;
};

TEST_F(RigLogs, RigReadersCheckUnitsByRange) {
  // A height logged in millimetres.
  const auto f = file(
      "t_s,h_m,tilt_deg,n1_rpm,n2_rpm,n3_rpm,n4_rpm,fx_N,fy_N,fz_N,tx_Nm,ty_Nm,tz_Nm\n"
      "0,120,0,1,1,1,1,0,0,1,0,0,0\n");
  try {
    (void)geaware::ident::readPlatformLog(f);
    ADD_FAILURE();
  } catch (const CsvError& e) {
    EXPECT_EQ(e.line(), 2u);
    EXPECT_EQ(e.column(), "h_m");
  }
  // Configurable names.
  geaware::ident::RotorStandColumns c;
  c.rpm = "speed";
  const auto g = file("t_s,throttle,speed,thrust_N,torque_Nm\n0,0.1,5000,1,0.01\n1,0.2,6000,1.4,0.02\n");
  const auto log = geaware::ident::readRotorStandLog(g, c);
  EXPECT_EQ(log.rpm, (std::vector<double>{5000.0, 6000.0}));
}

TEST_F(RigLogs, PlatformRoundTripThroughAFile) {
  ident_test::PlatformSpec spec;
  spec.level_samples = 500;
  spec.tilted_samples = 500;
  const auto log = ident_test::syntheticPlatform(spec, 3);
  const auto f = dir_ / "platform.csv";
  ident_test::writePlatformCsv(f, log);
  const auto back = geaware::ident::readPlatformLog(f);
  ASSERT_EQ(back.size(), log.size());
  for (std::size_t i = 0; i < log.size(); i += 97) {
    EXPECT_NEAR(back.f_N[2][i], log.f_N[2][i], 1e-9 * std::abs(log.f_N[2][i]));
    EXPECT_NEAR(back.n_rpm[3][i], log.n_rpm[3][i], 1e-6);
  }
}

}  // namespace
