// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Shared by the vehicle-file tests: bad files are built from the built-in YAML text by replacing
// exactly one snippet. The replacement helper throws when the snippet does not occur exactly
// once, and the unmodified text is asserted to parse, so a test cannot pass because its edit
// silently did nothing.

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "geaware/io/config_error.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware_test/eigen_matchers.hpp"

namespace vehicle_file_test {

namespace io = geaware::io;
namespace model = geaware::model;

namespace io = geaware::io;
namespace model = geaware::model;

inline constexpr const char* kSource = "test.yaml";

inline std::string builtinText() { return std::string(io::builtinVehicleYaml()); }

/// Index of the only occurrence of `what` in `text`; throws unless there is exactly one, so a
/// test whose snippet no longer matches the built-in file fails loudly instead of testing the
/// unmodified (valid) file.
inline std::size_t uniquePosition(const std::string& text, std::string_view what) {
  const auto pos = text.find(what);
  if (pos == std::string::npos) {
    throw std::logic_error("test snippet not found in the built-in vehicle YAML: '" +
                           std::string(what) + "'");
  }
  if (text.find(what, pos + 1) != std::string::npos) {
    throw std::logic_error("test snippet occurs more than once in the built-in vehicle YAML: '" +
                           std::string(what) + "'");
  }
  return pos;
}

/// `text` with its only occurrence of `from` replaced by `to`.
inline std::string replaced(std::string text, std::string_view from, std::string_view to) {
  text.replace(uniquePosition(text, from), from.size(), to);
  return text;
}

/// 1-based line on which the only occurrence of `what` starts.
inline int lineOf(const std::string& text, std::string_view what) {
  const auto pos = uniquePosition(text, what);
  return 1 +
         static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

/// The error that parsing `yaml` raises, or nothing when it parses.
inline std::optional<io::ConfigError> rejection(const std::string& yaml) {
  try {
    (void)io::parseVehicleYaml(yaml, kSource);
  } catch (const io::ConfigError& e) {
    return e;
  }
  return std::nullopt;
}

/// The problem reported for `key`, or nullptr.
inline const io::ConfigProblem* problemFor(const io::ConfigError& e, std::string_view key) {
  for (const auto& p : e.problems()) {
    if (p.key == key) return &p;
  }
  return nullptr;
}

inline std::string describe(const io::ConfigError& e) { return std::string("what():\n") + e.what(); }

/// The source root: GEAWARE_SOURCE_DIR (CTest sets it), else the working directory (CTest runs
/// the tests from the source root; by hand, run them from there too).
inline std::filesystem::path sourceDir() {
  const char* dir = std::getenv("GEAWARE_SOURCE_DIR");
  return dir ? std::filesystem::path(dir) : std::filesystem::current_path();
}

/// Every field equal (exactly: both sides are parsed from the same digits).
inline void expectSameVehicle(const model::VehicleParams& a, const model::VehicleParams& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.mass_kg, b.mass_kg);
  EXPECT_MATRIX_NEAR(a.inertia_kgm2, b.inertia_kgm2, 0.0);
  EXPECT_EQ(a.diagonal_rotor_distance_m, b.diagonal_rotor_distance_m);
  EXPECT_EQ(a.propeller_radius_m, b.propeller_radius_m);
  EXPECT_EQ(a.min_rotor_plane_height_m, b.min_rotor_plane_height_m);
  EXPECT_EQ(a.rotor.k_T_N_per_rpm2, b.rotor.k_T_N_per_rpm2);
  EXPECT_EQ(a.rotor.k_TX_N_per_rpm2, b.rotor.k_TX_N_per_rpm2);
  EXPECT_EQ(a.rotor.k_TY_N_per_rpm2, b.rotor.k_TY_N_per_rpm2);
  EXPECT_EQ(a.rotor.k_I_Nm_per_rpm2, b.rotor.k_I_Nm_per_rpm2);
  EXPECT_EQ(a.rotor.J_R_kgm2, b.rotor.J_R_kgm2);
  EXPECT_EQ(a.throttle.c2_rpm2, b.throttle.c2_rpm2);
  EXPECT_EQ(a.throttle.c1_rpm2, b.throttle.c1_rpm2);
  EXPECT_EQ(a.throttle.c0_rpm2, b.throttle.c0_rpm2);
  EXPECT_EQ(a.additional_thrust.g1_m2, b.additional_thrust.g1_m2);
  EXPECT_EQ(a.additional_thrust.g2_m2, b.additional_thrust.g2_m2);
  EXPECT_EQ(a.leveling_torque.g3_m, b.leveling_torque.g3_m);
  EXPECT_EQ(a.leveling_torque.g4_m2, b.leveling_torque.g4_m2);
  EXPECT_EQ(a.leveling_torque.scale_m4, b.leveling_torque.scale_m4);
  EXPECT_EQ(a.additional_thrust.table.heights_m, b.additional_thrust.table.heights_m);
  EXPECT_EQ(a.additional_thrust.table.values, b.additional_thrust.table.values);
  EXPECT_EQ(a.leveling_torque.table.heights_m, b.leveling_torque.table.heights_m);
  EXPECT_EQ(a.leveling_torque.table.values, b.leveling_torque.table.values);
  EXPECT_EQ(a.drag.heights_m, b.drag.heights_m);
  EXPECT_EQ(a.drag.d_x_N_per_mps, b.drag.d_x_N_per_mps);
  EXPECT_EQ(a.drag.d_y_N_per_mps, b.drag.d_y_N_per_mps);
}

}  // namespace vehicle_file_test
