#pragma once
// Flight scenario files (YAML): the vehicle, the trajectory, the controller configuration, the
// terrain, the disturbances and the truth's mismatch of one flight, loaded strictly — every key
// of the chosen types is required, unknown keys are errors, each problem names the file, line
// and key. Format and examples: docs/scenario-file.md, config/scenarios/.

#include <filesystem>
#include <string>
#include <string_view>

#include "geaware/experiments/flight.hpp"
#include "geaware/io/config_error.hpp"

namespace geaware::experiments {

/// Reads a scenario file; relative paths inside it (vehicle, height map) are resolved against
/// the file's folder. Throws io::ConfigError (file, line, key, expectation), or
/// std::runtime_error when a file cannot be read.
[[nodiscard]] FlightScenario loadScenarioFile(const std::filesystem::path& file);

/// Parses scenario YAML; `source` names it in errors, `base_dir` resolves relative paths.
[[nodiscard]] FlightScenario parseScenarioYaml(std::string_view yaml_text, const std::string& source,
                                               const std::filesystem::path& base_dir);

}  // namespace geaware::experiments
