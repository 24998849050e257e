// Merging fitted parameters into a base vehicle file: only the fitted keys change, comments and
// every other key are kept, the result loads, and the base file is never touched.

#include "geaware/ident/vehicle_writer.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "geaware/io/vehicle_file.hpp"
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

}  // namespace
