// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Parsing of "FROM:TO:STEP" ranges given on the command line (heights, tilts, speeds).

#include <string>
#include <string_view>
#include <vector>

namespace geaware::io {

struct Range {
  double from = 0.0;
  double to = 0.0;
  double step = 0.0;

  /// from, from + step, … up to and including `to` (within 1e-9·step of rounding); a single
  /// value when from == to.
  [[nodiscard]] std::vector<double> values() const;
};

/// Parses "FROM:TO:STEP" (or a single number "X", meaning X:X:1). Throws std::invalid_argument
/// naming `option` when the text is malformed, non-finite, the step is ≤ 0 or TO < FROM, or the
/// range would hold more than `max_values` values.
[[nodiscard]] Range parseRange(std::string_view text, const std::string& option,
                               std::size_t max_values = 1'000'000);

}  // namespace geaware::io
