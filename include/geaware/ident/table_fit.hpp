// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Ground-effect curves identified as tables (docs/identification.md, "Curves as tables"):
// instead of the paper's closed forms, the curve's value at each of a set of knot heights.
//
// The fits treat the curve as linear in its knot values: between two knots it is the linear
// interpolation, below the first knot the first value is held, above the last it is the
// inverse-square tail v_N·(h_N/h)² that model::HeightTable uses too. Each sample's regressor
// therefore touches at most two knots, and every table fit is a sparse linear least-squares
// problem (fitSparseLinear), robust like every other fit. Rig logs are taken at fixed heights,
// and the automatic knots are those heights: every sample then sits on a knot, where the
// fitted linear interpolation and the model's PCHIP interpolation agree exactly.

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geaware/ident/least_squares.hpp"

namespace geaware::ident {

/// Where a table's knots go.
struct TableOptions {
  /// The knots [m], strictly increasing. Empty: chosen from the log (chooseKnots).
  std::vector<double> heights_m;
  /// Automatic knots: none above this height [m]; samples above it follow the 1/h² tail.
  double top_m = std::numeric_limits<double>::infinity();
  /// Automatic knots: at most this many (more distinct heights are thinned by sample count).
  std::size_t max_knots = 120;
};

/// A curve fitted as a table: its value and standard error at each knot.
struct TableCurve {
  std::vector<double> heights_m;
  std::vector<Estimate> values;
  Eigen::MatrixXd covariance;  ///< of the knot values
  std::vector<std::size_t> samples;  ///< samples with weight on each knot (within its intervals)
};

/// The knots for sample heights `h` (any order): `options.heights_m` when given (checked), or
/// the distinct heights (to 0.1 mm) up to top_m, thinned to max_knots by sample count. Throws
/// IdentError (naming `source` and `what`) when fewer than 2 knots result.
[[nodiscard]] std::vector<double> chooseKnots(const std::vector<double>& h,
                                              const TableOptions& options,
                                              const std::string& source, const std::string& what);

/// The basis at h: fills up to 2 (knot index, weight) pairs and returns their count.
int tableBasis(const std::vector<double>& knots, double h_m, int* index, double* weight) noexcept;

/// The linear interpolant of a table at h with the held start and the 1/h² tail (the fits'
/// own curve; at the knots it equals model::HeightTable's).
[[nodiscard]] double tableValue(const std::vector<double>& knots,
                                const std::vector<double>& values, double h_m) noexcept;

}  // namespace geaware::ident
