// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The built-in log maps (config/log-maps/*.yaml), embedded at build time by src/io/CMakeLists.txt
// into the generated builtin_log_maps.cpp. Private to io.

#include <string_view>
#include <vector>

namespace geaware::io::detail {

struct BuiltinLogMap {
  std::string_view name;  ///< as --map names it ("px4")
  std::string_view path;  ///< the repository path ("config/log-maps/px4.yaml")
  std::string_view yaml;  ///< the file's text
};
extern const std::vector<BuiltinLogMap> kBuiltinLogMaps;

}  // namespace geaware::io::detail
