// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The `format_version` key every input file may carry (vehicle, scenario, height-map, weights
// and config files). A file without it is read as version 1, today's format; a version this
// geaware does not read is an error naming the file, the key and the versions it reads, before
// anything else of the file is read (its keys may mean something else in another version).

#include <string>
#include <vector>

#include "geaware/io/yaml_reader.hpp"

namespace geaware::io {

/// The key, at the top level of a file.
inline constexpr const char* kFormatVersionKey = "format_version";

/// The versions this geaware reads, for every file kind so far.
inline const std::vector<int> kFormatVersions = {1};

/// The file's format version: `format_version` of `root`, 1 when absent. Throws ConfigError
/// naming `file`, the key's line and the supported versions when the value is not a whole
/// number or not one of `supported` (the problems `ctx` already holds are reported with it).
[[nodiscard]] int readFormatVersion(MapReader& root, YamlContext& ctx, const std::string& file,
                                    const std::vector<int>& supported = kFormatVersions);

/// "1" or "1, 2 and 3".
[[nodiscard]] std::string describeVersions(const std::vector<int>& versions);

}  // namespace geaware::io
