// Merging fitted parameters into a base vehicle file: only the fitted keys change, comments and
// every other key are kept, the result loads, and the base file is never touched.

#include "geaware/ident/vehicle_writer.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/ground_effect.hpp"
#include "synthetic.hpp"

namespace {

namespace fs = std::filesystem;
using geaware::ident::VehicleUpdate;

fs::path sourceDir() {
  const char* dir = std::getenv("GEAWARE_SOURCE_DIR");
  return dir != nullptr ? fs::path(dir) : fs::current_path();
}

std::string slurp(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream is(text);
  for (std::string l; std::getline(is, l);) out.push_back(l);
  return out;
}

VehicleUpdate someUpdate() {
  VehicleUpdate u;
  u.provenance = "platform.csv";
  u.set("rotor.k_T_N_per_rpm2", 3.9e-8, 1.2e-11);
  u.set("ground_effect.additional_thrust.g1_m2", 0.0175, 3e-4);
  u.set("ground_effect.leveling_torque.scale_m4", 2.2e-5);
  u.setList("drag.heights_m", {0.1, 0.3, 2.0});
  u.setList("drag.d_x_N_per_mps", {0.25, 0.35, 0.4});
  u.setList("drag.d_y_N_per_mps", {0.2, 0.3, 0.33});
  return u;
}

// --- ground-effect tables ------------------------------------------------------------------

constexpr const char* kThrust = "ground_effect.additional_thrust";
constexpr const char* kLeveling = "ground_effect.leveling_torque";

std::size_t indentOf(const std::string& l) {
  const auto i = l.find_first_not_of(' ');
  return i == std::string::npos ? l.size() : i;
}

bool isBlank(const std::string& l) { return l.find_first_not_of(" \r") == std::string::npos; }

/// `text` with the block of the ground_effect section `name` (its key line and every line under
/// it, up to the next line indented no deeper than 2) replaced by `block`.
std::string withSection(const std::string& text, const std::string& name,
                        const std::string& block) {
  const auto ls = lines(text);
  std::string out;
  std::size_t i = 0;
  for (; i < ls.size() && ls[i].rfind("  " + name + ":", 0) != 0; ++i) out += ls[i] + "\n";
  EXPECT_LT(i, ls.size()) << name;
  for (++i; i < ls.size() && (isBlank(ls[i]) || indentOf(ls[i]) > 2); ++i) {
  }
  // Keep the blank lines that ended the block.
  std::size_t blanks = i;
  while (blanks > 0 && isBlank(ls[blanks - 1])) --blanks;
  out += block;
  for (std::size_t j = blanks; j < ls.size(); ++j) out += ls[j] + "\n";
  return out;
}

const std::string kThrustTableBlock =
    "  additional_thrust:               # measured on the platform\n"
    "    table:\n"
    "      heights_m: [0.08, 0.1, 0.15, 0.3]\n"
    "      F_G: [0.3, 0.22, 0.12, 0.04]\n";
const std::string kLevelingTableBlock =
    "  leveling_torque:                 # measured on the platform\n"
    "    table:\n"
    "      heights_m: [0.1, 0.15, 0.2, 0.3]\n"
    "      M_G_m: [0.012, 0.02, 0.023, 0.015]\n"
    "    # a note on the measured table\n";

/// paper_quad.yaml with both curves given as tables.
std::string tableBase(const std::string& paper_quad) {
  return withSection(withSection(paper_quad, "additional_thrust", kThrustTableBlock),
                     "leveling_torque", kLevelingTableBlock);
}

/// Checks that `after` differs from `before` only in the lines from the key line of the
/// ground_effect section `first` to the end of the body of section `last`, and returns those
/// lines of `after`.
std::vector<std::string> changedSectionLines(const std::string& before, const std::string& after,
                                             const std::string& first, const std::string& last) {
  const auto a = lines(before);
  const auto b = lines(after);
  std::size_t k = 0;
  while (k < a.size() && a[k].rfind("  " + first + ":", 0) != 0) ++k;
  std::size_t e = k;
  while (e < a.size() && a[e].rfind("  " + last + ":", 0) != 0) ++e;
  for (++e; e < a.size() && (isBlank(a[e]) || indentOf(a[e]) > 2); ++e) {
  }
  while (isBlank(a[e - 1])) --e;
  const std::size_t tail = a.size() - e;
  EXPECT_LT(e, a.size());
  if (b.size() < k + tail + 1) {
    ADD_FAILURE() << "the merged file is too short";
    return {};
  }
  for (std::size_t i = 0; i < k; ++i) EXPECT_EQ(b[i], a[i]) << "line " << i + 1;
  for (std::size_t j = 0; j < tail; ++j) {
    EXPECT_EQ(b[b.size() - tail + j], a[e + j]) << "line " << e + j + 1 << " of the base";
  }
  return {b.begin() + static_cast<std::ptrdiff_t>(k), b.end() - static_cast<std::ptrdiff_t>(tail)};
}

class VehicleWriter : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = ident_test::tempDir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    base_ = dir_ / "base.yaml";
    fs::copy_file(sourceDir() / "config/vehicles/paper_quad.yaml", base_);
  }
  fs::path dir_;
  fs::path base_;
};

TEST_F(VehicleWriter, MergesFittedKeysAndKeepsEverythingElse) {
  const std::string before = slurp(base_);
  const auto out = dir_ / "fitted.yaml";
  const auto result = geaware::ident::writeVehicleFile(base_, out, someUpdate());
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
  const auto result = geaware::ident::mergeVehicleYaml(text, "block.yaml", someUpdate());
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
  EXPECT_THROW((void)geaware::ident::writeVehicleFile(base_, out, u), geaware::io::ConfigError);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_THROW(u.set("mass_kg", 2.0), std::invalid_argument);  // not an identified key
  EXPECT_THROW(u.set("rotor.k_T_N_per_rpm2", std::nan("")), std::invalid_argument);
}

TEST_F(VehicleWriter, OverwritesTheBaseOnlyWhenItIsTheNamedOutput) {
  VehicleUpdate u;
  u.set("rotor.k_I_Nm_per_rpm2", 6.5e-10);
  (void)geaware::ident::writeVehicleFile(base_, base_, u);
  EXPECT_EQ(geaware::io::loadVehicleFile(base_).rotor.k_I_Nm_per_rpm2, 6.5e-10);
  EXPECT_FALSE(fs::exists(dir_ / "base.yaml.tmp"));
}

TEST_F(VehicleWriter, FitResultsBecomeUpdates) {
  ident_test::PlatformSpec spec;
  spec.level_samples = 5000;
  spec.tilted_samples = 5000;
  const auto log = ident_test::syntheticPlatform(spec, 2);
  const auto& p = geaware_test::paperParams();
  VehicleUpdate u;
  geaware::ident::addAdditionalThrust(u, geaware::ident::fitAdditionalThrust(log));
  geaware::ident::addMixing(u, geaware::ident::fitMixing(log, p.diagonal_rotor_distance_m));
  geaware::ident::addLeveling(
      u, geaware::ident::fitLeveling(log, {p.rotor.k_T_N_per_rpm2, p.rotor.k_TY_N_per_rpm2,
                                           p.diagonal_rotor_distance_m}));
  EXPECT_EQ(u.entries().size(), 9u);
  const auto out = dir_ / "fitted.yaml";
  (void)geaware::ident::writeVehicleFile(base_, out, u);
  const auto merged = geaware::io::loadVehicleFile(out);
  EXPECT_NEAR(merged.additional_thrust.g2_m2 / p.additional_thrust.g2_m2, 1.0, 0.05);
  EXPECT_NEAR(merged.rotor.k_TX_N_per_rpm2 / p.rotor.k_TX_N_per_rpm2, 1.0, 0.02);
  EXPECT_NEAR(merged.leveling_torque.g3_m / p.leveling_torque.g3_m, 1.0, 0.1);
}

TEST_F(VehicleWriter, FormulaSectionBecomesATableInPlace) {
  const std::string before = slurp(base_);
  VehicleUpdate u;
  u.provenance = "hover.csv";
  u.set("rotor.k_T_N_per_rpm2", 3.9e-8);
  u.setTable(kThrust, {0.08, 0.1, 0.15, 0.3}, {0.3, 0.22, 0.12, 0.04});
  const auto result = geaware::ident::mergeVehicleYaml(before, "base.yaml", u);
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
  const auto result = geaware::ident::mergeVehicleYaml(before, "tables.yaml", u);
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
  const auto result = geaware::ident::mergeVehicleYaml(before, "tables.yaml", u);
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
    (void)geaware::ident::mergeVehicleYaml(base, "tables.yaml", u);
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
    (void)geaware::ident::mergeVehicleYaml(base, "tables.yaml", v);
    ADD_FAILURE() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("scale_m4 is missing"), std::string::npos) << e.what();
  }
  // A single formula key into a formula base is an ordinary in-place edit.
  const auto ok = geaware::ident::mergeVehicleYaml(slurp(base_), "base.yaml", v);
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
  const auto result = geaware::ident::writeVehicleFile(base_, out, u);
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

TEST_F(VehicleWriter, TableRewriteKeepsWindowsLineEndings) {
  std::string text;
  for (const auto& l : lines(slurp(base_))) text += l + "\r\n";
  VehicleUpdate u;
  u.setTable(kThrust, {0.08, 0.1, 0.15, 0.3}, {0.3, 0.22, 0.12, 0.04}, {0.01, 0.01, 0.01, 0.01});
  const auto result = geaware::ident::mergeVehicleYaml(text, "crlf.yaml", u);
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
  const auto result = geaware::ident::mergeVehicleYaml(flow, "flow.yaml", u);
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
  const auto back = geaware::ident::mergeVehicleYaml(flow_table, "flow_table.yaml", v);
  EXPECT_FALSE(back.comments_preserved);
  const auto formula = geaware::io::parseVehicleYaml(back.yaml, "merged");
  EXPECT_TRUE(formula.leveling_torque.table.empty());
  EXPECT_EQ(formula.leveling_torque.g4_m2, 0.0415);
  EXPECT_EQ(formula.additional_thrust.g2_m2, orig.additional_thrust.g2_m2);
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
  EXPECT_EQ(VehicleUpdate::fittedKeys().size(), 16u);
  EXPECT_THROW(u.set(kThrust, 1.0), std::invalid_argument);
}

TEST_F(VehicleWriter, FailedTableMergesNeverWriteTheOutput) {
  const auto out = dir_ / "out.yaml";
  VehicleUpdate too_big;  // F_G = 20 is out of range
  too_big.setTable(kThrust, {0.1, 0.2}, {20.0, 0.1});
  EXPECT_THROW((void)geaware::ident::writeVehicleFile(base_, out, too_big),
               geaware::io::ConfigError);
  VehicleUpdate not_increasing;
  not_increasing.setTable(kLeveling, {0.2, 0.1, 0.3}, {0.01, 0.02, 0.01});
  EXPECT_THROW((void)geaware::ident::writeVehicleFile(base_, out, not_increasing),
               geaware::io::ConfigError);
  const std::string tables = tableBase(slurp(base_));
  VehicleUpdate partial;
  partial.set("ground_effect.additional_thrust.g2_m2", 0.0072);
  EXPECT_THROW((void)geaware::ident::writeVehicleFile(tables, "tables.yaml", out, partial),
               std::invalid_argument);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(dir_ / "out.yaml.tmp"));
  // The error of a bad value names its key.
  try {
    (void)geaware::ident::mergeVehicleYaml(slurp(base_), "base.yaml", too_big);
    ADD_FAILURE() << "expected io::ConfigError";
  } catch (const geaware::io::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("ground_effect.additional_thrust.table.F_G[0]"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
