// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/input_file.hpp"
#include "geaware/io/vehicle_file.hpp"

#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "geaware/io/format_version.hpp"
#include "geaware/io/param_reader.hpp"
#include "geaware/io/yaml_reader.hpp"
#include "geaware/model/vehicle_schema.hpp"

namespace geaware::io {
namespace detail {
extern const std::string_view kBuiltinVehicleYaml;
}  // namespace detail

model::VehicleParams parseVehicleYaml(std::string_view yaml_text, const std::string& source) {
  YAML::Node doc;
  try {
    doc = YAML::Load(std::string(yaml_text));
  } catch (const YAML::ParserException& e) {
    throw ConfigError(source, {{e.mark.line + 1, "", "not valid YAML: " + e.msg}});
  }
  if (!doc.IsMap()) {
    throw ConfigError(source, {{1, "", "expected a map of vehicle parameters at the top level"}});
  }
  YamlContext ctx;
  MapReader root(doc, "", ctx);
  (void)readFormatVersion(root, ctx, source);
  model::VehicleParams params;
  readParameters(root, model::vehicleSchema(), params);
  root.rejectUnknownKeys();
  if (!ctx.problems.empty()) throw ConfigError(source, std::move(ctx.problems));

  // Physical validation, each problem reported at the line of its key.
  for (const auto& e : params.validate()) {
    ctx.problem(ctx.lineOf(e.field), e.field, "got " + e.value + ", expected " + e.expected);
  }
  if (!ctx.problems.empty()) throw ConfigError(source, std::move(ctx.problems));
  return params;
}

model::VehicleParams loadVehicleFile(const std::filesystem::path& file) {
  return parseVehicleYaml(readInputFile(file, "vehicle file", "vehicle YAML file"), file.string());
}

std::string_view builtinVehicleYaml() noexcept { return detail::kBuiltinVehicleYaml; }

model::VehicleParams builtinVehicle() {
  return parseVehicleYaml(detail::kBuiltinVehicleYaml, "<built-in paper_quad>");
}

}  // namespace geaware::io
