// SPDX-License-Identifier: BSD-3-Clause
// Truth files (io/truth_file.hpp, docs/truth-file.md): any vehicle file is a truth file whose
// world is its ideal world; the `truth:` section's keys land where the table says, in the
// world's units; unknown keys, bad values and versions are errors naming the file, line and
// key; the writer reads back exactly; the docs' key list is the table; the built-in ideal world
// is today's world.
#include "geaware/io/truth_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "geaware/io/vehicle_file.hpp"

namespace {

namespace io = geaware::io;
namespace sim = geaware::sim;

std::filesystem::path sourceDir() {
  const char* dir = std::getenv("GEAWARE_SOURCE_DIR");
  return dir ? std::filesystem::path(dir) : std::filesystem::current_path();
}

std::string vehicleText() { return std::string(io::builtinVehicleYaml()); }

int lineOf(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  if (at == std::string::npos) return -1;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

std::vector<io::ConfigProblem> problemsOf(const std::string& text) {
  try {
    (void)io::parseTruthYaml(text, "t.yaml");
  } catch (const io::ConfigError& e) {
    EXPECT_EQ(e.file(), "t.yaml");
    return e.problems();
  }
  ADD_FAILURE() << "the truth file was accepted:\n" << text;
  return {};
}

/// Every key of the world's truth section as text, to compare two worlds key by key.
std::string section(const sim::World& w) { return io::truthSectionYaml(w); }

void expectSameTruth(const sim::TruthParams& a, const sim::TruthParams& b) {
  EXPECT_EQ(a.mass_kg, b.mass_kg);
  EXPECT_TRUE(a.inertia_kgm2 == b.inertia_kgm2);
  EXPECT_TRUE(a.cog_offset_B == b.cog_offset_B);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_TRUE(a.rotor_position_B[i] == b.rotor_position_B[i]);
    EXPECT_EQ(a.yaw_sign[i], b.yaw_sign[i]);
    EXPECT_EQ(a.thrust_multiplier[i], b.thrust_multiplier[i]);
  }
  EXPECT_EQ(a.k_T_N_per_rpm2, b.k_T_N_per_rpm2);
  EXPECT_EQ(a.k_I_Nm_per_rpm2, b.k_I_Nm_per_rpm2);
  EXPECT_EQ(a.propeller_radius_m, b.propeller_radius_m);
  EXPECT_EQ(a.motor.J_R_kgm2, b.motor.J_R_kgm2);
  EXPECT_EQ(a.motor.throttle.c0_rpm2, b.motor.throttle.c0_rpm2);
  EXPECT_EQ(a.landing_feet_B.size(), b.landing_feet_B.size());
}

TEST(TruthFile, AVehicleFileIsATruthFileOfItsIdealWorld) {
  const sim::World w = io::parseTruthYaml(vehicleText(), "v.yaml");
  const sim::World ideal = sim::idealWorld(io::builtinVehicle());
  expectSameTruth(w.truth, ideal.truth);
  EXPECT_EQ(section(w), section(ideal));
  EXPECT_EQ(w.source, "v.yaml");
  EXPECT_EQ(w.vehicle.name, "paper_quad");
}

// config/truths/ideal.yaml is today's world: the built-in vehicle's ideal world, key for key.
TEST(TruthFile, TheBuiltInIdealWorldIsTodaysWorld) {
  const sim::World ideal = io::builtinTruth("ideal");
  const sim::World today = sim::idealWorld(io::builtinVehicle());
  expectSameTruth(ideal.truth, today.truth);
  EXPECT_EQ(section(ideal), section(today));
  EXPECT_TRUE(ideal.ground_turbulence);
  EXPECT_FALSE(ideal.room_air);
  EXPECT_FALSE(ideal.variesPerFlight());
  EXPECT_EQ(ideal.source, "config/truths/ideal.yaml");
  // The committed file is the embedded one.
  const sim::World from_file = io::loadTruthFile(sourceDir() / "config/truths/ideal.yaml");
  EXPECT_EQ(section(from_file), section(ideal));
  EXPECT_THROW((void)io::builtinTruth("nowhere"), std::invalid_argument);
}

// config/truths/paper_quad_as_built.yaml carries docs/world.md's values, in the world's units.
TEST(TruthFile, TheAsBuiltWorldIsDocsWorld) {
  const sim::World w = io::builtinTruth("as_built");
  EXPECT_EQ(w.source, "config/truths/paper_quad_as_built.yaml");
  EXPECT_EQ(w.truth.mass_kg, 1.696);
  EXPECT_EQ(w.truth.inertia_kgm2(0, 0), 0.0077048);
  EXPECT_EQ(w.truth.inertia_kgm2(2, 2), 0.0128923);
  EXPECT_EQ(w.truth.cog_offset_B.z(), -0.0017);
  EXPECT_EQ(w.truth.thrust_multiplier[2], 0.97);
  EXPECT_EQ(w.truth.torque_multiplier[2], 1.04);
  EXPECT_NEAR(w.truth.thrust_axis_tilt_rad[2].y(), 0.60 * 3.14159265358979323846 / 180.0, 1e-15);
  EXPECT_EQ(w.truth.motor.dead_time_s, 0.010);
  EXPECT_EQ(w.truth.aero.in_flight_cushion_scale, 0.40);
  EXPECT_EQ(w.truth.aero.induced_velocity_mps, 8.26);
  EXPECT_EQ(w.truth.aero.airframe_drag_area_m2, 0.02);
  EXPECT_EQ(w.sensors.imu.vibration_gyro_std_rad_per_s, 0.0524);
  EXPECT_EQ(w.sensors.imu.lowpass_cutoff_Hz, 20.0);
  EXPECT_EQ(w.sensors.mocap.reported_latency_s, 0.010);
  EXPECT_TRUE(w.unsteadyAtAltitude());
  EXPECT_EQ(w.altitude_unsteadiness_params.torque_std_Nm, 0.0075);
  EXPECT_TRUE(w.room_air);
  EXPECT_EQ(w.room_air_params.gust_correlation_time_s, 1.5);
  EXPECT_TRUE(w.ground_turbulence);
  EXPECT_FALSE(w.variesPerFlight());
  EXPECT_EQ(w.team_scale_error_std_kg, 0.002);
  // What it does not name stays the ideal world's: the rigs' calibrated aerodynamics.
  EXPECT_EQ(w.truth.aero.body_coefficient, sim::RotorAeroParams{}.body_coefficient);
  const sim::World from_file = io::loadTruthFile(sourceDir() / "config/truths/paper_quad_as_built.yaml");
  EXPECT_EQ(section(from_file), section(w));
}

TEST(TruthFile, SectionKeysLandInTheWorld) {
  const std::string text = vehicleText() +
                           "truth:\n"
                           "  motor_k_T_scale: [1.01, 0.99, 1.02, 0.98]\n"
                           "  cog_offset_m: [0.003, -0.002, 0.004]\n"
                           "  motor:\n"
                           "    time_constant_s: 0.025\n"
                           "  sensors:\n"
                           "    mocap:\n"
                           "      latency_s: 0.015\n"
                           "      burst_length_samples: 4\n"
                           "  disturbances:\n"
                           "    room_air:\n"
                           "      enabled: true\n"
                           "      gust_std_mps: [0.2, 0.2, 0.1]\n"
                           "  per_flight_variation:\n"
                           "    mass_rel: 0.01\n"
                           "  team:\n"
                           "    scale_error_std_kg: 0.003\n";
  const sim::World w = io::parseTruthYaml(text, "t.yaml");
  EXPECT_EQ(w.truth.thrust_multiplier[2], 1.02);
  EXPECT_EQ(w.truth.cog_offset_B.y(), -0.002);
  EXPECT_EQ(w.truth.motor.time_constant_s, 0.025);
  EXPECT_EQ(w.sensors.mocap.latency_s, 0.015);
  EXPECT_EQ(w.sensors.mocap.burst_length_samples, 4);
  EXPECT_TRUE(w.room_air);
  EXPECT_EQ(w.room_air_params.gust_std_mps.z(), 0.1);
  EXPECT_TRUE(w.variesPerFlight());
  EXPECT_EQ(w.per_flight_variation.mass_rel, 0.01);
  EXPECT_EQ(w.team_scale_error_std_kg, 0.003);
  // Keys not given keep today's value; the vehicle part still makes the body.
  EXPECT_EQ(w.sensors.imu.rate_Hz, sim::ImuParams{}.rate_Hz);
  EXPECT_EQ(w.truth.mass_kg, 1.696);
}

TEST(TruthFile, UnknownKeysAreNamedWithTheirLine) {
  const std::string text = vehicleText() + "truth:\n  motor:\n    time_constnt_s: 0.02\n  colour: red\n";
  const auto p = problemsOf(text);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].key, "truth.motor.time_constnt_s");
  EXPECT_EQ(p[0].line, lineOf(text, "time_constnt_s"));
  EXPECT_NE(p[0].message.find("unknown key"), std::string::npos) << p[0].message;
  EXPECT_NE(p[0].message.find("time_constant_s"), std::string::npos) << p[0].message;
  EXPECT_EQ(p[1].key, "truth.colour");
  EXPECT_EQ(p[1].line, lineOf(text, "colour"));
  // And at the top level, beside the vehicle keys.
  const std::string top = vehicleText() + "truht:\n  motor: {}\n";
  const auto q = problemsOf(top);
  ASSERT_EQ(q.size(), 1u);
  EXPECT_EQ(q[0].key, "truht");
  EXPECT_EQ(q[0].line, lineOf(top, "truht"));
}

TEST(TruthFile, BadValuesNameTheKeyTheLineAndTheRange) {
  {
    const std::string text = vehicleText() + "truth:\n  motor_k_T_scale: [1.0, 1.0, 2.0, 1.0]\n";
    const auto p = problemsOf(text);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].key, "truth.motor_k_T_scale[2]");
    EXPECT_EQ(p[0].line, lineOf(text, "motor_k_T_scale"));
    EXPECT_NE(p[0].message.find("got 2, expected [0.5, 1.5]"), std::string::npos) << p[0].message;
  }
  {
    const std::string text = vehicleText() + "truth:\n  cog_offset_m: [0.0, 0.0]\n";
    const auto p = problemsOf(text);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].key, "truth.cog_offset_m");
  }
  {
    const std::string text = vehicleText() + "truth:\n  sensors:\n    ranger:\n      side: 17\n";
    const auto p = problemsOf(text);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].key, "truth.sensors.ranger.side");
    EXPECT_EQ(p[0].line, lineOf(text, "side: 17"));
  }
  {
    // A check across keys (the simulator's own): at the key's line.
    const std::string text =
        vehicleText() + "truth:\n  motor:\n    min_speed_rpm: 5000\n    max_speed_rpm: 4000\n";
    const auto p = problemsOf(text);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].key, "truth.motor.max_speed_rpm");
    EXPECT_EQ(p[0].line, lineOf(text, "max_speed_rpm"));
    EXPECT_NE(p[0].message.find("greater than"), std::string::npos) << p[0].message;
  }
  {
    // The vehicle part is checked as a vehicle file is.
    std::string text = vehicleText();
    text.replace(text.find("mass_kg: 1.696"), 14, "mass_kg: -1.696");
    const auto p = problemsOf(text + "truth:\n  motor:\n    time_constant_s: 0.02\n");
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].key, "mass_kg");
  }
}

TEST(TruthFile, FormatVersionIsChecked) {
  std::string text = vehicleText();
  text.replace(text.find("format_version: 1"), 17, "format_version: 2");
  const auto p = problemsOf(text + "truth:\n  motor:\n    time_constant_s: 0.02\n");
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].key, "format_version");
}

// Every key away from its default, written and read back: the same section, exactly.
TEST(TruthFile, TheWriterReadsBackExactly) {
  sim::World w = sim::idealWorld(io::builtinVehicle());
  for (const io::TruthKey& k : io::truthFileKeys()) {
    switch (k.kind) {
      case io::TruthValueKind::kBoolean: k.flag(w) = !k.flag(w); break;
      case io::TruthValueKind::kInteger: k.set_integer(w, static_cast<long>(k.lo) + 1); break;
      default:
        for (std::size_t i = 0; i < k.count(); ++i) {
          // Inside the range, a value with many digits, different per entry.
          const double lo = k.lo_exclusive ? k.lo + 1e-3 * (k.hi - k.lo) : k.lo;
          const double v = lo + (k.hi - lo) * (0.3 + 0.01 * static_cast<double>(i)) / 3.0;
          k.number(w, i) = v * k.to_si;
        }
    }
  }
  // Keep the cross-key checks satisfied: speeds and voltages in order.
  w.truth.motor.min_speed_rpm = 100.0;
  w.truth.motor.max_speed_rpm = 30000.0;
  w.truth.battery.empty_voltage_V = 10.0;
  w.truth.battery.full_voltage_V = 20.0;
  w.truth.battery.initial_charge_used_Ah = 0.1;
  w.sensors.ranger.min_range_m = 0.01;
  w.sensors.mocap.rate_Hz = 120.0;
  w.sensors.mocap.latency_s = 0.0123;
  const std::string written = io::truthSectionYaml(w);
  const sim::World back = io::parseTruthYaml(vehicleText() + written, "t.yaml");
  EXPECT_EQ(io::truthSectionYaml(back), written);
}

/// The table as docs/truth-file.md's key list writes it.
std::string expectedDocTable() {
  std::string s = "| key | unit | valid | meaning |\n|---|---|---|---|\n";
  for (const io::TruthKey& k : io::truthFileKeys()) {
    s += "| `truth." + std::string(k.key) + "` | " + (k.unit.empty() ? "–" : std::string(k.unit)) +
         " | " + k.validText() + " | " + std::string(k.meaning) + " |\n";
  }
  return s;
}

TEST(TruthFile, DocsKeyListIsTheTable) {
  std::ifstream in(sourceDir() / "docs/truth-file.md", std::ios::binary);
  ASSERT_TRUE(in) << "docs/truth-file.md not found from " << sourceDir();
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  const std::string begin = "<!-- truth-keys: begin (checked by TruthFile.DocsKeyListIsTheTable) -->\n";
  const std::string end = "<!-- truth-keys: end -->";
  const auto b = doc.find(begin);
  const auto e = doc.find(end);
  ASSERT_NE(b, std::string::npos) << "no key list in docs/truth-file.md";
  ASSERT_NE(e, std::string::npos);
  EXPECT_EQ(doc.substr(b + begin.size(), e - b - begin.size()), expectedDocTable())
      << "docs/truth-file.md's key list differs from the table; the table's:\n"
      << expectedDocTable();
}

}  // namespace
