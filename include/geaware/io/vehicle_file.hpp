// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Vehicle files (config/vehicles/*.yaml): strict YAML loading into model::VehicleParams.
// Every key is required, unknown keys are errors, and the parameters are validated
// (VehicleParams::validate) with each problem reported at its line. Format: docs/vehicle-file.md.

#include <filesystem>
#include <string>
#include <string_view>

#include "geaware/io/config_error.hpp"
#include "geaware/model/vehicle_params.hpp"

namespace geaware::io {

/// Reads and validates a vehicle file; throws ConfigError (file, line, key, expectation), or
/// std::runtime_error when the file cannot be read.
[[nodiscard]] model::VehicleParams loadVehicleFile(const std::filesystem::path& file);

/// Parses vehicle YAML text; `source` names it in error messages.
[[nodiscard]] model::VehicleParams parseVehicleYaml(std::string_view yaml_text,
                                                    const std::string& source);

/// The YAML text of the built-in default vehicle (the paper's quadrotor,
/// config/vehicles/paper_quad.yaml embedded at build time).
[[nodiscard]] std::string_view builtinVehicleYaml() noexcept;

/// The built-in default vehicle, parsed and validated.
[[nodiscard]] model::VehicleParams builtinVehicle();

}  // namespace geaware::io
