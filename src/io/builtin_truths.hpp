// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The built-in truth files (config/truths/*.yaml), embedded at build time by
// src/io/CMakeLists.txt into the generated builtin_truths.cpp. Private to geaware_truth_file.

#include <string_view>
#include <vector>

namespace geaware::io::detail {

struct BuiltinTruth {
  std::string_view name;  ///< as scenario files and --truth name it ("ideal")
  std::string_view path;  ///< the repository path ("config/truths/ideal.yaml")
  std::string_view yaml;  ///< the file's text
};
extern const std::vector<BuiltinTruth> kBuiltinTruths;

}  // namespace geaware::io::detail
