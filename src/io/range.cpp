// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/range.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace geaware::io {
namespace {

double parseNumber(std::string_view s, const std::string& option, std::string_view whole,
                   const char* part) {
  double v = 0.0;
  const char* end = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(s.data(), end, v);
  if (s.empty() || ec != std::errc() || ptr != end || !std::isfinite(v)) {
    throw std::invalid_argument(option + " '" + std::string(whole) + "': " + part + " '" +
                                std::string(s) + "' is not a finite number (expected FROM:TO:STEP)");
  }
  return v;
}

}  // namespace

std::vector<double> Range::values() const {
  std::vector<double> out;
  if (from == to) return {from};
  const auto n = static_cast<std::size_t>(std::floor((to - from) / step + 1e-9)) + 1;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) out.push_back(from + static_cast<double>(i) * step);
  return out;
}

Range parseRange(std::string_view text, const std::string& option, std::size_t max_values) {
  Range r;
  const auto c1 = text.find(':');
  if (c1 == std::string_view::npos) {
    r.from = r.to = parseNumber(text, option, text, "value");
    r.step = 1.0;
    return r;
  }
  const auto c2 = text.find(':', c1 + 1);
  if (c2 == std::string_view::npos || text.find(':', c2 + 1) != std::string_view::npos) {
    throw std::invalid_argument(option + " '" + std::string(text) +
                                "': expected FROM:TO:STEP (three numbers separated by ':')");
  }
  r.from = parseNumber(text.substr(0, c1), option, text, "FROM");
  r.to = parseNumber(text.substr(c1 + 1, c2 - c1 - 1), option, text, "TO");
  r.step = parseNumber(text.substr(c2 + 1), option, text, "STEP");
  if (r.step <= 0.0) {
    throw std::invalid_argument(option + " '" + std::string(text) + "': STEP must be > 0");
  }
  if (r.to < r.from) {
    throw std::invalid_argument(option + " '" + std::string(text) + "': TO must be ≥ FROM");
  }
  if ((r.to - r.from) / r.step + 1.0 > static_cast<double>(max_values)) {
    throw std::invalid_argument(option + " '" + std::string(text) + "': more than " +
                                std::to_string(max_values) + " values; use a larger STEP");
  }
  return r;
}

}  // namespace geaware::io
