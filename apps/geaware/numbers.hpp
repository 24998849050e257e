// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The one number parser of the command line: every numeric option is checked on its text,
// before CLI11 converts it, by one of these validators. The text must be a whole number
// (std::from_chars, an optional leading '+', nothing after it): NaN, ±∞, 1e999, "3x" and, for
// whole numbers, "-1" or anything above the type's range are usage errors naming the option
// (CLI11 prefixes the option's name), e.g. "--seed: '-1' is not a whole number in [0, 2^64 − 1]".

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

namespace geaware::cli {

/// The finite double `text` is, or nothing (NaN, ±∞, out of range, trailing text).
[[nodiscard]] std::optional<double> parseFinite(std::string_view text);
/// The unsigned 64-bit whole number `text` is (digits only), or nothing.
[[nodiscard]] std::optional<std::uint64_t> parseWhole(std::string_view text);

/// A finite number v with lo < v (lo_open) or lo <= v, and v <= hi.
[[nodiscard]] CLI::Validator finiteIn(double lo, double hi, bool lo_open = false);
/// A finite number > 0.
[[nodiscard]] CLI::Validator positive();
/// A finite number >= 0.
[[nodiscard]] CLI::Validator nonNegative();
/// A whole number in [lo, hi].
[[nodiscard]] CLI::Validator wholeIn(std::uint64_t lo, std::uint64_t hi);
/// A seed: a whole number in [0, 2^64 − 1].
[[nodiscard]] CLI::Validator seed();

}  // namespace geaware::cli
