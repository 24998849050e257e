// SPDX-License-Identifier: BSD-3-Clause
// `geaware identify … --json -` and `geaware rig calibrate --json -` as a user runs them: the
// standard output must be ONE JSON document (the text tables go to stderr then), parsed here
// with nlohmann-json, carrying the numbers and the provenance.

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "synthetic.hpp"

namespace {

struct Run {
  int status = -1;
  std::string out;
};

/// Runs the geaware binary with `args` (a shell command tail), stderr discarded.
Run geaware(const std::string& args) {
  const std::string cmd = std::string("'") + GEAWARE_EXE + "' " + args + " 2>/dev/null";
  Run r;
  std::FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  r.status = pclose(p);
  return r;
}

nlohmann::json parse(const Run& r) {
  EXPECT_EQ(r.status, 0);
  return nlohmann::json::parse(r.out);  // throws (test fails) on anything but one document
}

void expectProvenance(const nlohmann::json& doc, const std::string& command_word) {
  ASSERT_TRUE(doc.contains("provenance"));
  const auto& p = doc["provenance"];
  EXPECT_FALSE(p["geaware_version"].get<std::string>().empty());
  EXPECT_NE(p["command_line"].get<std::string>().find(command_word), std::string::npos);
}

/// The rig logs in a directory of the test's own (CTest runs each test as its own process,
/// possibly in parallel).
class IdentifyCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = ident_test::tempDir(std::string("identify_cli_") +
                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
    ASSERT_EQ(geaware("rig platform --heights 0.08:1.0:0.04 --tilts-deg 0:10:5 --rpm 9000:15000:3000 "
                      "--rpm-diff 0:1500:1500 --seed 1 --out '" + (dir_ / "platform.csv").string() + "'")
                  .status,
              0);
    ASSERT_EQ(geaware("rig rotor --throttle 0:1:0.1 --seed 1 --out '" + (dir_ / "rotor.csv").string() + "'").status,
              0);
  }
  std::filesystem::path dir_;
};

TEST_F(IdentifyCli, PlatformJsonOnStdoutIsOneDocumentWithEveryParameter) {
  const auto log = (dir_ / "platform.csv").string();
  const auto doc = parse(geaware("identify platform '" + log + "' --json -"));
  EXPECT_EQ(doc["command"], "platform");
  EXPECT_EQ(doc["log"], log);
  for (const char* key : {"rotor.k_T_N_per_rpm2", "ground_effect.additional_thrust.g1_m2",
                          "rotor.k_TY_N_per_rpm2", "ground_effect.leveling_torque.scale_m4"}) {
    ASSERT_TRUE(doc["parameters"].contains(key)) << key;
    EXPECT_GT(doc["parameters"][key]["value"].get<double>(), 0.0) << key;
    EXPECT_GT(doc["parameters"][key]["std_error"].get<double>(), 0.0) << key;
  }
  EXPECT_TRUE(doc["fits"].contains("f_z = k_T·Σn²·(1 + F_G(h))"));
  EXPECT_EQ(doc["height_bands"].size(), 6U);
  expectProvenance(doc, "identify platform");
  ASSERT_EQ(doc["provenance"]["inputs"].size(), 1U);
  EXPECT_EQ(doc["provenance"]["inputs"][0]["sha256"].get<std::string>().size(), 64U);
}

TEST_F(IdentifyCli, TablesAndRotorAndCorrelationsJson) {
  const auto platform = (dir_ / "platform.csv").string();
  const auto tables = parse(geaware("identify platform '" + platform + "' --ground-effect table --json -"));
  EXPECT_EQ(tables["tables"]["additional_thrust"]["heights_m"][0].get<double>(), 0.08);
  EXPECT_TRUE(tables["tables"]["leveling_torque"].contains("M_G_m"));
  const auto rotor = parse(geaware("identify rotor '" + (dir_ / "rotor.csv").string() + "' --json -"));
  EXPECT_TRUE(rotor["parameters"].contains("rotor.J_R_kgm2"));
  expectProvenance(rotor, "identify rotor");
  const auto corr = parse(geaware("identify correlations '" + platform + "' --json -"));
  EXPECT_EQ(corr["correlations"]["rows"].size(), corr["correlations"]["r"].size());
}

TEST_F(IdentifyCli, HoverFarFromTheGroundGivesKTAloneInTheJson) {
  // A hover at 0.4–0.6 m, in a world without ground effect: k_T, no g1/g2, and the JSON says so.
  const auto log = (dir_ / "hover.csv").string();
  ident_test::writeHoverCsv(log, ident_test::hoverNoGroundEffect(5, 0.4, 0.6));
  const auto& p = geaware_test::paperParams();
  const auto doc = parse(geaware("identify flight --hover '" + log + "' --mass-kg " + std::to_string(p.mass_kg) +
                                 " --json -"));
  ASSERT_TRUE(doc["parameters"].contains("rotor.k_T_N_per_rpm2"));
  EXPECT_NEAR(doc["parameters"]["rotor.k_T_N_per_rpm2"]["value"].get<double>() / p.rotor.k_T_N_per_rpm2, 1.0, 1e-3);
  EXPECT_FALSE(doc["parameters"].contains("ground_effect.additional_thrust.g2_m2"));
  EXPECT_FALSE(doc["ground_effect_fitted"].get<bool>());
  ASSERT_EQ(doc["notes"].size(), 1U);
  EXPECT_NE(doc["notes"][0].get<std::string>().find("F_G not fitted"), std::string::npos);
}

TEST(RigCli, CalibrateJsonOnStdoutIsOneDocument) {
  const auto doc = parse(geaware("rig calibrate --json -"));
  EXPECT_TRUE(doc["all_pass"].get<bool>());
  ASSERT_FALSE(doc["checks"].empty());
  for (const auto& c : doc["checks"]) {
    EXPECT_TRUE(c["paper"].is_number()) << c["name"];
    EXPECT_TRUE(c["ours"].is_number()) << c["name"];
  }
  expectProvenance(doc, "rig calibrate");
}

}  // namespace
