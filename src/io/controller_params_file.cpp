// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/controller_params_file.hpp"

#include <vector>

#include <yaml-cpp/yaml.h>

#include "geaware/control/controller_schema.hpp"
#include "geaware/io/format_version.hpp"
#include "geaware/io/input_file.hpp"
#include "geaware/io/param_reader.hpp"
#include "geaware/io/yaml_reader.hpp"
#include "geaware/model/field_check.hpp"
#include "vehicle_text.hpp"

namespace geaware::io {

control::ControllerParams parseControllerParamsYaml(std::string_view yaml_text,
                                                    const std::string& source) {
  YAML::Node doc;
  try {
    doc = YAML::Load(std::string(yaml_text));
  } catch (const YAML::ParserException& e) {
    throw ConfigError(source, {{e.mark.line + 1, "", "not valid YAML: " + e.msg}});
  }
  if (!doc.IsMap()) {
    throw ConfigError(source, {{1, "", "expected a map of controller parameters at the top level"}});
  }
  YamlContext ctx;
  MapReader root(doc, "", ctx);
  (void)readFormatVersion(root, ctx, source);
  control::ControllerParams values = control::defaultParameterValues();
  readParameters(root, control::controllerSchema(), values);
  root.rejectUnknownKeys();
  if (!ctx.problems.empty()) throw ConfigError(source, std::move(ctx.problems));

  // Ranges (NaN and ±inf refused) and the checks across keys, each at its key's line.
  std::vector<model::FieldError> errors;
  model::FieldChecker c(errors);
  control::controllerSchema().validate(values, c, errors);
  for (const auto& e : errors) {
    ctx.problem(ctx.lineOf(e.field), e.field, "got " + e.value + ", expected " + e.expected);
  }
  if (!ctx.problems.empty()) throw ConfigError(source, std::move(ctx.problems));
  return values;
}

control::ControllerParams loadControllerParamsFile(const std::filesystem::path& file) {
  return parseControllerParamsYaml(
      readInputFile(file, "controller-parameters file", "controller-parameters YAML file"),
      file.string());
}

control::ControllerParams withControllerParamsFile(const control::ControllerParams& configuration,
                                                   const std::filesystem::path& file) {
  return control::applyParameters(configuration, loadControllerParamsFile(file));
}

std::string controllerParamsYaml(const control::ControllerParams& values) {
  std::string out =
      "# geaware controller parameters (docs/controller-params.md). Every key is required.\n"
      "format_version: 1\n";
  std::vector<std::string> open;  // the sections of the previous key
  for (const auto& s : control::controllerSchema().specs()) {
    std::vector<std::string> parts = detail::splitPath(std::string(s.key));
    const std::string leaf = parts.back();
    parts.pop_back();
    std::size_t common = 0;
    while (common < open.size() && common < parts.size() && open[common] == parts[common]) ++common;
    for (std::size_t i = common; i < parts.size(); ++i) {
      out += std::string(2 * i, ' ') + parts[i] + ":\n";
    }
    open = parts;
    out += std::string(2 * parts.size(), ' ') + leaf + ": " + detail::formatNumber(s.numberOf(values));
    out += s.unit.empty() ? "\n" : "  # " + std::string(s.unit) + "\n";
  }
  return out;
}

}  // namespace geaware::io
