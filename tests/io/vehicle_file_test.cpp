// Vehicle files (io/vehicle_file): the built-in vehicle is the committed file and carries the
// paper's parameters (shared/reference/FACTS.md, with its caveats resolved as documented in
// docs/vehicle-file.md); every kind of bad file is rejected with the key path, the line and
// what was expected.
//
// Bad files are built from the built-in YAML text by replacing exactly one snippet. The
// replacement helper throws when the snippet does not occur exactly once, and the unmodified
// text is asserted to parse, so a test cannot pass because its edit silently did nothing.

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "geaware/io/config_error.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/ground_effect.hpp"
#include "geaware/model/units.hpp"
#include "geaware_test/eigen_matchers.hpp"

namespace {

namespace io = geaware::io;
namespace model = geaware::model;

constexpr const char* kSource = "test.yaml";

std::string builtinText() { return std::string(io::builtinVehicleYaml()); }

/// Index of the only occurrence of `what` in `text`; throws unless there is exactly one, so a
/// test whose snippet no longer matches the built-in file fails loudly instead of testing the
/// unmodified (valid) file.
std::size_t uniquePosition(const std::string& text, std::string_view what) {
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
std::string replaced(std::string text, std::string_view from, std::string_view to) {
  text.replace(uniquePosition(text, from), from.size(), to);
  return text;
}

/// 1-based line on which the only occurrence of `what` starts.
int lineOf(const std::string& text, std::string_view what) {
  const auto pos = uniquePosition(text, what);
  return 1 +
         static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

/// The error that parsing `yaml` raises, or nothing when it parses.
std::optional<io::ConfigError> rejection(const std::string& yaml) {
  try {
    (void)io::parseVehicleYaml(yaml, kSource);
  } catch (const io::ConfigError& e) {
    return e;
  }
  return std::nullopt;
}

/// The problem reported for `key`, or nullptr.
const io::ConfigProblem* problemFor(const io::ConfigError& e, std::string_view key) {
  for (const auto& p : e.problems()) {
    if (p.key == key) return &p;
  }
  return nullptr;
}

std::string describe(const io::ConfigError& e) { return std::string("what():\n") + e.what(); }

/// The source root: GEAWARE_SOURCE_DIR (CTest sets it), else the working directory (CTest runs
/// the tests from the source root; by hand, run them from there too).
std::filesystem::path sourceDir() {
  const char* dir = std::getenv("GEAWARE_SOURCE_DIR");
  return dir ? std::filesystem::path(dir) : std::filesystem::current_path();
}

/// Every field equal (exactly: both sides are parsed from the same digits).
void expectSameVehicle(const model::VehicleParams& a, const model::VehicleParams& b) {
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

// ---------------------------------------------------------------------------------------------
// The built-in vehicle

TEST(BuiltinVehicle, UnmodifiedTextParses) {
  // The base of every bad-file test below: without edits it must load.
  EXPECT_NO_THROW((void)io::parseVehicleYaml(builtinText(), kSource));
  EXPECT_NO_THROW((void)io::builtinVehicle());
}

TEST(BuiltinVehicle, EqualsTheCommittedFile) {
  const auto file = sourceDir() / "config" / "vehicles" / "paper_quad.yaml";
  ASSERT_TRUE(std::filesystem::is_regular_file(file))
      << file << " not found: set GEAWARE_SOURCE_DIR or run from the source root";

  const model::VehicleParams from_file = io::loadVehicleFile(file);
  expectSameVehicle(io::builtinVehicle(), from_file);

  // The embedding is byte-for-byte, so a stale build (file edited, CMake not re-run) shows here.
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  EXPECT_TRUE(text.str() == io::builtinVehicleYaml())
      << "the built-in vehicle YAML differs from " << file << "; re-run CMake";
}

TEST(BuiltinVehicle, HasThePapersParameters) {
  const model::VehicleParams p = io::builtinVehicle();
  EXPECT_EQ(p.name, "paper_quad");
  EXPECT_TRUE(p.validate().empty());

  // Supplementary table (FACTS.md); k_T is the single-rotor stand's of the three published.
  EXPECT_DOUBLE_EQ(p.mass_kg, 1.696);
  EXPECT_MATRIX_NEAR(p.inertia_kgm2, Eigen::Vector3d(0.00745220, 0.00792752, 0.01249522), 0.0);
  EXPECT_DOUBLE_EQ(p.propeller_radius_m, 0.089);
  EXPECT_DOUBLE_EQ(p.min_rotor_plane_height_m, 0.072);
  EXPECT_DOUBLE_EQ(p.diagonal_rotor_distance_m, 0.35);  // estimate, not published
  EXPECT_DOUBLE_EQ(p.rotor.k_T_N_per_rpm2, 4.0083e-8);
  EXPECT_DOUBLE_EQ(p.rotor.k_TX_N_per_rpm2, 4.678e-8);
  EXPECT_DOUBLE_EQ(p.rotor.k_TY_N_per_rpm2, 3.588e-8);
  EXPECT_DOUBLE_EQ(p.rotor.k_I_Nm_per_rpm2, 6.3859e-10);
  EXPECT_DOUBLE_EQ(p.rotor.J_R_kgm2, 1.0556e-4);
  EXPECT_DOUBLE_EQ(p.throttle.c2_rpm2, -1.448471e8);
  EXPECT_DOUBLE_EQ(p.throttle.c1_rpm2, 5.228928e8);
  EXPECT_DOUBLE_EQ(p.throttle.c0_rpm2, 1.033111e7);  // printed 1.033111e8 is a typo
  EXPECT_DOUBLE_EQ(p.additional_thrust.g1_m2, 1.804e-2);
  EXPECT_DOUBLE_EQ(p.additional_thrust.g2_m2, 7.339e-3);
  EXPECT_DOUBLE_EQ(p.leveling_torque.g3_m, -3.365e-1);
  EXPECT_DOUBLE_EQ(p.leveling_torque.g4_m2, 4.126e-2);
  EXPECT_DOUBLE_EQ(p.leveling_torque.scale_m4, 2.1791e-5);
}

TEST(BuiltinVehicle, ThrottleCurveWithCorrectedC0MatchesTheFigure) {
  // FACTS.md: the throttle figure shows about 3,300 rpm at t = 0 and 19,700 rpm at t = 1, and
  // the corrected curve reproduces it within 3 % (the printed c0 would give 10,200 at t = 0).
  const auto& t = io::builtinVehicle().throttle;
  const auto rpm = [&](double x) {
    return std::sqrt(t.c2_rpm2 * x * x + t.c1_rpm2 * x + t.c0_rpm2);
  };
  constexpr double kFigureReadingTolerance = 0.03;
  EXPECT_NEAR(rpm(0.0) / 3300.0, 1.0, kFigureReadingTolerance);
  EXPECT_NEAR(rpm(0.5) / 15000.0, 1.0, kFigureReadingTolerance);
  EXPECT_NEAR(rpm(1.0) / 19700.0, 1.0, kFigureReadingTolerance);
}

TEST(BuiltinVehicle, LevelingScaleMatchesTheMeasuredPeakTorque) {
  // M_G(h) = scale·h/(h² + g3·h + g4)² peaks at (−g3 + √(g3² + 12·g4))/6 ≈ 0.186 m; the scale is
  // calibrated so that there it equals the measured 0.215 N·m at 15° tilt and 15,000 rpm
  // (T = 4·k_T·15000²). Evaluated here by hand, independently of model/ground_effect.
  const model::VehicleParams p = io::builtinVehicle();
  const auto& l = p.leveling_torque;
  const double h_peak = (-l.g3_m + std::sqrt(l.g3_m * l.g3_m + 12.0 * l.g4_m2)) / 6.0;
  EXPECT_NEAR(h_peak, 0.186, 5e-4);  // FACTS.md quotes three digits
  const double den = h_peak * h_peak + l.g3_m * h_peak + l.g4_m2;
  const double m_g_peak = l.scale_m4 * h_peak / (den * den);
  const double thrust_N = 4.0 * p.rotor.k_T_N_per_rpm2 * 15000.0 * 15000.0;
  const double measured = 0.215 / (thrust_N * std::sin(15.0 * model::kDegToRad));
  EXPECT_NEAR(thrust_N, 36.07, 0.01);
  // scale_m4 is written to five significant digits: relative tolerance 1e-4.
  EXPECT_NEAR(m_g_peak / measured, 1.0, 1e-4);
  EXPECT_NEAR(m_g_peak, 0.02303, 1e-5);
}

TEST(BuiltinVehicle, DragTableEndsAtHighAltitudeAndStartsAtTheMeasuredRatios) {
  const auto& d = io::builtinVehicle().drag;
  ASSERT_EQ(d.heights_m.size(), 7u);
  ASSERT_EQ(d.d_x_N_per_mps.size(), d.heights_m.size());
  ASSERT_EQ(d.d_y_N_per_mps.size(), d.heights_m.size());
  // Measured: d_x, d_y at 2.0 m, and d(0.1)/d(2.0) = 0.5963 (x), 0.6179 (y).
  EXPECT_DOUBLE_EQ(d.heights_m.front(), 0.10);
  EXPECT_DOUBLE_EQ(d.heights_m.back(), 2.00);
  EXPECT_DOUBLE_EQ(d.d_x_N_per_mps.back(), 0.397);
  EXPECT_DOUBLE_EQ(d.d_y_N_per_mps.back(), 0.33);
  // The table is written to four decimals: half a unit of the last digit.
  constexpr double kRounding = 5e-5;
  EXPECT_NEAR(d.d_x_N_per_mps.front(), 0.5963 * 0.397, kRounding);
  EXPECT_NEAR(d.d_y_N_per_mps.front(), 0.6179 * 0.33, kRounding);
  // The estimated rows in between recover monotonically towards the high-altitude values.
  for (std::size_t i = 1; i < d.heights_m.size(); ++i) {
    EXPECT_GT(d.heights_m[i], d.heights_m[i - 1]) << i;
    EXPECT_GE(d.d_x_N_per_mps[i], d.d_x_N_per_mps[i - 1]) << i;
    EXPECT_GE(d.d_y_N_per_mps[i], d.d_y_N_per_mps[i - 1]) << i;
  }
}

TEST(BuiltinVehicle, EstimatedDragRowsFadeLikeTheAdditionalThrust) {
  // docs/vehicle-file.md: between the measured rows the deficit follows F_G,
  // d(h) = d(2.0) − [d(2.0) − d(0.1)]·(F_G(h) − F_G(2.0))/(F_G(0.1) − F_G(2.0)).
  const model::VehicleParams p = io::builtinVehicle();
  const auto f_g = [&](double h) {
    return p.additional_thrust.g2_m2 / (h * h + p.additional_thrust.g1_m2);
  };
  const auto& d = p.drag;
  const double lo = d.heights_m.front();
  const double hi = d.heights_m.back();
  // Anchored at the measured values (not the rounded first row): d(0.1) = ratio·d(2.0).
  const double dx_hi = d.d_x_N_per_mps.back();
  const double dy_hi = d.d_y_N_per_mps.back();
  const double dx_lo = 0.5963 * dx_hi;
  const double dy_lo = 0.6179 * dy_hi;
  constexpr double kRounding = 5e-5;  // four decimals in the file
  for (std::size_t i = 0; i < d.heights_m.size(); ++i) {
    const double w = (f_g(d.heights_m[i]) - f_g(hi)) / (f_g(lo) - f_g(hi));
    EXPECT_NEAR(d.d_x_N_per_mps[i], dx_hi - (dx_hi - dx_lo) * w, kRounding)
        << "h = " << d.heights_m[i];
    EXPECT_NEAR(d.d_y_N_per_mps[i], dy_hi - (dy_hi - dy_lo) * w, kRounding)
        << "h = " << d.heights_m[i];
  }
}

// ---------------------------------------------------------------------------------------------
// The test helpers themselves

TEST(VehicleFileTestHelpers, ReplaceThrowsWhenTheSnippetDoesNotMatchExactlyOnce) {
  EXPECT_THROW((void)replaced(builtinText(), "no such text in the file", "x"), std::logic_error);
  EXPECT_THROW((void)replaced(builtinText(), "_m2:", "x"), std::logic_error);  // many matches
}

// ---------------------------------------------------------------------------------------------
// Structural problems: missing keys, unknown keys, wrong types, malformed YAML

TEST(VehicleFileErrors, MissingKeyNamesTheFullKeyPath) {
  const std::string text = replaced(builtinText(), "  k_T_N_per_rpm2: 4.0083e-8\n", "");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "rotor.k_T_N_per_rpm2");
  EXPECT_NE(p.message.find("missing"), std::string::npos) << p.message;
  // A missing key has no line of its own; it is reported inside its parent map.
  EXPECT_GE(p.line, lineOf(text, "rotor:"));
  EXPECT_LE(p.line, lineOf(text, "k_TX_N_per_rpm2:"));
  EXPECT_NE(std::string(err->what()).find("key 'rotor.k_T_N_per_rpm2'"), std::string::npos)
      << describe(*err);
}

TEST(VehicleFileErrors, MissingNestedKeyTwoLevelsDown) {
  const auto err = rejection(replaced(builtinText(), "    g4_m2: 4.126e-2\n", ""));
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  EXPECT_EQ(err->problems().front().key, "ground_effect.leveling_torque.g4_m2");
  EXPECT_NE(err->problems().front().message.find("missing"), std::string::npos);
}

TEST(VehicleFileErrors, MissingSectionIsReportedOnceNotPerChild) {
  const std::string base = builtinText();
  const auto begin = uniquePosition(base, "\ninertia_kgm2:") + 1;
  const auto end = uniquePosition(base, "\ngeometry:") + 1;
  std::string text = base;
  text.erase(begin, end - begin);
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  EXPECT_EQ(err->problems().front().key, "inertia_kgm2");
  EXPECT_NE(err->problems().front().message.find("missing"), std::string::npos);
}

TEST(VehicleFileErrors, EmptyValueIsRejected) {
  const std::string text = replaced(builtinText(), "mass_kg: 1.696", "mass_kg:");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  const auto* p = problemFor(*err, "mass_kg");
  ASSERT_NE(p, nullptr) << describe(*err);
  EXPECT_NE(p->message.find("no value"), std::string::npos) << p->message;
}

TEST(VehicleFileErrors, UnknownKeyIsNamedWithItsLine) {
  const std::string text = replaced(builtinText(), "  k_TX_N_per_rpm2: 4.678e-8",
                                    "  k_TZ_N_per_rpm2: 1.0e-8\n  k_TX_N_per_rpm2: 4.678e-8");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "rotor.k_TZ_N_per_rpm2");
  EXPECT_EQ(p.line, lineOf(text, "k_TZ_N_per_rpm2"));
  EXPECT_NE(p.message.find("unknown key"), std::string::npos) << p.message;
  // The message lists what is allowed there, so a typo is easy to fix.
  EXPECT_NE(p.message.find("k_TX_N_per_rpm2"), std::string::npos) << p.message;
}

TEST(VehicleFileErrors, UnknownTopLevelKeyIsNamedWithItsLine) {
  const std::string text = replaced(builtinText(), "mass_kg: 1.696", "mass_kg: 1.696\nmas_kg: 1.7");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  EXPECT_EQ(err->problems().front().key, "mas_kg");
  EXPECT_EQ(err->problems().front().line, lineOf(text, "mas_kg"));
}

// KNOWN BUG (loader, not this test): yaml-cpp accepts duplicate keys and the loader reads the
// first occurrence, silently ignoring the second. Strict loading should reject the file. Enable
// once src/io/yaml_reader.cpp reports duplicates.
TEST(VehicleFileErrors, DuplicateKeyIsRejected) {
  const std::string text =
      replaced(builtinText(), "mass_kg: 1.696", "mass_kg: 2.0\nmass_kg: 1.696");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value()) << "a duplicate key was accepted";
  const auto* p = problemFor(*err, "mass_kg");
  ASSERT_NE(p, nullptr) << describe(*err);
  EXPECT_EQ(p->line, lineOf(text, "mass_kg: 1.696"));
}

TEST(VehicleFileErrors, NonNumericValueIsQuotedWithItsLine) {
  const std::string text =
      replaced(builtinText(), "k_TX_N_per_rpm2: 4.678e-8", "k_TX_N_per_rpm2: abc");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "rotor.k_TX_N_per_rpm2");
  EXPECT_EQ(p.line, lineOf(text, "k_TX_N_per_rpm2"));
  EXPECT_NE(p.message.find("'abc'"), std::string::npos) << p.message;
  EXPECT_NE(p.message.find("expected a number"), std::string::npos) << p.message;
}

TEST(VehicleFileErrors, NonNumericListEntryNamesItsIndex) {
  const std::string text =
      replaced(builtinText(), "[0.2367, 0.2865, 0.3202,", "[0.2367, 0.2865, abc,");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "drag.d_x_N_per_mps[2]");
  EXPECT_EQ(p.line, lineOf(text, "d_x_N_per_mps:"));
  EXPECT_NE(p.message.find("'abc'"), std::string::npos) << p.message;
}

TEST(VehicleFileErrors, MapWhereANumberIsExpected) {
  const std::string text = replaced(builtinText(), "mass_kg: 1.696 ", "mass_kg: {value: 1.696}");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  const auto* p = problemFor(*err, "mass_kg");
  ASSERT_NE(p, nullptr) << describe(*err);
  EXPECT_NE(p->message.find("expected a number, got a map"), std::string::npos) << p->message;
}

TEST(VehicleFileErrors, NanIsRejectedAsNotFinite) {
  const std::string text =
      replaced(builtinText(), "k_T_N_per_rpm2: 4.0083e-8", "k_T_N_per_rpm2: .nan");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "rotor.k_T_N_per_rpm2");
  EXPECT_EQ(p.line, lineOf(text, "k_T_N_per_rpm2"));
  EXPECT_NE(p.message.find("finite"), std::string::npos) << p.message;
}

TEST(VehicleFileErrors, InfinityIsRejectedAsNotFinite) {
  // Both signs: g3 may be negative, so −∞ would pass a mere "≤ hi" check.
  for (const char* inf : {".inf", "-.inf"}) {
    const std::string text =
        replaced(builtinText(), "g3_m: -3.365e-1", std::string("g3_m: ") + inf);
    const auto err = rejection(text);
    ASSERT_TRUE(err.has_value()) << inf;
    ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
    const auto& p = err->problems().front();
    EXPECT_EQ(p.key, "ground_effect.leveling_torque.g3_m") << inf;
    EXPECT_EQ(p.line, lineOf(text, "g3_m:")) << inf;
    EXPECT_NE(p.message.find("finite"), std::string::npos) << p.message;
  }
}

TEST(VehicleFileErrors, InfiniteListEntryNamesItsIndex) {
  const std::string text = replaced(builtinText(), "[0.2039, 0.2431,", "[.inf, 0.2431,");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  EXPECT_EQ(err->problems().front().key, "drag.d_y_N_per_mps[0]");
  EXPECT_EQ(err->problems().front().line, lineOf(text, "d_y_N_per_mps:"));
}

TEST(VehicleFileErrors, MalformedYamlGivesItsLine) {
  // A second ':' on a line is an "illegal map value", reported at that line.
  const std::string text = replaced(builtinText(), "mass_kg: 1.696", "mass_kg: 1.696: 2");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_NE(p.message.find("not valid YAML"), std::string::npos) << p.message;
  EXPECT_EQ(p.line, lineOf(text, "mass_kg:"));
  EXPECT_EQ(
      std::string(err->what()).rfind(std::string(kSource) + ":" + std::to_string(p.line) + ": ", 0),
      0u)
      << describe(*err);
}

TEST(VehicleFileErrors, UnclosedFlowListGivesALineAtOrAfterItsStart) {
  // The parser notices the missing ']' only on a following line.
  const std::string text = replaced(builtinText(), "0.3937, 0.3970]", "0.3937, 0.3970");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  EXPECT_NE(err->problems().front().message.find("not valid YAML"), std::string::npos);
  EXPECT_GE(err->problems().front().line, lineOf(text, "d_x_N_per_mps:")) << describe(*err);
}

TEST(VehicleFileErrors, BadIndentationGivesItsLine) {
  const std::string text = replaced(builtinText(), "  yy: 0.00792752", "    yy: 0.00792752");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  EXPECT_NE(err->problems().front().message.find("not valid YAML"), std::string::npos);
  EXPECT_EQ(err->problems().front().line, lineOf(text, "yy:"));
}

TEST(VehicleFileErrors, TopLevelListIsRejected) {
  const auto err = rejection("- mass_kg: 1.696\n- name: paper_quad\n");
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  EXPECT_EQ(err->problems().front().line, 1);
  EXPECT_NE(err->problems().front().message.find("expected a map"), std::string::npos);
}

TEST(VehicleFileErrors, EmptyDocumentIsRejected) {
  const auto err = rejection("# nothing but a comment\n");
  ASSERT_TRUE(err.has_value());
  EXPECT_NE(err->problems().front().message.find("expected a map"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Physical validation, each problem at the line of its key

TEST(VehicleFileErrors, NegativeMassNamesKeyLineAndRange) {
  const std::string text = replaced(builtinText(), "mass_kg: 1.696", "mass_kg: -1.696");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "mass_kg");
  EXPECT_EQ(p.line, lineOf(text, "mass_kg:"));
  EXPECT_NE(p.message.find("-1.696"), std::string::npos) << p.message;
  EXPECT_NE(p.message.find("(0, 1000] kg"), std::string::npos) << p.message;
  // what(): "FILE:LINE: key 'K': MESSAGE"
  EXPECT_EQ(std::string(err->what()),
            std::string(kSource) + ":" + std::to_string(p.line) + ": key 'mass_kg': " + p.message);
}

TEST(VehicleFileErrors, MismatchedDragTableLengths) {
  const std::string text = replaced(builtinText(), "0.3274, 0.3300]", "0.3274]");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "drag");
  // A problem of a whole section is reported at the section header.
  EXPECT_EQ(p.line, lineOf(text, "drag:"));  // the section header
  EXPECT_NE(p.message.find("d_y_N_per_mps: 6"), std::string::npos) << p.message;
  EXPECT_NE(p.message.find("heights_m: 7"), std::string::npos) << p.message;
}

TEST(VehicleFileErrors, EmptyDragTableIsRejected) {
  const std::string text =
      replaced(builtinText(), "[0.10,   0.15,   0.20,   0.30,   0.50,   1.00,   2.00]", "[]");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_NE(problemFor(*err, "drag.heights_m"), nullptr) << describe(*err);
}

TEST(VehicleFileErrors, NonIncreasingDragHeightsNameTheIndex) {
  const std::string text = replaced(builtinText(), "0.15,   0.20,   0.30", "0.15,   0.15,   0.30");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "drag.heights_m[2]");
  EXPECT_EQ(p.line, lineOf(text, "heights_m:"));  // the line of the list entry
  EXPECT_NE(p.message.find("strictly greater"), std::string::npos) << p.message;
}

TEST(VehicleFileErrors, DecreasingThrottleCurve) {
  // Slope at full throttle c1 + 2·c2 = 5.23e8 − 6.0e8 < 0: n² falls near t = 1.
  const std::string text = replaced(builtinText(), "c2_rpm2: -1.448471e8", "c2_rpm2: -3.0e8");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "throttle_curve");
  EXPECT_EQ(p.line, lineOf(text, "throttle_curve:"));  // the section header
  EXPECT_NE(p.message.find("strictly increasing"), std::string::npos) << p.message;
}

TEST(VehicleFileErrors, LevelingTorqueDenominatorThatVanishes) {
  // g3² = 0.113 ≥ 4·g4 = 0.08: h² + g3·h + g4 has a root at h > 0, where M_G is infinite.
  const std::string text = replaced(builtinText(), "g4_m2: 4.126e-2", "g4_m2: 2.0e-2");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "ground_effect.leveling_torque");
  EXPECT_EQ(p.line, lineOf(text, "leveling_torque:"));  // the section header
  EXPECT_NE(p.message.find("g4=0.02"), std::string::npos) << p.message;
}

// ---------------------------------------------------------------------------------------------
// Ground-effect curves given as tables

constexpr std::string_view kThrustFormula = "    g1_m2: 1.804e-2\n    g2_m2: 7.339e-3\n";
constexpr std::string_view kLevelingFormula =
    "    g3_m: -3.365e-1                # shape from the quadrotor platform (peak at 0.186 m)\n"
    "    g4_m2: 4.126e-2\n";

std::string withThrustTable(std::string_view table) {
  return replaced(builtinText(), kThrustFormula, table);
}

TEST(VehicleFileTables, TablesReplaceTheFormulas) {
  std::string text = withThrustTable(
      "    table:                       # F_G measured at three heights\n"
      "      heights_m: [0.08, 0.1, 0.2]\n"
      "      F_G: [0.30, 0.26, 0.12]\n");
  text = replaced(text, kLevelingFormula,
                  "    table:\n      heights_m: [0.1, 0.2, 0.3]\n      M_G_m: [0.015, 0.022, 0.008]\n");
  text = replaced(text, "    scale_m4: 2.1791e-5\n", "");
  const model::VehicleParams p = io::parseVehicleYaml(text, kSource);
  EXPECT_EQ(p.additional_thrust.table.heights_m, (std::vector<double>{0.08, 0.1, 0.2}));
  EXPECT_EQ(p.additional_thrust.table.values, (std::vector<double>{0.30, 0.26, 0.12}));
  EXPECT_EQ(p.leveling_torque.table.heights_m, (std::vector<double>{0.1, 0.2, 0.3}));
  EXPECT_EQ(p.leveling_torque.table.values, (std::vector<double>{0.015, 0.022, 0.008}));
  const model::GroundEffectModel ge(p);
  EXPECT_DOUBLE_EQ(ge.thrustRatio(0.1), 0.26);
  EXPECT_DOUBLE_EQ(ge.levelingCoefficient(0.2), 0.022);
  EXPECT_DOUBLE_EQ(ge.levelingPeakHeight(), 0.2);
}

TEST(VehicleFileTables, TableNextToTheFormulaIsRejectedAtTheFormulasKey) {
  const std::string text = replaced(
      builtinText(), kThrustFormula,
      std::string(kThrustFormula) + "    table: {heights_m: [0.08, 0.2], F_G: [0.3, 0.1]}\n");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 2u) << describe(*err);
  const auto* p = problemFor(*err, "ground_effect.additional_thrust.g1_m2");
  ASSERT_NE(p, nullptr) << describe(*err);
  EXPECT_EQ(p->line, lineOf(text, "g1_m2:"));
  EXPECT_NE(p->message.find("not both"), std::string::npos) << p->message;
  EXPECT_NE(problemFor(*err, "ground_effect.additional_thrust.g2_m2"), nullptr) << describe(*err);
}

TEST(VehicleFileTables, MisnamedValuesListIsMissingAndUnknown) {
  const std::string text =
      withThrustTable("    table:\n      heights_m: [0.08, 0.2]\n      F_G_m: [0.3, 0.1]\n");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  EXPECT_NE(problemFor(*err, "ground_effect.additional_thrust.table.F_G"), nullptr) << describe(*err);
  const auto* unknown = problemFor(*err, "ground_effect.additional_thrust.table.F_G_m");
  ASSERT_NE(unknown, nullptr) << describe(*err);
  EXPECT_EQ(unknown->line, lineOf(text, "F_G_m:"));
}

TEST(VehicleFileTables, BadTableEntryNamesItsIndexAndLine) {
  const std::string text = withThrustTable(
      "    table:\n      heights_m: [0.08, 0.2, 0.15]\n      F_G: [0.3, 0.1, -1.5]\n");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 2u) << describe(*err);
  const auto* h = problemFor(*err, "ground_effect.additional_thrust.table.heights_m[2]");
  ASSERT_NE(h, nullptr) << describe(*err);
  EXPECT_EQ(h->line, lineOf(text, "heights_m: [0.08"));
  EXPECT_NE(h->message.find("strictly greater"), std::string::npos) << h->message;
  const auto* f = problemFor(*err, "ground_effect.additional_thrust.table.F_G[2]");
  ASSERT_NE(f, nullptr) << describe(*err);
  EXPECT_EQ(f->line, lineOf(text, "F_G: ["));
}

TEST(VehicleFileErrors, OverlappingPropellers) {
  // Adjacent rotors are b/√2 = 0.247 m apart; two 0.15 m radii overlap.
  const std::string text =
      replaced(builtinText(), "propeller_radius_m: 0.089", "propeller_radius_m: 0.15");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "geometry.propeller_radius_m");
  EXPECT_EQ(p.line, lineOf(text, "propeller_radius_m:"));
  EXPECT_NE(p.message.find("overlap"), std::string::npos) << p.message;
}

TEST(VehicleFileErrors, InertiaViolatingTheTriangleInequality) {
  // Izz = 0.02 > Ixx + Iyy = 0.0154: no rigid body has these principal moments.
  const std::string text = replaced(builtinText(), "zz: 0.01249522", "zz: 0.02");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 1u) << describe(*err);
  const auto& p = err->problems().front();
  EXPECT_EQ(p.key, "inertia_kgm2.zz");
  EXPECT_EQ(p.line, lineOf(text, "zz:"));
  EXPECT_NE(p.message.find("sum of the other two"), std::string::npos) << p.message;
}

// ---------------------------------------------------------------------------------------------
// Several problems in one file: all reported, one line each

TEST(VehicleFileErrors, SeveralStructuralProblemsAreAllReported) {
  std::string text = builtinText();
  text = replaced(text, "  k_T_N_per_rpm2: 4.0083e-8\n", "");              // missing
  text = replaced(text, "mass_kg: 1.696", "mass_kg: 1.696\ncolour: red");  // unknown
  text = replaced(text, "g2_m2: 7.339e-3", "g2_m2: abc");                  // not a number
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  EXPECT_EQ(err->problems().size(), 3u) << describe(*err);
  EXPECT_NE(problemFor(*err, "rotor.k_T_N_per_rpm2"), nullptr) << describe(*err);
  EXPECT_NE(problemFor(*err, "colour"), nullptr) << describe(*err);
  EXPECT_NE(problemFor(*err, "ground_effect.additional_thrust.g2_m2"), nullptr) << describe(*err);
}

TEST(VehicleFileErrors, SeveralValidationProblemsAreAllReportedOneLineEach) {
  std::string text = builtinText();
  text = replaced(text, "mass_kg: 1.696", "mass_kg: -1.696");
  text = replaced(text, "propeller_radius_m: 0.089", "propeller_radius_m: 0.15");
  text = replaced(text, "J_R_kgm2: 1.0556e-4", "J_R_kgm2: .nan");
  const auto err = rejection(text);
  ASSERT_TRUE(err.has_value());
  ASSERT_EQ(err->problems().size(), 3u) << describe(*err);
  for (const char* key : {"mass_kg", "geometry.propeller_radius_m", "rotor.J_R_kgm2"}) {
    const auto* p = problemFor(*err, key);
    ASSERT_NE(p, nullptr) << key << "\n" << describe(*err);
    const std::string leaf = std::string(key).substr(std::string(key).rfind('.') + 1);
    EXPECT_EQ(p->line, lineOf(text, leaf + ":")) << key;
  }
  // what() has one line per problem, each "FILE:LINE: key 'K': MESSAGE".
  std::istringstream lines(err->what());
  std::size_t i = 0;
  for (std::string line; std::getline(lines, line); ++i) {
    ASSERT_LT(i, err->problems().size()) << describe(*err);
    const auto& p = err->problems()[i];
    EXPECT_EQ(line, std::string(kSource) + ":" + std::to_string(p.line) + ": key '" + p.key +
                        "': " + p.message);
  }
  EXPECT_EQ(i, err->problems().size());
}

// ---------------------------------------------------------------------------------------------
// Files on disk

class VehicleFileOnDisk : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) /
           ("geaware_vehicle_file_test_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const auto path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  std::filesystem::path dir_;
};

TEST_F(VehicleFileOnDisk, LoadsAValidFile) {
  const auto path = write("good.yaml", builtinText());
  expectSameVehicle(io::loadVehicleFile(path), io::builtinVehicle());
}

TEST_F(VehicleFileOnDisk, ErrorNamesThePathAndLine) {
  const std::string text = replaced(builtinText(), "mass_kg: 1.696", "mass_kg: -1.696");
  const auto path = write("negative_mass.yaml", text);
  try {
    (void)io::loadVehicleFile(path);
    FAIL() << "a negative mass was accepted";
  } catch (const io::ConfigError& e) {
    EXPECT_EQ(e.file(), path.string());
    const std::string prefix =
        path.string() + ":" + std::to_string(lineOf(text, "mass_kg:")) + ": key 'mass_kg': ";
    EXPECT_EQ(std::string(e.what()).rfind(prefix, 0), 0u) << e.what();
  }
}

TEST_F(VehicleFileOnDisk, NonexistentFileIsAnErrorNamingIt) {
  const auto path = dir_ / "does_not_exist.yaml";
  try {
    (void)io::loadVehicleFile(path);
    FAIL() << "loading a nonexistent file succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no such vehicle file"), std::string::npos) << e.what();
  }
}

TEST_F(VehicleFileOnDisk, DirectoryIsAnErrorNamingIt) {
  // A path that exists but cannot be read as a file (permission bits do not stop root, which
  // CI may run as; a directory is unreadable for everyone).
  try {
    (void)io::loadVehicleFile(dir_);
    FAIL() << "loading a directory succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(dir_.string()), std::string::npos) << e.what();
  }
}

}  // namespace
