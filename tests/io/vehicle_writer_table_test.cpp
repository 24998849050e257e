// SPDX-License-Identifier: BSD-3-Clause
// Ground-effect curves written as tables: a formula section becomes a table in place, a table
// section gets a new table or the formula back, and a failed merge never writes the output.

#include <stdexcept>

#include <gtest/gtest.h>

#include "geaware/io/config_error.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/io/vehicle_writer.hpp"
#include "geaware_test/paper_vehicle.hpp"
#include "vehicle_writer_support.hpp"

namespace {

using namespace vehicle_writer_test;
using geaware::io::mergeVehicleYaml;
using geaware::io::writeVehicleFile;

TEST_F(VehicleWriter, FormulaSectionBecomesATableInPlace) {
  const std::string before = slurp(base_);
  VehicleUpdate u;
  u.provenance = "hover.csv";
  u.set("rotor.k_T_N_per_rpm2", 3.9e-8);
  u.setTable(kThrust, {0.08, 0.1, 0.15, 0.3}, {0.3, 0.22, 0.12, 0.04});
  const auto result = mergeVehicleYaml(before, "base.yaml", u);
  EXPECT_TRUE(result.comments_preserved);
  EXPECT_TRUE(result.notes.empty());

  const auto merged = geaware::io::parseVehicleYaml(result.yaml, "merged");
  const auto orig = geaware::io::parseVehicleYaml(before, "base");
  EXPECT_EQ(merged.additional_thrust.table.heights_m, (std::vector<double>{0.08, 0.1, 0.15, 0.3}));
  EXPECT_EQ(merged.additional_thrust.table.values, (std::vector<double>{0.3, 0.22, 0.12, 0.04}));
  EXPECT_EQ(merged.rotor.k_T_N_per_rpm2, 3.9e-8);
  EXPECT_TRUE(merged.leveling_torque.table.empty());
  EXPECT_EQ(merged.leveling_torque.scale_m4, orig.leveling_torque.scale_m4);
  const geaware::model::GroundEffectModel ge(merged);
  const geaware::model::GroundEffectModel ge_orig(orig);
  EXPECT_EQ(ge.thrustRatio(0.1), 0.22);  // the table, exactly at a knot
  EXPECT_EQ(ge.thrustRatio(0.15), 0.12);
  EXPECT_EQ(ge.levelingCoefficient(0.15), ge_orig.levelingCoefficient(0.15));

  // The k_T line changes in place; of the ground-effect block only the thrust section does.
  auto a = lines(before);
  auto b = lines(result.yaml);
  const auto k_T = std::find_if(a.begin(), a.end(), [](const std::string& l) {
    return l.find("k_T_N_per_rpm2:") != std::string::npos;
  });
  ASSERT_NE(k_T, a.end());
  const auto k_T_line = static_cast<std::size_t>(k_T - a.begin());
  EXPECT_EQ(b[k_T_line], "  k_T_N_per_rpm2: 3.9e-08  # identified from hover.csv");
  b[k_T_line] = a[k_T_line];
  std::string b_text;
  for (const auto& l : b) b_text += l + "\n";
  const auto section =
      changedSectionLines(before, b_text, "additional_thrust", "additional_thrust");
  EXPECT_EQ(section, (std::vector<std::string>{
                         "  additional_thrust:               # F_G table: PCHIP between the "
                         "knots, 1/h² above (docs/vehicle-file.md)",
                         "    table:                         # identified from hover.csv",
                         "      heights_m: [0.08, 0.1, 0.15, 0.3]",
                         "      F_G: [0.3, 0.22, 0.12, 0.04]",
                     }));
  // The formula's comment is gone, the others are kept.
  EXPECT_EQ(result.yaml.find("F_G(h) = g2/(h² + g1)"), std::string::npos);
  EXPECT_NE(result.yaml.find("# 7-inch propellers, 0.178 m diameter"), std::string::npos);
  EXPECT_NE(result.yaml.find("# M_G(h) = scale·h/(h² + g3·h + g4)²"), std::string::npos);
}

TEST_F(VehicleWriter, TableSectionGetsANewTableWithStdErrors) {
  const std::string before = tableBase(slurp(base_));
  VehicleUpdate u;
  u.provenance = "tilt.csv";
  u.setTable(kLeveling, {0.09, 0.12, 0.186, 0.25, 0.4}, {0.01, 0.018, 0.02303, 0.019, 0.008},
             {0.001, 0.0012, 0.0009, 0.0011, 0.0015});
  const auto result = mergeVehicleYaml(before, "tables.yaml", u);
  EXPECT_TRUE(result.comments_preserved);
  const auto merged = geaware::io::parseVehicleYaml(result.yaml, "merged");
  const auto orig = geaware::io::parseVehicleYaml(before, "base");
  EXPECT_EQ(merged.leveling_torque.table.heights_m,
            (std::vector<double>{0.09, 0.12, 0.186, 0.25, 0.4}));
  EXPECT_EQ(merged.leveling_torque.table.values,
            (std::vector<double>{0.01, 0.018, 0.02303, 0.019, 0.008}));
  EXPECT_EQ(merged.additional_thrust.table.values, orig.additional_thrust.table.values);
  EXPECT_EQ(geaware::model::GroundEffectModel(merged).levelingPeakHeight(), 0.186);

  // The old table and the note under it are replaced; everything else is as it was.
  const auto section =
      changedSectionLines(before, result.yaml, "leveling_torque", "leveling_torque");
  EXPECT_EQ(section, (std::vector<std::string>{
                         "  leveling_torque:                 # M_G table [m]: PCHIP between the "
                         "knots, 1/h² above (docs/vehicle-file.md)",
                         "    table:                         # identified from tilt.csv",
                         "      heights_m: [0.09, 0.12, 0.186, 0.25, 0.4]",
                         "      M_G_m: [0.01, 0.018, 0.02303, 0.019, 0.008]",
                         "      # std. errors of M_G_m: [0.001, 0.0012, 0.0009, 0.0011, 0.0015]",
                     }));
  EXPECT_NE(result.yaml.find(kThrustTableBlock), std::string::npos);
}

TEST_F(VehicleWriter, TableSectionsBecomeTheFormulaWhenEveryKeyIsSet) {
  const std::string before = tableBase(slurp(base_));
  VehicleUpdate u;
  u.provenance = "platform.csv";
  u.set("ground_effect.additional_thrust.g1_m2", 0.0175, 3e-4);
  u.set("ground_effect.additional_thrust.g2_m2", 0.0072);
  u.set("ground_effect.leveling_torque.scale_m4", 2.2e-5);
  u.set("ground_effect.leveling_torque.g3_m", -0.33);
  u.set("ground_effect.leveling_torque.g4_m2", 0.0415);
  const auto result = mergeVehicleYaml(before, "tables.yaml", u);
  EXPECT_TRUE(result.comments_preserved);
  const auto merged = geaware::io::parseVehicleYaml(result.yaml, "merged");
  EXPECT_TRUE(merged.additional_thrust.table.empty());
  EXPECT_TRUE(merged.leveling_torque.table.empty());
  EXPECT_EQ(merged.additional_thrust.g1_m2, 0.0175);
  EXPECT_EQ(merged.additional_thrust.g2_m2, 0.0072);
  EXPECT_EQ(merged.leveling_torque.g3_m, -0.33);
  EXPECT_EQ(merged.leveling_torque.g4_m2, 0.0415);
  EXPECT_EQ(merged.leveling_torque.scale_m4, 2.2e-5);

  // Written in the formula's order, whatever the order of the update.
  const auto section =
      changedSectionLines(before, result.yaml, "additional_thrust", "leveling_torque");
  EXPECT_EQ(section, (std::vector<std::string>{
                         "  additional_thrust:               # F_G(h) = g2/(h² + g1)",
                         "    g1_m2: 0.0175                  # identified from platform.csv, "
                         "std. error 0.0003",
                         "    g2_m2: 0.0072                  # identified from platform.csv",
                         "  leveling_torque:                 # M_G(h) = scale·h/(h² + g3·h + "
                         "g4)², in N·m per N per sin δ",
                         "    g3_m: -0.33                    # identified from platform.csv",
                         "    g4_m2: 0.0415                  # identified from platform.csv",
                         "    scale_m4: 2.2e-05              # identified from platform.csv",
                     }));
}

TEST_F(VehicleWriter, FormulaIntoATableNeedsEveryFormulaKey) {
  const std::string base = tableBase(slurp(base_));
  VehicleUpdate u;
  u.set("ground_effect.additional_thrust.g1_m2", 0.0175);
  try {
    (void)mergeVehicleYaml(base, "tables.yaml", u);
    ADD_FAILURE() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ground_effect.additional_thrust.g2_m2 is missing"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("set g1_m2 and g2_m2 together"), std::string::npos)
        << e.what();
  }
  VehicleUpdate v;
  v.set("ground_effect.leveling_torque.g3_m", -0.33);
  v.set("ground_effect.leveling_torque.g4_m2", 0.0415);
  try {
    (void)mergeVehicleYaml(base, "tables.yaml", v);
    ADD_FAILURE() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("scale_m4 is missing"), std::string::npos) << e.what();
  }
  // A single formula key into a formula base is an ordinary in-place edit.
  const auto ok = mergeVehicleYaml(slurp(base_), "base.yaml", v);
  EXPECT_TRUE(ok.comments_preserved);
  EXPECT_EQ(geaware::io::parseVehicleYaml(ok.yaml, "merged").leveling_torque.g3_m, -0.33);
}

TEST_F(VehicleWriter, BothCurvesBecomeTablesAtOnce) {
  const std::string before = slurp(base_);
  VehicleUpdate u;
  u.provenance = "rig";
  u.set("ground_effect.additional_thrust.g1_m2", 0.0175);  // replaced by the table below
  u.setTable(kThrust, {0.08, 0.1, 0.15, 0.3}, {0.3, 0.22, 0.12, 0.04});
  u.setTable(kLeveling, {0.1, 0.15, 0.2, 0.3}, {0.012, 0.02, 0.023, 0.015});
  u.setList("drag.d_y_N_per_mps", {0.2, 0.24, 0.27, 0.3, 0.32, 0.33, 0.33});
  ASSERT_EQ(u.entries().size(), 3u);
  const auto out = dir_ / "tables.yaml";
  const auto result = writeVehicleFile(base_, out, u);
  EXPECT_TRUE(result.comments_preserved);
  EXPECT_EQ(slurp(out), result.yaml);
  const auto merged = geaware::io::loadVehicleFile(out);
  const geaware::model::GroundEffectModel ge(merged);
  EXPECT_EQ(ge.thrustRatio(0.08), 0.3);
  EXPECT_EQ(ge.levelingCoefficient(0.2), 0.023);
  EXPECT_EQ(merged.drag.d_y_N_per_mps[1], 0.24);

  // Lines outside the two sections: only the drag row changed.
  auto b = lines(result.yaml);
  const auto a = lines(before);
  const auto d_y = std::find_if(
      b.begin(), b.end(), [](const std::string& l) { return l.rfind("  d_y_N_per_mps:", 0) == 0; });
  ASSERT_NE(d_y, b.end());
  EXPECT_NE(d_y->find("# identified from rig"), std::string::npos);
  *d_y = a[a.size() - static_cast<std::size_t>(b.end() - d_y)];
  std::string b_text;
  for (const auto& l : b) b_text += l + "\n";
  const auto section = changedSectionLines(before, b_text, "additional_thrust", "leveling_torque");
  ASSERT_EQ(section.size(), 8u);
  EXPECT_EQ(section[1], "    table:                         # identified from rig");
  EXPECT_EQ(section[3], "      F_G: [0.3, 0.22, 0.12, 0.04]");
  EXPECT_EQ(section[7], "      M_G_m: [0.012, 0.02, 0.023, 0.015]");
}

TEST_F(VehicleWriter, SetTableRejectsInvalidInput) {
  VehicleUpdate u;
  const std::vector<double> h = {0.1, 0.2, 0.3};
  const std::vector<double> v = {0.2, 0.1, 0.05};
  EXPECT_THROW(u.setTable("ground_effect", h, v), std::invalid_argument);
  EXPECT_THROW(u.setTable("drag", h, v), std::invalid_argument);
  EXPECT_THROW(u.setTable("ground_effect.additional_thrust.table", h, v), std::invalid_argument);
  EXPECT_THROW(u.setTable(kThrust, {0.1}, {0.2}), std::invalid_argument);  // 1 knot
  EXPECT_THROW(u.setTable(kThrust, {}, {}), std::invalid_argument);
  EXPECT_THROW(u.setTable(kThrust, h, {0.2, 0.1}), std::invalid_argument);       // sizes
  EXPECT_THROW(u.setTable(kThrust, h, v, {0.01, 0.01}), std::invalid_argument);  // errors
  EXPECT_THROW(u.setTable(kThrust, {0.1, std::nan(""), 0.3}, v), std::invalid_argument);
  EXPECT_THROW(u.setTable(kLeveling, h, {0.02, HUGE_VAL, 0.01}), std::invalid_argument);
  EXPECT_THROW(u.setTable(kLeveling, h, v, {0.01, std::nan(""), 0.01}), std::invalid_argument);
  EXPECT_TRUE(u.empty());
  u.setTable(kLeveling, h, v, {});  // no errors: fine
  u.setTable(kThrust, h, v, {0.01, 0.02, 0.03});
  EXPECT_EQ(u.entries().size(), 2u);
}

TEST_F(VehicleWriter, TablesAndFormulaKeysOfACurveReplaceEachOther) {
  VehicleUpdate u;
  u.set("ground_effect.additional_thrust.g1_m2", 0.0175);
  u.set("ground_effect.additional_thrust.g2_m2", 0.0072);
  u.set("ground_effect.leveling_torque.g3_m", -0.33);
  u.setTable(kThrust, {0.1, 0.2}, {0.2, 0.1});
  ASSERT_EQ(u.entries().size(), 2u);  // g1, g2 gone; g3 (the other curve) kept
  EXPECT_EQ(u.entries()[0].key, "ground_effect.leveling_torque.g3_m");
  EXPECT_TRUE(u.entries()[1].table);
  EXPECT_EQ(u.entries()[1].key, kThrust);
  EXPECT_EQ(u.entries()[1].heights_m, (std::vector<double>{0.1, 0.2}));
  u.setTable(kThrust, {0.1, 0.3}, {0.25, 0.1});  // again: replaces
  ASSERT_EQ(u.entries().size(), 2u);
  EXPECT_EQ(u.entries()[1].values, (std::vector<double>{0.25, 0.1}));
  u.set("ground_effect.additional_thrust.g2_m2", 0.0072);  // a formula key drops the table
  ASSERT_EQ(u.entries().size(), 2u);
  EXPECT_FALSE(u.entries()[1].table);
  EXPECT_EQ(u.entries()[1].key, "ground_effect.additional_thrust.g2_m2");
  u.setTable(kLeveling, {0.1, 0.2}, {0.02, 0.01});
  ASSERT_EQ(u.entries().size(), 2u);
  EXPECT_EQ(u.entries()[1].key, kLeveling);
  // scalar keys keep their rules
  EXPECT_EQ(VehicleUpdate::fittedKeys().size(), 19u);  // with the throttle curve's two voltage keys
                                                       // and the forward fade's v_i
  EXPECT_THROW(u.set(kThrust, 1.0), std::invalid_argument);
}

TEST_F(VehicleWriter, FailedTableMergesNeverWriteTheOutput) {
  const auto out = dir_ / "out.yaml";
  VehicleUpdate too_big;  // F_G = 20 is out of range
  too_big.setTable(kThrust, {0.1, 0.2}, {20.0, 0.1});
  EXPECT_THROW((void)writeVehicleFile(base_, out, too_big),
               geaware::io::ConfigError);
  VehicleUpdate not_increasing;
  not_increasing.setTable(kLeveling, {0.2, 0.1, 0.3}, {0.01, 0.02, 0.01});
  EXPECT_THROW((void)writeVehicleFile(base_, out, not_increasing),
               geaware::io::ConfigError);
  const std::string tables = tableBase(slurp(base_));
  VehicleUpdate partial;
  partial.set("ground_effect.additional_thrust.g2_m2", 0.0072);
  EXPECT_THROW((void)writeVehicleFile(tables, "tables.yaml", out, partial),
               std::invalid_argument);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(dir_ / "out.yaml.tmp"));
  // The error of a bad value names its key.
  try {
    (void)mergeVehicleYaml(slurp(base_), "base.yaml", too_big);
    ADD_FAILURE() << "expected io::ConfigError";
  } catch (const geaware::io::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("ground_effect.additional_thrust.table.F_G[0]"),
              std::string::npos)
        << e.what();
  }
}
}  // namespace
