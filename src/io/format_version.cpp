// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/format_version.hpp"

#include <algorithm>
#include <cmath>

#include "geaware/model/field_check.hpp"

namespace geaware::io {

std::string describeVersions(const std::vector<int>& versions) {
  std::string s;
  for (std::size_t i = 0; i < versions.size(); ++i) {
    s += (i == 0 ? "" : i + 1 == versions.size() ? " and " : ", ") + std::to_string(versions[i]);
  }
  return s;
}

int readFormatVersion(MapReader& root, YamlContext& ctx, const std::string& file,
                      const std::vector<int>& supported) {
  if (!root.has(kFormatVersionKey)) return 1;
  const std::size_t before = ctx.problems.size();
  const double v = root.number(kFormatVersionKey);
  const bool known = ctx.problems.size() == before && v == std::floor(v) &&
                     std::find(supported.begin(), supported.end(), v) != supported.end();
  if (known) return static_cast<int>(v);
  if (ctx.problems.size() == before) {
    root.problem(kFormatVersionKey,
                 "version " + model::formatValue(v) + " is not one this geaware reads (supported: " +
                     describeVersions(supported) + ")");
  } else {
    ctx.problems.back().message += " (supported format versions: " + describeVersions(supported) + ")";
  }
  throw ConfigError(file, std::move(ctx.problems));
}

}  // namespace geaware::io
