// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Flight scenario files (YAML): the vehicle the controller believes in, the world it flies in
// (a truth file, docs/truth-file.md), the trajectory, the controller configuration, the terrain
// and this flight's disturbances, loaded strictly — every key of the chosen types is required
// (`truth` and `disturbances` are optional), unknown keys are errors, each problem names the
// file, line and key. Format and examples: docs/scenario-file.md, config/scenarios/.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "geaware/experiments/flight.hpp"
#include "geaware/io/config_error.hpp"
#include "geaware/sim/world.hpp"

namespace geaware::experiments {

/// Reads a scenario file; relative paths inside it (vehicle, truth, height map) are resolved
/// against the file's folder. `truth_override` (`fly --truth`), when given, replaces the file's
/// `truth`; `max_sim_s_override` (`fly --max-sim-s`), when given, replaces the file's max_sim_s.
/// Throws io::ConfigError (file, line, key, expectation), or std::runtime_error when a file
/// cannot be read.
[[nodiscard]] FlightScenario loadScenarioFile(const std::filesystem::path& file,
                                              const sim::World* truth_override = nullptr,
                                              std::optional<double> max_sim_s_override = {});

/// Parses scenario YAML; `source` names it in errors, `base_dir` resolves relative paths.
[[nodiscard]] FlightScenario parseScenarioYaml(std::string_view yaml_text, const std::string& source,
                                               const std::filesystem::path& base_dir,
                                               const sim::World* truth_override = nullptr,
                                               std::optional<double> max_sim_s_override = {});

}  // namespace geaware::experiments
