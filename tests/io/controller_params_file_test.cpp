// SPDX-License-Identifier: BSD-3-Clause
// Controller-parameters files (docs/controller-params.md): the shipped default file is the
// compiled defaults, a written file reads back bit for bit, the defaults change no
// configuration, a flight with the default file is bit-identical to one without, and bad files
// are refused naming the file, line and key (with the nearest valid key for a misspelt one).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "geaware/control/controller.hpp"
#include "geaware/control/controller_schema.hpp"
#include "geaware/io/controller_params_file.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace {

using namespace geaware;

std::filesystem::path sourceDir() {
  const char* dir = std::getenv("GEAWARE_SOURCE_DIR");
  return dir != nullptr ? std::filesystem::path(dir) : std::filesystem::current_path();
}

std::string readText(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Every configuration `--controller` can name.
std::vector<std::string> configurations() {
  std::vector<std::string> names = {"recommended"};
  for (const char* acc : {"none", "indi", "neural", "model"}) {
    for (const char* torque : {"none", "model", "indi", "model_indi"}) {
      names.push_back(std::string(acc) + ":" + torque);
    }
  }
  return names;
}

/// Whether every field of the two parameter sets is the same (switches too).
bool identical(const control::ControllerParams& a, const control::ControllerParams& b) {
  return control::sameParameterValues(a, b) && a.acceleration == b.acceleration &&
         a.torque == b.torque && a.clearance_guard == b.clearance_guard &&
         a.neural_iterations == b.neural_iterations &&
         a.compensate_rotor_inertia == b.compensate_rotor_inertia &&
         a.ground_effect_height == b.ground_effect_height &&
         control::configurationName(a) == control::configurationName(b);
}

/// The problems of parsing `text`, joined ("" when it parses).
std::string problemsOf(const std::string& text) {
  try {
    (void)io::parseControllerParamsYaml(text, "my_gains.yaml");
  } catch (const io::ConfigError& e) {
    return e.what();
  }
  return "";
}

/// The default text with one line replaced.
std::string withLine(const std::string& from, const std::string& to) {
  std::string t = io::controllerParamsYaml(control::defaultParameterValues());
  const auto at = t.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return t.replace(at, from.size(), to);
}

TEST(ControllerParamsFile, ShippedDefaultFileIsTheCompiledDefaults) {
  const auto path = sourceDir() / "config/controller-params/default.yaml";
  const std::string expected = io::controllerParamsYaml(control::defaultParameterValues());
  EXPECT_EQ(readText(path), expected) << "config/controller-params/default.yaml differs from the "
                                         "compiled defaults; they write:\n" << expected;
  EXPECT_TRUE(control::sameParameterValues(io::loadControllerParamsFile(path),
                                           control::defaultParameterValues()));
}

TEST(ControllerParamsFile, WrittenFileReadsBackBitForBit) {
  control::ControllerParams v = control::defaultParameterValues();
  // Every value changed to another valid one with a long expansion.
  double k = 1.0;
  for (const auto& s : control::controllerSchema().specs()) {
    double& x = s.number(v);
    x = (x == 0.0 ? 0.1 : x) * (1.0 + k / 7.0);
    k += 1.0;
  }
  v.filter_cutoff_hz = 0.2 * v.rate_hz;
  v.k_i_per_s3 = 0.3 * v.k_p_per_s2.cwiseProduct(v.k_v_per_s);
  v.max_tilt_rad = 0.61;
  v.thrust_pi_limit = 0.123456789;
  v.guard_margin_m = 0.0321;
  v.guard_reaction_time_s = 0.07;
  v.dob_time_constant_s = 0.3;
  v.rotor_speed_limit_throttle = 0.25;
  v.rotor_speed_lag_s = 0.05;
  ASSERT_EQ(problemsOf(io::controllerParamsYaml(v)), "");
  const auto back = io::parseControllerParamsYaml(io::controllerParamsYaml(v), "t");
  EXPECT_TRUE(control::sameParameterValues(back, v)) << io::controllerParamsYaml(back);
  EXPECT_FALSE(control::sameParameterValues(back, control::defaultParameterValues()));
  const auto defaults = io::parseControllerParamsYaml(
      io::controllerParamsYaml(control::defaultParameterValues()), "t");
  EXPECT_TRUE(control::sameParameterValues(defaults, control::defaultParameterValues()));
}

TEST(ControllerParamsFile, DefaultsChangeNoConfiguration) {
  const auto values = io::loadControllerParamsFile(sourceDir() / "config/controller-params/default.yaml");
  for (const auto& name : configurations()) {
    control::ControllerParams c;
    ASSERT_TRUE(control::parseConfiguration(name, c)) << name;
    EXPECT_TRUE(identical(control::applyParameters(c, values), c)) << name;
  }
}

TEST(ControllerParamsFile, ValuesReachTheConfigurationAndOnlyTheAdditionsItSwitchesOn) {
  control::ControllerParams v = control::defaultParameterValues();
  v.k_p_per_s2.x() = 4.0;
  v.guard_margin_m = 0.05;
  v.dob_time_constant_s = 0.2;
  control::ControllerParams paper;
  ASSERT_TRUE(control::parseConfiguration("model:model_indi", paper));
  const auto p = control::applyParameters(paper, v);
  EXPECT_EQ(p.k_p_per_s2.x(), 4.0);
  EXPECT_EQ(p.dob_time_constant_s, 0.0);  // off in the paper's configuration: stays off
  EXPECT_EQ(control::configurationName(p), "model:model_indi");
  const auto r = control::applyParameters(control::recommendedControllerParams(), v);
  EXPECT_EQ(r.guard_margin_m, 0.05);
  EXPECT_EQ(r.dob_time_constant_s, 0.2);
  EXPECT_EQ(control::configurationName(r), "model:model_indi+dob+integral+guard+speedloop+proximity");
  EXPECT_EQ(r.rotor_speed_ki_per_s, 15.0);
  EXPECT_EQ(p.rotor_speed_ki_per_s, 0.0);  // an addition: the paper's configuration stays open loop
  // k_i_per_s = 0 switches the speed loop off in `recommended`.
  control::ControllerParams off = control::defaultParameterValues();
  off.rotor_speed_ki_per_s = 0.0;
  EXPECT_EQ(control::configurationName(control::applyParameters(control::recommendedControllerParams(), off)),
            "model:model_indi+dob+integral+guard+proximity");
}

/// A second of hover from 2 cm below the reference, with and without the default file's
/// values: every throttle of every tick is the same double.
TEST(ControllerParamsFile, ControllerWithTheDefaultFileIsBitIdentical) {
  const model::VehicleModel vehicle(io::builtinVehicle());
  const auto values = io::loadControllerParamsFile(sourceDir() / "config/controller-params/default.yaml");
  for (const char* name : {"recommended", "model:model_indi", "indi:indi"}) {
    control::ControllerParams c;
    ASSERT_TRUE(control::parseConfiguration(name, c));
    control::Controller a(vehicle, c);
    control::Controller b(vehicle, control::applyParameters(c, values));
    control::ControllerInput in;
    in.reference.p_W = {0.0, 0.0, 0.3};
    in.estimate.p_W = {0.01, -0.01, 0.28};
    in.height_m = 0.28;
    in.height_valid = true;
    in.accel_B = {0.0, 0.0, 9.81};
    in.rotor_speeds_rpm.setConstant(9000.0);
    for (int i = 0; i < 200; ++i) {
      in.t_s = i / 200.0;
      in.gyro_B = {0.01 * std::sin(i), 0.0, 0.002};
      const auto ya = a.update(in);
      const auto yb = b.update(in);
      for (std::size_t k = 0; k < 4; ++k) ASSERT_EQ(ya.throttle[k], yb.throttle[k]) << name << " tick " << i;
      in.rotor_speeds_rpm = ya.n_des_rpm;
    }
  }
}

TEST(ControllerParamsFile, MisspeltKeyNamesTheFileTheKeyAndTheNearestValidKey) {
  const std::string e = problemsOf(withLine("  k_v_per_s:", "  k_v_per_sec:"));
  EXPECT_NE(e.find("my_gains.yaml"), std::string::npos) << e;
  EXPECT_NE(e.find("position.k_v_per_sec"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'k_v_per_s'"), std::string::npos) << e;
  EXPECT_NE(e.find("position.k_v_per_s"), std::string::npos) << e;  // and the missing key
}

TEST(ControllerParamsFile, NonFiniteAndOutOfRangeValuesAreRefusedAtTheirKey) {
  const std::string nan = problemsOf(withLine("rate_hz: 200", "rate_hz: .nan"));
  EXPECT_NE(nan.find("loop.rate_hz"), std::string::npos) << nan;
  const std::string inf = problemsOf(withLine("max_tilt_rad: 0.7", "max_tilt_rad: .inf"));
  EXPECT_NE(inf.find("attitude.max_tilt_rad"), std::string::npos) << inf;
  const std::string neg = problemsOf(withLine("margin_m: 0.01", "margin_m: -0.01"));
  EXPECT_NE(neg.find("clearance_guard.margin_m"), std::string::npos) << neg;
  EXPECT_NE(neg.find("my_gains.yaml:39:"), std::string::npos) << neg;  // its line
  // Across keys: a cut-off at or above the Nyquist frequency, K^I at the Routh–Hurwitz bound.
  const std::string cut = problemsOf(withLine("filter_cutoff_hz: 30", "filter_cutoff_hz: 100"));
  EXPECT_NE(cut.find("loop.filter_cutoff_hz"), std::string::npos) << cut;
  EXPECT_NE(cut.find("rate_hz/2 = 100"), std::string::npos) << cut;
  std::string ki = io::controllerParamsYaml(control::defaultParameterValues());
  const std::string ki_z = "    z: 1  # 1/s³";
  ki.replace(ki.find(ki_z), ki_z.size(), "    z: 7.5  # 1/s³");
  const std::string ki_e = problemsOf(ki);
  EXPECT_NE(ki_e.find("integral.k_i_per_s3.z"), std::string::npos) << ki_e;
  EXPECT_EQ(problemsOf(withLine("rate_hz: 200", "rate_hz: 500")), "");
}

TEST(ControllerParamsFile, MissingFileAndMissingKeyAreNamed) {
  EXPECT_THROW((void)io::loadControllerParamsFile("no/such/params.yaml"), std::runtime_error);
  const std::string e = problemsOf(withLine("  limit_mps2: 3  # m/s²\n", ""));
  EXPECT_NE(e.find("disturbance_feedforward.limit_mps2"), std::string::npos) << e;
}

TEST(ControllerParamsFile, DocsListEveryKey) {
  const std::string doc = readText(sourceDir() / "docs/controller-params.md");
  ASSERT_FALSE(doc.empty()) << "docs/controller-params.md not found from " << sourceDir();
  for (const auto& s : control::controllerSchema().specs()) {
    std::string key(s.key);
    // Per-axis keys are listed as "`….x`, `.y`, `.z`".
    if (key.ends_with(".y") || key.ends_with(".z")) {
      EXPECT_NE(doc.find("`" + key.substr(0, key.size() - 2) + ".x`, `.y`, `.z`"), std::string::npos) << key;
      continue;
    }
    EXPECT_NE(doc.find("| `" + key + "`"), std::string::npos) << key << " is not in docs/controller-params.md";
  }
}

}  // namespace
