// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Controller-parameters files (config/controller-params/*.yaml, docs/controller-params.md):
// strict YAML loading into the values of control::controllerSchema(). Every key is required,
// unknown keys are errors naming the nearest valid key, and every value is range-checked (NaN
// and ±inf refused) with each problem reported at its line. The values are applied to a
// configuration with control::applyParameters.

#include <filesystem>
#include <string>
#include <string_view>

#include "geaware/control/controller_params.hpp"
#include "geaware/io/config_error.hpp"

namespace geaware::io {

/// Reads and validates a controller-parameters file; throws ConfigError (file, line, key,
/// expectation), or std::runtime_error when the file cannot be read.
[[nodiscard]] control::ControllerParams loadControllerParamsFile(const std::filesystem::path& file);

/// `configuration` with the values of `file` (control::applyParameters): what `--controller-params
/// FILE` does to the configuration `--controller` chose.
[[nodiscard]] control::ControllerParams withControllerParamsFile(
    const control::ControllerParams& configuration, const std::filesystem::path& file);

/// Parses controller-parameters YAML text; `source` names it in error messages.
[[nodiscard]] control::ControllerParams parseControllerParamsYaml(std::string_view yaml_text,
                                                                  const std::string& source);

/// The YAML text of `values` (every key of the schema, each number in the shortest form that
/// reads back exactly, its unit as a comment): what config/controller-params/default.yaml is
/// for control::defaultParameterValues().
[[nodiscard]] std::string controllerParamsYaml(const control::ControllerParams& values);

}  // namespace geaware::io
