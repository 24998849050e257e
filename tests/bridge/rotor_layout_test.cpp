// SPDX-License-Identifier: BSD-3-Clause
// The vehicle file's rotor layout (rotor_layout.rotorN.{x_m, y_m, spin, px4_motor}): the defaults
// are the mixer's X layout with PX4's quadrotor-x numbering, a layout the file gives is read and
// checked against the mixer, and the bridge's motor map comes from it.
#include <gtest/gtest.h>

#include <string>

#include "geaware/bridge/px4_codec.hpp"
#include "geaware/io/config_error.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/mixer.hpp"

namespace geaware::bridge {
namespace {

std::string withLayout(const std::string& layout) {
  return std::string(io::builtinVehicleYaml()) + "\nrotor_layout:\n" + layout;
}

const char* kPaperLayout =
    "  rotor1: {x_m: 0.123744, y_m: -0.123744, spin: 1, px4_motor: 1}\n"
    "  rotor2: {x_m: -0.123744, y_m: 0.123744, spin: 1, px4_motor: 2}\n"
    "  rotor3: {x_m: 0.123744, y_m: 0.123744, spin: -1, px4_motor: 3}\n"
    "  rotor4: {x_m: -0.123744, y_m: -0.123744, spin: -1, px4_motor: 4}\n";

TEST(RotorLayout, DefaultIsTheMixersXWithPx4QuadXNumbering) {
  const model::VehicleParams v = io::builtinVehicle();
  EXPECT_FALSE(v.rotor_layout.positionsGiven());
  EXPECT_EQ(motorMapOf(v.rotor_layout).px4_index, (std::array<int, 4>{0, 1, 2, 3}));
  // Spins: counter-clockwise (+1) is a reaction torque along −z, the mixer's yaw sign −1.
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(v.rotor_layout.rotors[i].spin, -model::Mixer::yawSigns()[static_cast<Eigen::Index>(i)]);
  }
}

TEST(RotorLayout, TheDocsExampleLoadsAndAnotherWiringIsTheMotorMap) {
  const model::VehicleParams v = io::parseVehicleYaml(withLayout(kPaperLayout), "v.yaml");
  EXPECT_TRUE(v.rotor_layout.positionsGiven());
  std::string swapped = kPaperLayout;
  swapped.replace(swapped.find("px4_motor: 1"), 12, "px4_motor: 7");
  const model::VehicleParams w = io::parseVehicleYaml(withLayout(swapped), "w.yaml");
  EXPECT_EQ(motorMapOf(w.rotor_layout).px4_index, (std::array<int, 4>{6, 1, 2, 3}));
}

/// The error parseVehicleYaml reports for `layout`, or "" when it loads.
std::string errorOf(const std::string& layout) {
  try {
    (void)io::parseVehicleYaml(withLayout(layout), "v.yaml");
  } catch (const io::ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(RotorLayout, APositionOffTheXLayoutIsRefusedWithTheExpectedOne) {
  std::string bad = kPaperLayout;
  bad.replace(bad.find("x_m: 0.123744"), 13, "x_m: 0.150000");
  const std::string e = errorOf(bad);
  EXPECT_NE(e.find("rotor_layout.rotor1.x_m"), std::string::npos) << e;
  EXPECT_NE(e.find("0.123744"), std::string::npos) << e;
}

TEST(RotorLayout, AReversedSpinAndADuplicateMotorAreRefused) {
  std::string spin = kPaperLayout;
  spin.replace(spin.find("spin: 1"), 7, "spin: -1");
  EXPECT_NE(errorOf(spin).find("rotor_layout.rotor1.spin"), std::string::npos) << errorOf(spin);
  std::string dup = kPaperLayout;
  dup.replace(dup.find("px4_motor: 2"), 12, "px4_motor: 1");
  const std::string e = errorOf(dup);
  EXPECT_NE(e.find("rotor_layout.rotor2.px4_motor"), std::string::npos) << e;
  EXPECT_NE(e.find("rotor1 has it"), std::string::npos) << e;
  std::string half = kPaperLayout;
  half.replace(half.find("px4_motor: 4"), 12, "px4_motor: 4.5");
  EXPECT_NE(errorOf(half).find("whole motor number"), std::string::npos) << errorOf(half);
}

}  // namespace
}  // namespace geaware::bridge
