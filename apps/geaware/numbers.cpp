// SPDX-License-Identifier: BSD-3-Clause
#include "numbers.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <system_error>

namespace geaware::cli {
namespace {

std::string_view withoutPlus(std::string_view text) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  return text;
}

/// The text echoed in a message: at most 40 characters.
std::string shown(std::string_view text) {
  return "'" + std::string(text.substr(0, 40)) + (text.size() > 40 ? "…" : "") + "'";
}

}  // namespace

std::optional<double> parseFinite(std::string_view text) {
  const std::string_view t = withoutPlus(text);
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (t.empty() || ec != std::errc() || ptr != t.data() + t.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<std::uint64_t> parseWhole(std::string_view text) {
  const std::string_view t = withoutPlus(text);
  std::uint64_t v = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (t.empty() || ec != std::errc() || ptr != t.data() + t.size()) return std::nullopt;
  return v;
}

/// A finite number in [lo, hi] ((lo, hi] when lo_open), described as `expected` in messages.
CLI::Validator checkedNumber(double lo, double hi, bool lo_open, const std::string& expected) {
  return CLI::Validator(
      [lo, hi, lo_open, expected](std::string& text) -> std::string {
        const auto v = parseFinite(text);
        if (!v) return shown(text) + " is not a finite number (expected " + expected + ")";
        if ((lo_open ? !(*v > lo) : !(*v >= lo)) || !(*v <= hi)) return shown(text) + ": expected " + expected;
        return {};
      },
      expected);
}

CLI::Validator finiteIn(double lo, double hi, bool lo_open) {
  return checkedNumber(lo, hi, lo_open, fmt::format("a number in {}{}, {}]", lo_open ? "(" : "[", lo, hi));
}

CLI::Validator positive() {
  return checkedNumber(0.0, std::numeric_limits<double>::max(), true, "a number > 0");
}

CLI::Validator nonNegative() {
  return checkedNumber(0.0, std::numeric_limits<double>::max(), false, "a number >= 0");
}

CLI::Validator wholeIn(std::uint64_t lo, std::uint64_t hi) {
  const std::string range = fmt::format("[{}, {}]", lo, hi);
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        const auto v = parseWhole(text);
        if (!v || *v < lo || *v > hi) return shown(text) + " is not a whole number in " + range;
        return {};
      },
      "INT in " + range);
}

CLI::Validator seed() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (parseWhole(text)) return {};
        return shown(text) + " is not a seed (expected a whole number in [0, 2^64 - 1])";
      },
      "SEED");
}

}  // namespace geaware::cli
