// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The parameter checks every layer's validate() is written with (STYLE.md §3: validation that
// says what is wrong). Each failed check appends one FieldError naming the key path, the
// offending value and what a valid value looks like; nothing throws, so one validate() call
// reports every bad field, in the order the checks ran.
//
// The `expected` texts are part of the interface: loaders, the CLI and tests quote them. Every
// one is listed with its check below. A unit, where given, follows after one space; an empty
// unit adds nothing.

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "geaware/model/field_error.hpp"

namespace geaware::model {

/// Significant digits of formatValue() unless told otherwise ("%.9g"): enough to tell apart any
/// two values a parameter file would write differently, short for round ones.
inline constexpr int kValueDigits = 9;

/// `v` as printf's "%.<significant_digits>g": 0.25, 1e-06, 1000, nan, inf, -inf.
[[nodiscard]] std::string formatValue(double v, int significant_digits = kValueDigits);

/// "<heading>" then one line per error, "\n  <field> = <value>: expected <expected>": the text of
/// the exceptions that carry a FieldError list (InvalidParameters and its kin).
[[nodiscard]] std::string describeErrors(std::string_view heading,
                                         const std::vector<FieldError>& errors);

/// Whether FieldChecker::range() admits its lower bound: [lo, hi] or (lo, hi]. The upper bound
/// is always admitted.
enum class LowerBound : bool { kExclusive = false, kInclusive = true };

/// Append-only collector of FieldErrors, bound to the caller's list. Every check returns whether
/// the value passed, so that a cross-field check can run only on fields that are valid alone.
/// NaN fails every numeric check.
class FieldChecker {
 public:
  /// Values are printed with `significant_digits` digits (formatValue()).
  explicit FieldChecker(std::vector<FieldError>& out, int significant_digits = kValueDigits)
      : out_(out), digits_(significant_digits) {}

  /// Finite, lo ≤ v (or lo < v when `lower` is kExclusive) and v ≤ hi.
  /// Expected: "a finite number in [lo, hi] unit" or "a finite number in (lo, hi] unit".
  bool range(std::string_view field, double v, double lo, double hi, LowerBound lower,
             std::string_view unit = {});

  /// Finite and > 0. Expected: "a finite number > 0 unit".
  bool positive(std::string_view field, double v, std::string_view unit = {});

  /// Finite and ≥ 0. Expected: "a finite number ≥ 0 unit".
  bool nonNegative(std::string_view field, double v, std::string_view unit = {});

  /// Every component finite and ≥ 0. Value "(x, y, z)"; expected: "three finite numbers ≥ 0 unit".
  bool nonNegative(std::string_view field, const Eigen::Vector3d& v, std::string_view unit = {});

  /// Finite. Expected: "a finite number unit".
  bool finite(std::string_view field, double v, std::string_view unit = {});

  /// Every component finite. Value "(x, y, z)"; expected: "three finite numbers unit".
  bool finite(std::string_view field, const Eigen::Vector3d& v, std::string_view unit = {});

  /// Every component finite with |v_k| ≤ bound, checked and reported one axis at a time as
  /// range("<field>.x" …, −bound, bound, kInclusive, unit), then .y and .z.
  bool componentsWithin(std::string_view field, const Eigen::Vector3d& v, double bound,
                        std::string_view unit = {});

  /// lo ≤ v ≤ hi. Expected: "an integer in [lo, hi]".
  bool integerRange(std::string_view field, long long v, long long lo, long long hi);

  /// v ≥ lo. Expected: "an integer ≥ lo".
  bool integerAtLeast(std::string_view field, long long v, long long lo);

  /// Appends one error as given: for checks that span fields or need their own wording.
  void fail(std::string_view field, std::string value, std::string expected);

  /// formatValue(v) with this checker's digits, for the value and expected texts of fail().
  [[nodiscard]] std::string format(double v) const { return formatValue(v, digits_); }

 private:
  /// Appends {field, value, expected + " " + unit (when unit is not empty)}; returns false.
  bool reject(std::string_view field, std::string value, std::string expected,
              std::string_view unit);
  [[nodiscard]] std::string formatVector(const Eigen::Vector3d& v) const;

  std::vector<FieldError>& out_;
  int digits_;
};

}  // namespace geaware::model
