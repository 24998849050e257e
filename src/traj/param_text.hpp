// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Private to traj/: how the trajectory parameters' validate() words a bad value, and the range
// tests they share.

#include <cmath>
#include <sstream>
#include <string>

namespace geaware::traj::detail {

/// "field = value (expected …)", the value with 10 significant digits.
template <typename T>
std::string describe(const char* field, const T& value, const char* expected) {
  std::ostringstream os;
  os.precision(10);
  os << field << " = " << value << " (expected " << expected << ")";
  return os.str();
}

inline bool positive(double x) { return std::isfinite(x) && x > 0.0; }
inline bool nonNegative(double x) { return std::isfinite(x) && x >= 0.0; }

}  // namespace geaware::traj::detail
