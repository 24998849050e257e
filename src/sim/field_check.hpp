#pragma once
// Parameter checks shared by the sensors' and disturbances' validate() (private to src/sim/):
// each failed check appends a model::FieldError naming the key path, the value and what a
// valid value looks like.

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geaware/model/vehicle_params.hpp"

namespace geaware::sim::detail {

inline std::string show(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

class FieldCheck {
 public:
  explicit FieldCheck(std::vector<model::FieldError>& out) : out_(out) {}

  /// Finite and lo < v ≤ hi (lo ≤ v when lo_inclusive).
  void range(const char* field, double v, double lo, double hi, bool lo_inclusive, const char* unit) {
    const bool ok = std::isfinite(v) && (lo_inclusive ? v >= lo : v > lo) && v <= hi;
    if (!ok) {
      out_.push_back({field, show(v),
                      std::string("a finite number in ") + (lo_inclusive ? "[" : "(") + show(lo) + ", " + show(hi) +
                          "] " + unit});
    }
  }
  /// Finite and ≥ 0.
  void nonNegative(const char* field, double v, const char* unit) {
    if (!(std::isfinite(v) && v >= 0.0)) out_.push_back({field, show(v), std::string("a finite number ≥ 0 ") + unit});
  }
  /// Every component finite and ≥ 0.
  void nonNegative(const char* field, const Eigen::Vector3d& v, const char* unit) {
    if (!(v.allFinite() && (v.array() >= 0.0).all())) {
      out_.push_back({field, "(" + show(v.x()) + ", " + show(v.y()) + ", " + show(v.z()) + ")",
                      std::string("three finite numbers ≥ 0 ") + unit});
    }
  }
  /// Every component finite.
  void finite(const char* field, const Eigen::Vector3d& v, const char* unit) {
    if (!v.allFinite()) {
      out_.push_back({field, "(" + show(v.x()) + ", " + show(v.y()) + ", " + show(v.z()) + ")",
                      std::string("three finite numbers ") + unit});
    }
  }
  void fail(const char* field, const std::string& value, const std::string& expected) {
    out_.push_back({field, value, expected});
  }

 private:
  std::vector<model::FieldError>& out_;
};

}  // namespace geaware::sim::detail
