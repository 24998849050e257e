// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Helpers shared by the fits of ident/ (private to the layer).

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <sstream>
#include <utility>
#include <string>
#include <vector>

#include "geaware/ident/least_squares.hpp"
#include "geaware/ident/platform_fit.hpp"
#include "geaware/ident/table_fit.hpp"

namespace geaware::ident::detail {

/// A value printed with 4 significant digits, for messages.
inline std::string num(double v) {
  std::ostringstream os;
  os.precision(4);
  os << v;
  return os.str();
}

/// Adds a warning when a parameter's standard error exceeds `max_relative` of its value: the
/// data do not constrain it (too little excitation or too narrow a height range).
inline void warnIfImprecise(std::vector<std::string>& warnings, const std::string& name,
                            const Estimate& e, const std::string& hint,
                            double max_relative = 0.25) {
  if (!(std::abs(e.std_error) <= max_relative * std::abs(e.value))) {
    warnings.push_back(name + " = " + num(e.value) + " ± " + num(e.std_error) +
                       " is poorly constrained by the data" + (hint.empty() ? "" : " (" + hint + ")"));
  }
}

/// Adds a warning when the fit dropped more than `max_fraction` of its samples as outliers.
inline void warnIfManyOutliers(std::vector<std::string>& warnings, const std::string& what,
                               const FitStats& s, double max_fraction = 0.1) {
  const double total = static_cast<double>(s.count + s.outliers);
  if (total > 0.0 && static_cast<double>(s.outliers) > max_fraction * total) {
    warnings.push_back(what + ": " + std::to_string(s.outliers) + " of " +
                       std::to_string(s.count + s.outliers) +
                       " samples were dropped as outliers (model mismatch or bad data?)");
  }
}

/// The warnings of a fit of a curve over heights: each of `params` poorly constrained (the hint
/// names the logged heights [h_min_m, h_max_m] and `advice`), and too many outliers (`what`). A
/// parameter whose standard error is at least its value is not determined at all (the data
/// cannot tell it from 0, nor its sign): that is a blocking warning (no --out without
/// --accept-warnings), not a plain one.
inline void warnCurveFit(std::vector<std::string>& warnings, std::vector<std::string>& blocking,
                         const std::string& what,
                         std::initializer_list<std::pair<const char*, const Estimate*>> params,
                         double h_min_m, double h_max_m, const std::string& advice,
                         const FitStats& stats) {
  const std::string hint = "heights " + num(h_min_m) + "–" + num(h_max_m) + " m; " + advice;
  for (const auto& [name, e] : params) {
    if (std::abs(e->std_error) >= std::abs(e->value) || !std::isfinite(e->std_error)) {
      blocking.push_back(what + ": " + name + " = " + num(e->value) + " ± " + num(e->std_error) +
                         " is not determined by the data (its standard error is at least its "
                         "value; " + hint + ")");
    } else {
      warnIfImprecise(warnings, name, *e, hint);
    }
  }
  warnIfManyOutliers(warnings, what, stats);
}

/// Adds a warning naming the knots of a table that fewer than `min_samples` samples support:
/// their values rest on a handful of samples (or on none, when only interpolation reaches them).
inline void warnSparseKnots(std::vector<std::string>& warnings, const std::string& what,
                            const TableCurve& curve, std::size_t min_samples = 5) {
  std::string list;
  std::size_t count = 0;
  for (std::size_t j = 0; j < curve.samples.size(); ++j) {
    if (curve.samples[j] >= min_samples) continue;
    if (++count <= 5) list += (list.empty() ? "" : ", ") + num(curve.heights_m[j]) + " m";
  }
  if (count > 0) {
    warnings.push_back(what + ": " + std::to_string(count) + " knot(s) with fewer than " +
                       std::to_string(min_samples) + " samples (" + list +
                       (count > 5 ? ", …" : "") + "): log more samples there or use fewer knots");
  }
}

/// The joint fit of (k_T, g1, g2) in f_z = k_T·S·(1 + g2/(h² + g1)) for per-sample S = Σn², h
/// and f_z [N] (robust, Ceres, from a variable-projection initial guess): the level board's
/// f̃_z, or a hover's m·a_z + k_T,observer·S. `w`: the samples' weights (empty: 1; 1/σ² with
/// robust.known_variances). Fills everything but the warnings. Throws IdentError naming
/// `source` and `what`.
AdditionalThrustFit fitThrustWithGroundEffect(const std::vector<double>& S,
                                              const std::vector<double>& h,
                                              const std::vector<double>& fz,
                                              const std::vector<double>& w,
                                              const RobustOptions& robust,
                                              const std::string& source, const std::string& what);

/// One blocking warning per parameter of a nonlinear fit that ended at a bound (fit.at_bound):
/// the optimum lies outside the range the fit allows, so the value is the bound, not a fit.
inline void blockAtBounds(std::vector<std::string>& blocking, const LeastSquaresFit& fit,
                          const NonlinearProblem& problem, std::initializer_list<const char*> names,
                          const std::string& what) {
  const std::vector<const char*> n(names);
  for (const int k : fit.at_bound) {
    const auto i = static_cast<std::size_t>(k);
    blocking.push_back(std::string(i < n.size() ? n[i] : "a parameter") + " = " + num(fit.x(k)) +
                       " ended at its bound (allowed [" + num(problem.lower[i]) + ", " + num(problem.upper[i]) +
                       "]) in the " + what + ": the data put its optimum outside the physical range, so the value "
                       "is the bound, not a fit");
  }
}

/// The fit, or an IdentError naming the log and what was being fitted.
inline const LeastSquaresFit& require(const LeastSquaresFit& fit, const std::string& source,
                                      const std::string& what) {
  if (!fit.ok) throw IdentError(source + ": cannot fit " + what + ": " + fit.message);
  return fit;
}

/// Splits heights sorted ascending into `bands` ranges [first, last) of about equal count; equal
/// heights never straddle two ranges (a platform logs many samples at each height). `samples`
/// (empty: 1 each): the samples behind each row (rows that are means), which the split counts.
inline std::vector<std::pair<std::size_t, std::size_t>> bandRanges(
    const std::vector<double>& sorted_h, int bands, const std::vector<double>& samples = {}) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  const std::size_t n = sorted_h.size();
  const auto count = static_cast<std::size_t>(std::max(1, bands));
  // cumulative[i]: samples in rows [0, i).
  std::vector<double> cumulative(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) cumulative[i + 1] = cumulative[i] + (samples.empty() ? 1.0 : samples[i]);
  std::size_t first = 0;
  for (std::size_t b = 0; b < count && first < n; ++b) {
    const double target = std::floor(static_cast<double>(b + 1) * cumulative[n] / static_cast<double>(count));
    std::size_t last = first + 1;
    while (last < n && cumulative[last] < target) ++last;
    if (b + 1 == count) last = n;
    while (last < n && sorted_h[last] == sorted_h[last - 1]) ++last;
    out.emplace_back(first, last);
    first = last;
  }
  return out;
}

}  // namespace geaware::ident::detail
