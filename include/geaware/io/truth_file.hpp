// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Truth files (config/truths/*.yaml, docs/truth-file.md): the simulated world as a file. A truth
// file is a vehicle file (the vehicle-file schema, read by the vehicle reader; any vehicle file
// is a valid truth file, whose world is then its ideal world, sim::idealWorld) plus an optional
// `truth:` section for what only the world has: per-motor spread, CoG offset, the motors, the
// battery, the truth aerodynamics, the sensors, the disturbances, the per-flight variation and
// the team's scale. Every key of the section is optional (absent: today's value), unknown keys
// are errors, every problem names the file, the line and the key.
//
// This header sees sim/: it is its own library (geaware_truth_file), linked by experiments,
// the campaign and the command line only. No controller-side or identification target can
// include or link it (tests/wall).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "geaware/io/config_error.hpp"
#include "geaware/sim/world.hpp"

namespace geaware::io {

/// What a key of the `truth:` section holds.
enum class TruthValueKind : std::uint8_t {
  kNumber,   ///< one number
  kInteger,  ///< one whole number
  kBoolean,  ///< true or false
  kVector,   ///< a list of `cols` numbers
  kRows,     ///< a list of `rows` lists of `cols` numbers
};

/// One key of the `truth:` section: its path below `truth`, unit, valid range, meaning and
/// where it goes in sim::World. A value in the file times `to_si` is what the world holds
/// (degrees in the file, radians in the world).
struct TruthKey {
  std::string_view key;   ///< below `truth:`, dot separated: "sensors.imu.rate_Hz"
  std::string_view unit;  ///< as written in the docs; empty: dimensionless
  TruthValueKind kind = TruthValueKind::kNumber;
  std::size_t rows = 1;   ///< kRows: the number of rows
  std::size_t cols = 1;   ///< kVector, kRows: numbers per (row)
  double lo = 0.0;        ///< valid values: lo ≤ v (lo < v when lo_exclusive) and v ≤ hi
  double hi = 0.0;
  bool lo_exclusive = false;
  double to_si = 1.0;
  std::string_view meaning;  ///< one line for the docs
  /// Number i (row-major for kRows) of kNumber/kVector/kRows, in the world's unit.
  double& (*number)(sim::World&, std::size_t) = nullptr;
  long (*get_integer)(const sim::World&) = nullptr;      ///< kInteger
  void (*set_integer)(sim::World&, long) = nullptr;      ///< kInteger
  bool& (*flag)(sim::World&) = nullptr;                  ///< kBoolean

  /// The number of numbers (1 for a number, cols for a vector, rows·cols for rows).
  [[nodiscard]] std::size_t count() const noexcept {
    return kind == TruthValueKind::kRows ? rows * cols : kind == TruthValueKind::kVector ? cols : 1;
  }
  /// What a valid value is, as the docs' key list writes it: "(0, 10]", "[0, 1], 4 numbers",
  /// "true/false", "whole number in [1, 16]".
  [[nodiscard]] std::string validText() const;
};

/// Every key of the `truth:` section, in file order (the table docs/truth-file.md lists and a
/// test checks).
[[nodiscard]] const std::vector<TruthKey>& truthFileKeys();

/// Reads a truth file; throws ConfigError (file, line, key, expectation), or std::runtime_error
/// when the file cannot be read. The world's source is the file's path.
[[nodiscard]] sim::World loadTruthFile(const std::filesystem::path& file);

/// Parses truth-file YAML text; `source` names it in errors and becomes the world's source.
[[nodiscard]] sim::World parseTruthYaml(std::string_view yaml_text, const std::string& source);

/// The `truth:` section of `world` with every key, two-space indented under `truth:`, numbers
/// written so that they read back exactly (the writer of docs/truth-file.md).
[[nodiscard]] std::string truthSectionYaml(const sim::World& world);

/// The names of the built-in truth files ("ideal", …), each config/truths/<file> embedded at
/// build time.
[[nodiscard]] std::vector<std::string> builtinTruthNames();
/// The built-in world `name` (one of builtinTruthNames()); std::invalid_argument otherwise.
[[nodiscard]] sim::World builtinTruth(std::string_view name);
/// The repository path of the built-in truth file `name` ("config/truths/ideal.yaml").
[[nodiscard]] std::string builtinTruthPath(std::string_view name);

/// A world from a truth reference as scenario files and `--truth` give it: a built-in name
/// ("ideal", …) or a truth file, relative paths resolved against `base_dir`.
[[nodiscard]] sim::World resolveTruth(const std::string& reference,
                                      const std::filesystem::path& base_dir);

}  // namespace geaware::io
