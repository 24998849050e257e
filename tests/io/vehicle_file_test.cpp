// SPDX-License-Identifier: BSD-3-Clause
// Vehicle files (io/vehicle_file): the built-in vehicle is the committed file and carries the
// paper's parameters (docs/paper-facts.md, with its caveats resolved as documented in
// docs/vehicle-file.md), and files on disk load or fail naming the path. Bad files:
// vehicle_file_errors_test.cpp (structure) and vehicle_file_validation_test.cpp (values).

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "geaware/io/config_error.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/ground_effect.hpp"
#include "geaware/model/units.hpp"
#include "vehicle_file_support.hpp"

namespace {

using namespace vehicle_file_test;

// ---------------------------------------------------------------------------------------------
// The built-in vehicle

TEST(BuiltinVehicle, UnmodifiedTextParses) {
  // The base of every bad-file test below: without edits it must load.
  EXPECT_NO_THROW((void)io::parseVehicleYaml(builtinText(), kSource));
  EXPECT_NO_THROW((void)io::builtinVehicle());
}

TEST(BuiltinVehicle, EqualsTheCommittedFile) {
  const auto file = sourceDir() / "config" / "vehicles" / "paper_quad.yaml";
  ASSERT_TRUE(std::filesystem::is_regular_file(file))
      << file << " not found: set GEAWARE_SOURCE_DIR or run from the source root";

  const model::VehicleParams from_file = io::loadVehicleFile(file);
  expectSameVehicle(io::builtinVehicle(), from_file);

  // The embedding is byte-for-byte, so a stale build (file edited, CMake not re-run) shows here.
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  EXPECT_TRUE(text.str() == io::builtinVehicleYaml())
      << "the built-in vehicle YAML differs from " << file << "; re-run CMake";
}

TEST(BuiltinVehicle, HasThePapersParameters) {
  const model::VehicleParams p = io::builtinVehicle();
  EXPECT_EQ(p.name, "paper_quad");
  EXPECT_TRUE(p.validate().empty());

  // Supplementary table (docs/paper-facts.md); k_T is the single-rotor stand's of the three.
  EXPECT_DOUBLE_EQ(p.mass_kg, 1.696);
  EXPECT_MATRIX_NEAR(p.inertia_kgm2, Eigen::Vector3d(0.00745220, 0.00792752, 0.01249522), 0.0);
  EXPECT_DOUBLE_EQ(p.propeller_radius_m, 0.089);
  EXPECT_DOUBLE_EQ(p.min_rotor_plane_height_m, 0.072);
  EXPECT_DOUBLE_EQ(p.diagonal_rotor_distance_m, 0.35);  // estimate, not published
  EXPECT_DOUBLE_EQ(p.rotor.k_T_N_per_rpm2, 4.0083e-8);
  EXPECT_DOUBLE_EQ(p.rotor.k_TX_N_per_rpm2, 4.678e-8);
  EXPECT_DOUBLE_EQ(p.rotor.k_TY_N_per_rpm2, 3.588e-8);
  EXPECT_DOUBLE_EQ(p.rotor.k_I_Nm_per_rpm2, 6.3859e-10);
  EXPECT_DOUBLE_EQ(p.rotor.J_R_kgm2, 1.0556e-4);
  EXPECT_DOUBLE_EQ(p.throttle.c2_rpm2, -1.448471e8);
  EXPECT_DOUBLE_EQ(p.throttle.c1_rpm2, 5.228928e8);
  EXPECT_DOUBLE_EQ(p.throttle.c0_rpm2, 1.033111e7);  // printed 1.033111e8 is a typo
  EXPECT_DOUBLE_EQ(p.additional_thrust.g1_m2, 1.804e-2);
  EXPECT_DOUBLE_EQ(p.additional_thrust.g2_m2, 7.339e-3);
  EXPECT_DOUBLE_EQ(p.leveling_torque.g3_m, -3.365e-1);
  EXPECT_DOUBLE_EQ(p.leveling_torque.g4_m2, 4.126e-2);
  EXPECT_DOUBLE_EQ(p.leveling_torque.scale_m4, 2.1791e-5);
}

TEST(BuiltinVehicle, ThrottleCurveWithCorrectedC0MatchesTheFigure) {
  // docs/paper-facts.md: the throttle figure shows about 3,300 rpm at t = 0 and 19,700 rpm at
  // t = 1, and the corrected curve reproduces it within 3 % (the printed c0 would give 10,200 at
  // t = 0).
  const auto& t = io::builtinVehicle().throttle;
  const auto rpm = [&](double x) {
    return std::sqrt(t.c2_rpm2 * x * x + t.c1_rpm2 * x + t.c0_rpm2);
  };
  constexpr double kFigureReadingTolerance = 0.03;
  EXPECT_NEAR(rpm(0.0) / 3300.0, 1.0, kFigureReadingTolerance);
  EXPECT_NEAR(rpm(0.5) / 15000.0, 1.0, kFigureReadingTolerance);
  EXPECT_NEAR(rpm(1.0) / 19700.0, 1.0, kFigureReadingTolerance);
}

TEST(BuiltinVehicle, LevelingScaleMatchesTheMeasuredPeakTorque) {
  // M_G(h) = scale·h/(h² + g3·h + g4)² peaks at (−g3 + √(g3² + 12·g4))/6 ≈ 0.186 m; the scale is
  // calibrated so that there it equals the measured 0.215 N·m at 15° tilt and 15,000 rpm
  // (T = 4·k_T·15000²). Evaluated here by hand, independently of model/ground_effect.
  const model::VehicleParams p = io::builtinVehicle();
  const auto& l = p.leveling_torque;
  const double h_peak = (-l.g3_m + std::sqrt(l.g3_m * l.g3_m + 12.0 * l.g4_m2)) / 6.0;
  EXPECT_NEAR(h_peak, 0.186, 5e-4);  // docs/paper-facts.md quotes three digits
  const double den = h_peak * h_peak + l.g3_m * h_peak + l.g4_m2;
  const double m_g_peak = l.scale_m4 * h_peak / (den * den);
  const double thrust_N = 4.0 * p.rotor.k_T_N_per_rpm2 * 15000.0 * 15000.0;
  const double measured = 0.215 / (thrust_N * std::sin(15.0 * model::kDegToRad));
  EXPECT_NEAR(thrust_N, 36.07, 0.01);
  // scale_m4 is written to five significant digits: relative tolerance 1e-4.
  EXPECT_NEAR(m_g_peak / measured, 1.0, 1e-4);
  EXPECT_NEAR(m_g_peak, 0.02303, 1e-5);
}

TEST(BuiltinVehicle, DragTableEndsAtHighAltitudeAndStartsAtTheMeasuredRatios) {
  const auto& d = io::builtinVehicle().drag;
  ASSERT_EQ(d.heights_m.size(), 7u);
  ASSERT_EQ(d.d_x_N_per_mps.size(), d.heights_m.size());
  ASSERT_EQ(d.d_y_N_per_mps.size(), d.heights_m.size());
  // Measured: d_x, d_y at 2.0 m, and d(0.1)/d(2.0) = 0.5963 (x), 0.6179 (y).
  EXPECT_DOUBLE_EQ(d.heights_m.front(), 0.10);
  EXPECT_DOUBLE_EQ(d.heights_m.back(), 2.00);
  EXPECT_DOUBLE_EQ(d.d_x_N_per_mps.back(), 0.397);
  EXPECT_DOUBLE_EQ(d.d_y_N_per_mps.back(), 0.33);
  // The table is written to four decimals: half a unit of the last digit.
  constexpr double kRounding = 5e-5;
  EXPECT_NEAR(d.d_x_N_per_mps.front(), 0.5963 * 0.397, kRounding);
  EXPECT_NEAR(d.d_y_N_per_mps.front(), 0.6179 * 0.33, kRounding);
  // The estimated rows in between recover monotonically towards the high-altitude values.
  for (std::size_t i = 1; i < d.heights_m.size(); ++i) {
    EXPECT_GT(d.heights_m[i], d.heights_m[i - 1]) << i;
    EXPECT_GE(d.d_x_N_per_mps[i], d.d_x_N_per_mps[i - 1]) << i;
    EXPECT_GE(d.d_y_N_per_mps[i], d.d_y_N_per_mps[i - 1]) << i;
  }
}

TEST(BuiltinVehicle, EstimatedDragRowsFadeLikeTheAdditionalThrust) {
  // docs/vehicle-file.md: between the measured rows the deficit follows F_G,
  // d(h) = d(2.0) − [d(2.0) − d(0.1)]·(F_G(h) − F_G(2.0))/(F_G(0.1) − F_G(2.0)).
  const model::VehicleParams p = io::builtinVehicle();
  const auto f_g = [&](double h) {
    return p.additional_thrust.g2_m2 / (h * h + p.additional_thrust.g1_m2);
  };
  const auto& d = p.drag;
  const double lo = d.heights_m.front();
  const double hi = d.heights_m.back();
  // Anchored at the measured values (not the rounded first row): d(0.1) = ratio·d(2.0).
  const double dx_hi = d.d_x_N_per_mps.back();
  const double dy_hi = d.d_y_N_per_mps.back();
  const double dx_lo = 0.5963 * dx_hi;
  const double dy_lo = 0.6179 * dy_hi;
  constexpr double kRounding = 5e-5;  // four decimals in the file
  for (std::size_t i = 0; i < d.heights_m.size(); ++i) {
    const double w = (f_g(d.heights_m[i]) - f_g(hi)) / (f_g(lo) - f_g(hi));
    EXPECT_NEAR(d.d_x_N_per_mps[i], dx_hi - (dx_hi - dx_lo) * w, kRounding)
        << "h = " << d.heights_m[i];
    EXPECT_NEAR(d.d_y_N_per_mps[i], dy_hi - (dy_hi - dy_lo) * w, kRounding)
        << "h = " << d.heights_m[i];
  }
}

// ---------------------------------------------------------------------------------------------
// The test helpers themselves

TEST(VehicleFileTestHelpers, ReplaceThrowsWhenTheSnippetDoesNotMatchExactlyOnce) {
  EXPECT_THROW((void)replaced(builtinText(), "no such text in the file", "x"), std::logic_error);
  EXPECT_THROW((void)replaced(builtinText(), "_m2:", "x"), std::logic_error);  // many matches
}

// ---------------------------------------------------------------------------------------------
// Files on disk

class VehicleFileOnDisk : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) /
           ("geaware_vehicle_file_test_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const auto path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  std::filesystem::path dir_;
};

TEST_F(VehicleFileOnDisk, LoadsAValidFile) {
  const auto path = write("good.yaml", builtinText());
  expectSameVehicle(io::loadVehicleFile(path), io::builtinVehicle());
}

TEST_F(VehicleFileOnDisk, ErrorNamesThePathAndLine) {
  const std::string text = replaced(builtinText(), "mass_kg: 1.696", "mass_kg: -1.696");
  const auto path = write("negative_mass.yaml", text);
  try {
    (void)io::loadVehicleFile(path);
    FAIL() << "a negative mass was accepted";
  } catch (const io::ConfigError& e) {
    EXPECT_EQ(e.file(), path.string());
    const std::string prefix =
        path.string() + ":" + std::to_string(lineOf(text, "mass_kg:")) + ": key 'mass_kg': ";
    EXPECT_EQ(std::string(e.what()).rfind(prefix, 0), 0u) << e.what();
  }
}

TEST_F(VehicleFileOnDisk, NonexistentFileIsAnErrorNamingIt) {
  const auto path = dir_ / "does_not_exist.yaml";
  try {
    (void)io::loadVehicleFile(path);
    FAIL() << "loading a nonexistent file succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no such vehicle file"), std::string::npos) << e.what();
  }
}

TEST_F(VehicleFileOnDisk, DirectoryIsAnErrorNamingIt) {
  // A path that exists but cannot be read as a file (permission bits do not stop root, which
  // CI may run as; a directory is unreadable for everyone).
  try {
    (void)io::loadVehicleFile(dir_);
    FAIL() << "loading a directory succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(dir_.string()), std::string::npos) << e.what();
  }
}

}  // namespace
