// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Internal to identify*.cpp: the pieces every kind of identification result is built from
// (plot curves, the parameter and residual tables).

#include <algorithm>
#include <cstddef>
#include <functional>
#include <string>

#include "geaware/ident/identify.hpp"

namespace geaware::ident::detail {

inline CurveData curveData(std::string name, std::string mode, std::string dash = "") {
  CurveData c;
  c.name = std::move(name);
  c.mode = std::move(mode);
  c.dash = std::move(dash);
  return c;
}

/// `f` sampled at 401 heights over [from, to] m, as a line.
CurveData sampledCurve(std::string name, const std::function<double(double)>& f, double from,
                       double to, std::string dash = "");

/// Every k-th index so that at most `max_points` are plotted.
inline std::size_t plotStride(std::size_t n, std::size_t max_points = 4000) {
  return std::max<std::size_t>(1, n / max_points);
}

/// The "Parameters" and "Residuals" report tables of `r`, appended to r.report_tables.
void addStatsTables(IdentifyResult& r);

/// Appends `from` to `to`.
void appendWarnings(std::vector<std::string>& to, const std::vector<std::string>& from);

}  // namespace geaware::ident::detail
