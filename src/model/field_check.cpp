// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/model/field_check.hpp"

#include <cmath>
#include <cstdio>
#include <utility>

namespace geaware::model {

std::string formatValue(double v, int significant_digits) {
  // "%.*g" is at most sign, 1 + (digits − 1) mantissa digits, point, "e-308": 32 bytes hold any
  // digits up to 17, the most a double carries.
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", significant_digits, v);
  return buf;
}

std::string describeErrors(std::string_view heading, const std::vector<FieldError>& errors) {
  std::string s(heading);
  for (const auto& e : errors) s += "\n  " + e.field + " = " + e.value + ": expected " + e.expected;
  return s;
}

bool FieldChecker::reject(std::string_view field, std::string value, std::string expected,
                          std::string_view unit) {
  if (!unit.empty()) {
    expected += ' ';
    expected += unit;
  }
  out_.push_back({std::string(field), std::move(value), std::move(expected)});
  return false;
}

std::string FieldChecker::formatVector(const Eigen::Vector3d& v) const {
  return "(" + format(v.x()) + ", " + format(v.y()) + ", " + format(v.z()) + ")";
}

bool FieldChecker::range(std::string_view field, double v, double lo, double hi, LowerBound lower,
                         std::string_view unit) {
  const bool inclusive = lower == LowerBound::kInclusive;
  const bool ok = std::isfinite(v) && (inclusive ? v >= lo : v > lo) && v <= hi;
  return ok || reject(field, format(v),
                      std::string("a finite number in ") + (inclusive ? "[" : "(") + format(lo) +
                          ", " + format(hi) + "]",
                      unit);
}

bool FieldChecker::positive(std::string_view field, double v, std::string_view unit) {
  const bool ok = std::isfinite(v) && v > 0.0;
  return ok || reject(field, format(v), "a finite number > 0", unit);
}

bool FieldChecker::nonNegative(std::string_view field, double v, std::string_view unit) {
  const bool ok = std::isfinite(v) && v >= 0.0;
  return ok || reject(field, format(v), "a finite number ≥ 0", unit);
}

bool FieldChecker::nonNegative(std::string_view field, const Eigen::Vector3d& v,
                               std::string_view unit) {
  const bool ok = v.allFinite() && (v.array() >= 0.0).all();
  return ok || reject(field, formatVector(v), "three finite numbers ≥ 0", unit);
}

bool FieldChecker::finite(std::string_view field, double v, std::string_view unit) {
  return std::isfinite(v) || reject(field, format(v), "a finite number", unit);
}

bool FieldChecker::finite(std::string_view field, const Eigen::Vector3d& v, std::string_view unit) {
  return v.allFinite() || reject(field, formatVector(v), "three finite numbers", unit);
}

bool FieldChecker::componentsWithin(std::string_view field, const Eigen::Vector3d& v, double bound,
                                    std::string_view unit) {
  bool ok = true;
  const char* const axis[3] = {".x", ".y", ".z"};
  for (int k = 0; k < 3; ++k) {
    ok &= range(std::string(field) + axis[k], v[k], -bound, bound, LowerBound::kInclusive, unit);
  }
  return ok;
}

bool FieldChecker::integerRange(std::string_view field, long long v, long long lo, long long hi) {
  const bool ok = v >= lo && v <= hi;
  return ok || reject(field, std::to_string(v),
                      "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", {});
}

bool FieldChecker::integerAtLeast(std::string_view field, long long v, long long lo) {
  return v >= lo || reject(field, std::to_string(v), "an integer ≥ " + std::to_string(lo), {});
}

void FieldChecker::fail(std::string_view field, std::string value, std::string expected) {
  reject(field, std::move(value), std::move(expected), {});
}

}  // namespace geaware::model
