// SPDX-License-Identifier: BSD-3-Clause
// Merging values into a base vehicle file: only the merged keys change, comments and every
// other key are kept, the result loads, and the base file is never touched. Styles the
// line-level edit does not handle fall back to re-emitting the whole file.

#include <cmath>
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

TEST_F(VehicleWriter, MergesFittedKeysAndKeepsEverythingElse) {
  const std::string before = slurp(base_);
  const auto out = dir_ / "fitted.yaml";
  const auto result = writeVehicleFile(base_, out, someUpdate());
  EXPECT_TRUE(result.comments_preserved);
  EXPECT_EQ(slurp(base_), before);  // the base is untouched

  const auto merged = geaware::io::loadVehicleFile(out);
  const auto orig = geaware::io::loadVehicleFile(base_);
  EXPECT_EQ(merged.rotor.k_T_N_per_rpm2, 3.9e-8);
  EXPECT_EQ(merged.additional_thrust.g1_m2, 0.0175);
  EXPECT_EQ(merged.leveling_torque.scale_m4, 2.2e-5);
  EXPECT_EQ(merged.drag.heights_m, (std::vector<double>{0.1, 0.3, 2.0}));
  // Untouched keys keep their values…
  EXPECT_EQ(merged.name, orig.name);
  EXPECT_EQ(merged.mass_kg, orig.mass_kg);
  EXPECT_EQ(merged.rotor.k_TX_N_per_rpm2, orig.rotor.k_TX_N_per_rpm2);
  EXPECT_EQ(merged.additional_thrust.g2_m2, orig.additional_thrust.g2_m2);
  EXPECT_EQ(merged.throttle.c0_rpm2, orig.throttle.c0_rpm2);
  // …and the text: only the six replaced lines differ, and they say where the value came from.
  const auto a = lines(before);
  const auto b = lines(slurp(out));
  ASSERT_EQ(a.size(), b.size());
  int changed = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] == b[i]) continue;
    ++changed;
    EXPECT_NE(b[i].find("# identified from platform.csv"), std::string::npos) << b[i];
  }
  EXPECT_EQ(changed, 6);
  EXPECT_NE(slurp(out).find("k_T_N_per_rpm2: 3.9e-08"), std::string::npos);
  EXPECT_NE(slurp(out).find("std. error 1.2e-11"), std::string::npos);
}

TEST_F(VehicleWriter, BlockListsFallBackToReEmittingWithoutComments) {
  std::string text = slurp(base_);
  const std::string flow = "heights_m:      [0.10,   0.15,   0.20,   0.30,   0.50,   1.00,   2.00]";
  const auto at = text.find(flow);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, flow.size(),
               "heights_m:\n    - 0.10\n    - 0.15\n    - 0.20\n    - 0.30\n    - 0.50\n    - 1.00\n    - 2.00");
  const auto result = mergeVehicleYaml(text, "block.yaml", someUpdate());
  EXPECT_FALSE(result.comments_preserved);
  ASSERT_FALSE(result.notes.empty());
  const auto merged = geaware::io::parseVehicleYaml(result.yaml, "merged");
  EXPECT_EQ(merged.drag.d_y_N_per_mps, (std::vector<double>{0.2, 0.3, 0.33}));
  EXPECT_EQ(merged.rotor.J_R_kgm2, geaware_test::paperParams().rotor.J_R_kgm2);
  EXPECT_EQ(merged.inertia_kgm2, geaware_test::paperParams().inertia_kgm2);
}

TEST_F(VehicleWriter, InvalidResultIsRejectedAndNothingIsWritten) {
  VehicleUpdate u;
  u.set("ground_effect.additional_thrust.g1_m2", -0.01);  // out of range
  const auto out = dir_ / "bad.yaml";
  EXPECT_THROW((void)writeVehicleFile(base_, out, u), geaware::io::ConfigError);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_THROW(u.set("mass_kg", 2.0), std::invalid_argument);  // not an identified key
  EXPECT_THROW(u.set("rotor.k_T_N_per_rpm2", std::nan("")), std::invalid_argument);
}

TEST_F(VehicleWriter, OverwritesTheBaseOnlyWhenItIsTheNamedOutput) {
  VehicleUpdate u;
  u.set("rotor.k_I_Nm_per_rpm2", 6.5e-10);
  (void)writeVehicleFile(base_, base_, u);
  EXPECT_EQ(geaware::io::loadVehicleFile(base_).rotor.k_I_Nm_per_rpm2, 6.5e-10);
  EXPECT_FALSE(fs::exists(dir_ / "base.yaml.tmp"));
}

TEST_F(VehicleWriter, TableRewriteKeepsWindowsLineEndings) {
  std::string text;
  for (const auto& l : lines(slurp(base_))) text += l + "\r\n";
  VehicleUpdate u;
  u.setTable(kThrust, {0.08, 0.1, 0.15, 0.3}, {0.3, 0.22, 0.12, 0.04}, {0.01, 0.01, 0.01, 0.01});
  const auto result = mergeVehicleYaml(text, "crlf.yaml", u);
  EXPECT_TRUE(result.comments_preserved);
  for (const auto& l : lines(result.yaml)) {
    ASSERT_FALSE(l.empty());
    EXPECT_EQ(l.back(), '\r') << l;
  }
  EXPECT_EQ(geaware::io::parseVehicleYaml(result.yaml, "merged").additional_thrust.table.values[1],
            0.22);
}

TEST_F(VehicleWriter, FlowStyleSectionsFallBackToReEmitting) {
  const std::string paper = slurp(base_);
  const std::string flow = withSection(paper, "additional_thrust",
                                       "  additional_thrust: {g1_m2: 1.804e-2, g2_m2: 7.339e-3}\n");
  ASSERT_NE(flow, paper);
  VehicleUpdate u;
  u.setTable(kThrust, {0.08, 0.1, 0.15, 0.3}, {0.3, 0.22, 0.12, 0.04}, {0.01, 0.01, 0.01, 0.01});
  u.set("rotor.J_R_kgm2", 1.1e-4);
  const auto result = mergeVehicleYaml(flow, "flow.yaml", u);
  EXPECT_FALSE(result.comments_preserved);
  ASSERT_FALSE(result.notes.empty());
  EXPECT_NE(result.notes.front().find(kThrust), std::string::npos) << result.notes.front();
  EXPECT_EQ(result.yaml.find('#'), std::string::npos);  // comments are lost, and said to be
  const auto merged = geaware::io::parseVehicleYaml(result.yaml, "merged");
  const auto orig = geaware::io::parseVehicleYaml(paper, "base");
  EXPECT_EQ(merged.additional_thrust.table.values, (std::vector<double>{0.3, 0.22, 0.12, 0.04}));
  EXPECT_EQ(merged.rotor.J_R_kgm2, 1.1e-4);
  EXPECT_EQ(merged.leveling_torque.g3_m, orig.leveling_torque.g3_m);
  EXPECT_EQ(merged.drag.d_x_N_per_mps, orig.drag.d_x_N_per_mps);
  EXPECT_EQ(merged.mass_kg, orig.mass_kg);

  // A flow-style table becomes the formula the same way.
  const std::string flow_table =
      withSection(paper, "leveling_torque",
                  "  leveling_torque: {table: {heights_m: [0.1, 0.2], M_G_m: [0.01, 0.02]}}\n");
  ASSERT_TRUE(geaware::io::parseVehicleYaml(flow_table, "flow table")
                  .leveling_torque.table.heights_m.size() == 2);
  VehicleUpdate v;
  v.set("ground_effect.leveling_torque.g3_m", -0.33);
  v.set("ground_effect.leveling_torque.g4_m2", 0.0415);
  v.set("ground_effect.leveling_torque.scale_m4", 2.2e-5);
  const auto back = mergeVehicleYaml(flow_table, "flow_table.yaml", v);
  EXPECT_FALSE(back.comments_preserved);
  const auto formula = geaware::io::parseVehicleYaml(back.yaml, "merged");
  EXPECT_TRUE(formula.leveling_torque.table.empty());
  EXPECT_EQ(formula.leveling_torque.g4_m2, 0.0415);
  EXPECT_EQ(formula.additional_thrust.g2_m2, orig.additional_thrust.g2_m2);
}
}  // namespace

namespace {

TEST_F(VehicleWriter, ValuesReadBackBitForBit) {
  // Values with 17 significant digits, and the next double after one: the file must give back
  // the very doubles that were merged (the shortest round-trip text, not a rounded one).
  VehicleUpdate u;
  const double k_T = 1.0 / 25.0e6 * (1.0 + 1.0 / 3.0);
  const double g1 = std::nextafter(0.0175, 1.0);
  u.set("rotor.k_T_N_per_rpm2", k_T);
  u.set("ground_effect.additional_thrust.g1_m2", g1);
  u.setList("drag.d_x_N_per_mps", {1.0 / 3.0, 0.1 + 0.2, 0.35, 0.4, 0.41, 0.42, 0.43});
  const auto merged = geaware::io::parseVehicleYaml(mergeVehicleYaml(slurp(base_), "base", u).yaml, "m");
  EXPECT_EQ(merged.rotor.k_T_N_per_rpm2, k_T);
  EXPECT_EQ(merged.additional_thrust.g1_m2, g1);
  EXPECT_EQ(merged.drag.d_x_N_per_mps[0], 1.0 / 3.0);
  EXPECT_EQ(merged.drag.d_x_N_per_mps[1], 0.1 + 0.2);
}

}  // namespace
