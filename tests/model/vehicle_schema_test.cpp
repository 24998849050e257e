// SPDX-License-Identifier: BSD-3-Clause
// The vehicle parameter schema: every accessor reaches its own field (an out-of-range value set
// through it is reported at its key and nowhere else), merges take exactly the keys named, the
// visit follows the form a curve is given in, and docs/vehicle-file.md's parameter list is the
// schema's (key, unit, valid range).

#include "geaware/model/vehicle_schema.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "geaware_test/paper_vehicle.hpp"

namespace {

namespace model = geaware::model;
using model::ParamForm;
using model::ParamKind;

const auto& schema() { return model::vehicleSchema(); }

std::filesystem::path sourceDir() {
  const char* dir = std::getenv("GEAWARE_SOURCE_DIR");
  return dir != nullptr ? std::filesystem::path(dir) : std::filesystem::current_path();
}

/// A table given for both curves (the paper's formulas sampled at a few heights).
model::VehicleParams withTables() {
  model::VehicleParams p = geaware_test::paperParams();
  p.additional_thrust.table = {{0.1, 0.2, 0.4}, {0.3, 0.1, 0.03}};
  p.leveling_torque.table = {{0.1, 0.2, 0.3}, {0.01, 0.02, 0.005}};
  return p;
}

TEST(VehicleSchema, KeysAreUniqueAndEveryTableHasItsHeightsFirst) {
  std::set<std::string_view> keys;
  for (const auto& s : schema().specs()) {
    EXPECT_TRUE(keys.insert(s.key).second) << s.key;
    if (s.kind == ParamKind::kList) {
      const auto cols = schema().columns(s.table);
      ASSERT_FALSE(cols.empty());
      EXPECT_TRUE(cols.front()->key.ends_with(".heights_m")) << s.table;
    }
  }
  EXPECT_EQ(keys.size(), 47u);  // 26 numbers and texts, two 2-column tables, the drag table,
                               // 16 of the rotor layout
}

TEST(VehicleSchema, EveryAccessorReachesItsOwnField) {
  // An out-of-range value set through one accessor is reported at that key, and only there.
  for (const auto& base : {geaware_test::paperParams(), withTables()}) {
    ASSERT_TRUE(base.validate().empty());
    for (const auto& s : schema().specs()) {
      if (s.kind == ParamKind::kText || !schema().inUse(s, base)) continue;
      model::VehicleParams p = base;
      const double bad = s.range.hi * 2.0 + 1.0;
      if (s.kind == ParamKind::kNumber) {
        s.number(p) = bad;
      } else {
        s.list(p).back() = bad;
      }
      const auto errors = p.validate();
      ASSERT_FALSE(errors.empty()) << s.key;
      const std::string expected_field =
          std::string(s.key) +
          (s.kind == ParamKind::kList ? "[" + std::to_string(s.listOf(p).size() - 1) + "]" : "");
      EXPECT_EQ(errors.front().field, expected_field);
      EXPECT_NE(errors.front().expected.find(std::string(s.unit)), std::string::npos) << s.key;
    }
  }
}

TEST(VehicleSchema, TheFormInUseIsTheOneValidated) {
  model::VehicleParams p = withTables();
  p.additional_thrust.g1_m2 = -5.0;  // unused: the table is in use
  EXPECT_TRUE(p.validate().empty());
  p.additional_thrust.table = {};
  ASSERT_EQ(p.validate().size(), 1u);
  EXPECT_EQ(p.validate().front().field, "ground_effect.additional_thrust.g1_m2");
}

TEST(VehicleSchema, MergeTakesExactlyTheKeysNamed) {
  const model::VehicleParams base = geaware_test::paperParams();
  model::VehicleParams update = base;
  update.mass_kg = 2.5;
  update.rotor.k_T_N_per_rpm2 = 5e-8;
  update.drag = {{0.2, 1.0}, {0.1, 0.2}, {0.3, 0.4}};
  const auto merged = model::mergeParameters(base, update, {"rotor.k_T_N_per_rpm2", "drag"});
  EXPECT_EQ(merged.rotor.k_T_N_per_rpm2, 5e-8);
  EXPECT_EQ(merged.mass_kg, base.mass_kg);  // not named
  EXPECT_EQ(merged.drag.heights_m, update.drag.heights_m);
  EXPECT_EQ(merged.drag.d_y_N_per_mps, update.drag.d_y_N_per_mps);
  EXPECT_THROW((void)model::mergeParameters(base, update, {"rotor.k_Q"}), std::invalid_argument);
}

TEST(VehicleSchema, MergingAFormulaKeyPutsTheFormulaInUse) {
  const model::VehicleParams tables = withTables();
  const model::VehicleParams formula = geaware_test::paperParams();
  const auto a = model::mergeParameters(tables, formula, {"ground_effect.additional_thrust.g1_m2",
                                                          "ground_effect.additional_thrust.g2_m2"});
  EXPECT_TRUE(a.additional_thrust.table.empty());
  EXPECT_EQ(a.additional_thrust.g2_m2, formula.additional_thrust.g2_m2);
  EXPECT_FALSE(a.leveling_torque.table.empty());  // the other curve keeps its table
  const auto b =
      model::mergeParameters(formula, tables, {"ground_effect.leveling_torque.table"});
  EXPECT_EQ(b.leveling_torque.table.values, tables.leveling_torque.table.values);
  EXPECT_TRUE(b.additional_thrust.table.empty());
}

TEST(VehicleSchema, ForEachParameterVisitsTheFormInUse) {
  std::vector<std::string> keys;
  auto collect = [&](std::string_view key, std::string_view, const auto&) {
    keys.emplace_back(key);
  };
  model::forEachParameter(geaware_test::paperParams(), collect);
  EXPECT_EQ(keys.size(), 43u);  // the name, 18 numbers, the 5 formula keys, the drag table,
                               // the rotor layout's 16
  EXPECT_EQ(keys.front(), "name");
  EXPECT_EQ(std::count(keys.begin(), keys.end(), "ground_effect.additional_thrust.g1_m2"), 1);
  keys.clear();
  model::forEachParameter(withTables(), collect);
  EXPECT_EQ(std::count(keys.begin(), keys.end(), "ground_effect.additional_thrust.g1_m2"), 0);
  EXPECT_EQ(std::count(keys.begin(), keys.end(), "ground_effect.leveling_torque.table.M_G_m"), 1);
  double k_T = 0.0;
  model::forEachParameter(geaware_test::paperParams(),
                          [&](std::string_view key, std::string_view unit, const auto& value) {
                            if constexpr (std::is_same_v<std::decay_t<decltype(value)>, double>) {
                              if (key == "rotor.k_T_N_per_rpm2") {
                                k_T = value;
                                EXPECT_EQ(unit, "N/rpm²");
                              }
                            }
                          });
  EXPECT_EQ(k_T, geaware_test::paperParams().rotor.k_T_N_per_rpm2);
}

/// The schema as docs/vehicle-file.md's parameter list writes it.
std::string expectedDocTable() {
  std::string s = "| key | unit | valid | identified |\n|---|---|---|---|\n";
  for (const auto& spec : schema().specs()) {
    const bool first = spec.kind == ParamKind::kList && schema().columns(spec.table).front() == &spec;
    const bool identified = spec.fitted || spec.form == ParamForm::kTable;
    s += "| `" + std::string(spec.key) + "` | " + (spec.unit.empty() ? "–" : std::string(spec.unit)) +
         " | " + spec.validText(first) + " | " + (identified ? "yes" : "–") + " |\n";
  }
  return s;
}

TEST(VehicleSchema, DocsParameterListIsTheSchema) {
  std::ifstream in(sourceDir() / "docs/vehicle-file.md", std::ios::binary);
  ASSERT_TRUE(in) << "docs/vehicle-file.md not found from " << sourceDir();
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  const std::string begin = "<!-- parameter-list: begin (checked by VehicleSchema.DocsParameterListIsTheSchema) -->\n";
  const std::string end = "<!-- parameter-list: end -->";
  const auto b = doc.find(begin);
  const auto e = doc.find(end);
  ASSERT_NE(b, std::string::npos) << "no parameter list in docs/vehicle-file.md";
  ASSERT_NE(e, std::string::npos);
  EXPECT_EQ(doc.substr(b + begin.size(), e - b - begin.size()), expectedDocTable())
      << "docs/vehicle-file.md's parameter list differs from the schema; the schema's:\n"
      << expectedDocTable();
}

}  // namespace
