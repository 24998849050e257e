// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Shared by the vehicle-file writer's tests: a fixture with a copy of paper_quad.yaml in a fresh
// directory, an update touching scalars and lists, and text helpers that build table-form bases
// and check which lines a merge changed.

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "geaware/io/vehicle_writer.hpp"

namespace vehicle_writer_test {

namespace fs = std::filesystem;
using geaware::io::VehicleUpdate;

/// A fresh, empty directory for one test's files.
inline fs::path tempDir(const std::string& name) {
  const auto dir = fs::path(::testing::TempDir()) / ("geaware_io_writer_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

inline fs::path sourceDir() {
  const char* dir = std::getenv("GEAWARE_SOURCE_DIR");
  return dir != nullptr ? fs::path(dir) : fs::current_path();
}

inline std::string slurp(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

inline std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream is(text);
  for (std::string l; std::getline(is, l);) out.push_back(l);
  return out;
}

inline VehicleUpdate someUpdate() {
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

inline constexpr const char* kThrust = "ground_effect.additional_thrust";
inline constexpr const char* kLeveling = "ground_effect.leveling_torque";

inline std::size_t indentOf(const std::string& l) {
  const auto i = l.find_first_not_of(' ');
  return i == std::string::npos ? l.size() : i;
}

inline bool isBlank(const std::string& l) { return l.find_first_not_of(" \r") == std::string::npos; }

/// `text` with the block of the ground_effect section `name` (its key line and every line under
/// it, up to the next line indented no deeper than 2) replaced by `block`.
inline std::string withSection(const std::string& text, const std::string& name,
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

inline const std::string kThrustTableBlock =
    "  additional_thrust:               # measured on the platform\n"
    "    table:\n"
    "      heights_m: [0.08, 0.1, 0.15, 0.3]\n"
    "      F_G: [0.3, 0.22, 0.12, 0.04]\n";
inline const std::string kLevelingTableBlock =
    "  leveling_torque:                 # measured on the platform\n"
    "    table:\n"
    "      heights_m: [0.1, 0.15, 0.2, 0.3]\n"
    "      M_G_m: [0.012, 0.02, 0.023, 0.015]\n"
    "    # a note on the measured table\n";

/// paper_quad.yaml with both curves given as tables.
inline std::string tableBase(const std::string& paper_quad) {
  return withSection(withSection(paper_quad, "additional_thrust", kThrustTableBlock),
                     "leveling_torque", kLevelingTableBlock);
}

/// Checks that `after` differs from `before` only in the lines from the key line of the
/// ground_effect section `first` to the end of the body of section `last`, and returns those
/// lines of `after`.
inline std::vector<std::string> changedSectionLines(const std::string& before, const std::string& after,
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
    dir_ = tempDir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    base_ = dir_ / "base.yaml";
    fs::copy_file(sourceDir() / "config/vehicles/paper_quad.yaml", base_);
  }
  fs::path dir_;
  fs::path base_;
};

}  // namespace vehicle_writer_test
