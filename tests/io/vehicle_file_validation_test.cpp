// SPDX-License-Identifier: BSD-3-Clause
// Vehicle files with physically invalid values (each problem at the line of its key), ground-
// effect curves given as tables, and several problems reported together.

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
// Physical validation, each problem at the line of its key

TEST(VehicleFileErrors, NegativeMassNamesKeyLineAndRange) {
  const std::string text = replaced(builtinText(), "mass_kg: 1.696", "mass_kg: -1.696");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "mass_kg");
  EXPECT_EQ(p.line, lineOf(text, "mass_kg:"));
  EXPECT_NE(p.message.find("-1.696"), std::string::npos) << p.message;
  EXPECT_NE(p.message.find("(0, 1000] kg"), std::string::npos) << p.message;
  // what(): "FILE:LINE: key 'K': MESSAGE"
  EXPECT_EQ(std::string(err->what()),
            std::string(kSource) + ":" + std::to_string(p.line) + ": key 'mass_kg': " + p.message);
}

TEST(VehicleFileErrors, MismatchedDragTableLengths) {
  const std::string text = replaced(builtinText(), "0.3274, 0.3300]", "0.3274]");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "drag");
  // A problem of a whole section is reported at the section header.
  EXPECT_EQ(p.line, lineOf(text, "drag:"));  // the section header
  EXPECT_NE(p.message.find("d_y_N_per_mps: 6"), std::string::npos) << p.message;
  EXPECT_NE(p.message.find("heights_m: 7"), std::string::npos) << p.message;
}

TEST(VehicleFileErrors, EmptyDragTableIsRejected) {
  const std::string text =
      replaced(builtinText(), "[0.10,   0.15,   0.20,   0.30,   0.50,   1.00,   2.00]", "[]");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_NE(problemFor(*err, "drag.heights_m"), nullptr) << describe(*err);
}

TEST(VehicleFileErrors, NonIncreasingDragHeightsNameTheIndex) {
  const std::string text = replaced(builtinText(), "0.15,   0.20,   0.30", "0.15,   0.15,   0.30");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "drag.heights_m[2]");
  EXPECT_EQ(p.line, lineOf(text, "heights_m:"));  // the line of the list entry
  EXPECT_NE(p.message.find("strictly greater"), std::string::npos) << p.message;
}

TEST(VehicleFileErrors, DecreasingThrottleCurve) {
  // Slope at full throttle c1 + 2·c2 = 5.23e8 − 6.0e8 < 0: n² falls near t = 1.
  const std::string text = replaced(builtinText(), "c2_rpm2: -1.448471e8", "c2_rpm2: -3.0e8");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "throttle_curve");
  EXPECT_EQ(p.line, lineOf(text, "throttle_curve:"));  // the section header
  EXPECT_NE(p.message.find("strictly increasing"), std::string::npos) << p.message;
}

TEST(VehicleFileErrors, LevelingTorqueDenominatorThatVanishes) {
  // g3² = 0.113 ≥ 4·g4 = 0.08: h² + g3·h + g4 has a root at h > 0, where M_G is infinite.
  const std::string text = replaced(builtinText(), "g4_m2: 4.126e-2", "g4_m2: 2.0e-2");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "ground_effect.leveling_torque");
  EXPECT_EQ(p.line, lineOf(text, "leveling_torque:"));  // the section header
  EXPECT_NE(p.message.find("g4=0.02"), std::string::npos) << p.message;
}

// ---------------------------------------------------------------------------------------------
// Ground-effect curves given as tables

constexpr std::string_view kThrustFormula = "    g1_m2: 1.804e-2\n    g2_m2: 7.339e-3\n";
constexpr std::string_view kLevelingFormula =
    "    g3_m: -3.365e-1                # shape from the quadrotor platform (peak at 0.186 m)\n"
    "    g4_m2: 4.126e-2\n";

std::string withThrustTable(std::string_view table) {
  return replaced(builtinText(), kThrustFormula, table);
}

TEST(VehicleFileTables, TablesReplaceTheFormulas) {
  std::string text = withThrustTable(
      "    table:                       # F_G measured at three heights\n"
      "      heights_m: [0.08, 0.1, 0.2]\n"
      "      F_G: [0.30, 0.26, 0.12]\n");
  text = replaced(text, kLevelingFormula,
                  "    table:\n      heights_m: [0.1, 0.2, 0.3]\n      M_G_m: [0.015, 0.022, 0.008]\n");
  text = replaced(text, "    scale_m4: 2.1791e-5\n", "");
  const model::VehicleParams p = io::parseVehicleYaml(text, kSource);
  EXPECT_EQ(p.additional_thrust.table.heights_m, (std::vector<double>{0.08, 0.1, 0.2}));
  EXPECT_EQ(p.additional_thrust.table.values, (std::vector<double>{0.30, 0.26, 0.12}));
  EXPECT_EQ(p.leveling_torque.table.heights_m, (std::vector<double>{0.1, 0.2, 0.3}));
  EXPECT_EQ(p.leveling_torque.table.values, (std::vector<double>{0.015, 0.022, 0.008}));
  const model::GroundEffectModel ge(p);
  EXPECT_DOUBLE_EQ(ge.thrustRatio(0.1), 0.26);
  EXPECT_DOUBLE_EQ(ge.levelingCoefficient(0.2), 0.022);
  EXPECT_DOUBLE_EQ(ge.levelingPeakHeight(), 0.2);
}

TEST(VehicleFileTables, TableNextToTheFormulaIsRejectedAtTheFormulasKey) {
  const std::string text = replaced(
      builtinText(), kThrustFormula,
      std::string(kThrustFormula) + "    table: {heights_m: [0.08, 0.2], F_G: [0.3, 0.1]}\n");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 2u) << describe(*err);
  const auto* p = problemFor(*err, "ground_effect.additional_thrust.g1_m2");
  ASSERT_NE(p, nullptr) << describe(*err);
  EXPECT_EQ(p->line, lineOf(text, "g1_m2:"));
  EXPECT_NE(p->message.find("not both"), std::string::npos) << p->message;
  EXPECT_NE(problemFor(*err, "ground_effect.additional_thrust.g2_m2"), nullptr) << describe(*err);
}

TEST(VehicleFileTables, MisnamedValuesListIsMissingAndUnknown) {
  const std::string text =
      withThrustTable("    table:\n      heights_m: [0.08, 0.2]\n      F_G_m: [0.3, 0.1]\n");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  EXPECT_NE(problemFor(*err, "ground_effect.additional_thrust.table.F_G"), nullptr) << describe(*err);
  const auto* unknown = problemFor(*err, "ground_effect.additional_thrust.table.F_G_m");
  ASSERT_NE(unknown, nullptr) << describe(*err);
  EXPECT_EQ(unknown->line, lineOf(text, "F_G_m:"));
}

TEST(VehicleFileTables, BadTableEntryNamesItsIndexAndLine) {
  const std::string text = withThrustTable(
      "    table:\n      heights_m: [0.08, 0.2, 0.15]\n      F_G: [0.3, 0.1, -1.5]\n");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 2u) << describe(*err);
  const auto* h = problemFor(*err, "ground_effect.additional_thrust.table.heights_m[2]");
  ASSERT_NE(h, nullptr) << describe(*err);
  EXPECT_EQ(h->line, lineOf(text, "heights_m: [0.08"));
  EXPECT_NE(h->message.find("strictly greater"), std::string::npos) << h->message;
  const auto* f = problemFor(*err, "ground_effect.additional_thrust.table.F_G[2]");
  ASSERT_NE(f, nullptr) << describe(*err);
  EXPECT_EQ(f->line, lineOf(text, "F_G: ["));
}

TEST(VehicleFileErrors, OverlappingPropellers) {
  // Adjacent rotors are b/√2 = 0.247 m apart; two 0.15 m radii overlap.
  const std::string text =
      replaced(builtinText(), "propeller_radius_m: 0.089", "propeller_radius_m: 0.15");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "geometry.propeller_radius_m");
  EXPECT_EQ(p.line, lineOf(text, "propeller_radius_m:"));
  EXPECT_NE(p.message.find("overlap"), std::string::npos) << p.message;
}

TEST(VehicleFileErrors, InertiaViolatingTheTriangleInequality) {
  // Izz = 0.02 > Ixx + Iyy = 0.0154: no rigid body has these principal moments.
  const std::string text = replaced(builtinText(), "zz: 0.01249522", "zz: 0.02");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "inertia_kgm2.zz");
  EXPECT_EQ(p.line, lineOf(text, "zz:"));
  EXPECT_NE(p.message.find("sum of the other two"), std::string::npos) << p.message;
}

// ---------------------------------------------------------------------------------------------
// Several problems in one file: all reported, one line each

TEST(VehicleFileErrors, SeveralStructuralProblemsAreAllReported) {
  std::string text = builtinText();
  text = replaced(text, "  k_T_N_per_rpm2: 4.0083e-8\n", "");              // missing
  text = replaced(text, "mass_kg: 1.696", "mass_kg: 1.696\ncolour: red");  // unknown
  text = replaced(text, "g2_m2: 7.339e-3", "g2_m2: abc");                  // not a number
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  EXPECT_EQ(err->problems().size(), 3u) << describe(*err);
  EXPECT_NE(problemFor(*err, "rotor.k_T_N_per_rpm2"), nullptr) << describe(*err);
  EXPECT_NE(problemFor(*err, "colour"), nullptr) << describe(*err);
  EXPECT_NE(problemFor(*err, "ground_effect.additional_thrust.g2_m2"), nullptr) << describe(*err);
}

TEST(VehicleFileErrors, SeveralValidationProblemsAreAllReportedOneLineEach) {
  std::string text = builtinText();
  text = replaced(text, "mass_kg: 1.696", "mass_kg: -1.696");
  text = replaced(text, "propeller_radius_m: 0.089", "propeller_radius_m: 0.15");
  text = replaced(text, "J_R_kgm2: 1.0556e-4", "J_R_kgm2: .nan");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 3u) << describe(*err);
  for (const char* key : {"mass_kg", "geometry.propeller_radius_m", "rotor.J_R_kgm2"}) {
    const auto* p = problemFor(*err, key);
    ASSERT_NE(p, nullptr) << key << "\n" << describe(*err);
    const std::string leaf = std::string(key).substr(std::string(key).rfind('.') + 1);
    EXPECT_EQ(p->line, lineOf(text, leaf + ":")) << key;
  }
  // what() has one line per problem, each "FILE:LINE: key 'K': MESSAGE".
  std::istringstream lines(err->what());
  std::size_t i = 0;
  for (std::string line; std::getline(lines, line); ++i) {
    ASSERT_LT(i, err->problems().size()) << describe(*err);
    const auto& p = err->problems()[i];
    EXPECT_EQ(line, std::string(kSource) + ":" + std::to_string(p.line) + ": key '" + p.key +
                        "': " + p.message);
  }
  EXPECT_EQ(i, err->problems().size());
}

}  // namespace
