// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One parameter that failed validation: what every layer's validate() returns (STYLE.md §3),
// what loaders turn into "file:line: key: …" and what model::describeErrors prints.

#include <string>

namespace geaware::model {

/// One field that failed validation. `field` is the key path as written in the parameter file
/// (e.g. "rotor.k_T_N_per_rpm2"), so loaders can point at the offending line.
struct FieldError {
  std::string field;     ///< key path, dot separated
  std::string value;     ///< the offending value, printed
  std::string expected;  ///< what a valid value looks like
};

}  // namespace geaware::model
