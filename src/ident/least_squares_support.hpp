// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Internal to least_squares.cpp and nonlinear_fit.cpp: the pieces the linear and the nonlinear
// solver share (the uncertainty and the identifiability test); and fitLinearColumns, the one-
// regressor linear fit of fitMixing (platform_fit.cpp).

#include <span>

#include <Eigen/Core>

#include "geaware/ident/least_squares.hpp"

namespace geaware::ident::detail {

inline constexpr int kMaxParameters = 8;
/// Smallest eigenvalue, relative to the largest, of the column-scaled normal matrix for which
/// the parameters still count as identifiable.
inline constexpr double kMinRelativeEigenvalue = 1e-12;

/// Variance of a standard normal truncated at ±k: the residuals kept after dropping those
/// beyond k robust sigmas under-estimate σ² by this factor.
double truncatedVariance(double k);

/// σ² for weights that are known inverse variances: 1, or the reduced χ² (corrected for the
/// truncation at ±k) where the residuals scatter more than their σ (the Birge ratio).
double knownVarianceFactor(double ssr, double dof, double k);

/// IRLS weight of a residual u, given in units of the loss threshold.
double lossWeight(RobustLoss loss, double u);

/// Inverse of a symmetric positive semi-definite normal matrix, computed on its column-scaled
/// form; false when it is (numerically) singular. `condition` (optional): the scaled matrix's
/// √(λmax/λmin), the design's condition number.
bool invertNormal(const Eigen::MatrixXd& A, Eigen::MatrixXd& inverse, double* condition = nullptr);

/// fitLinear with one regressor from columns: sample i is x[i], y[i] with weight w[i] (left out
/// where w[i] ≤ 0), the numbers fitLinear gives for a row that returns them, without a call
/// through std::function per sample.
[[nodiscard]] LeastSquaresFit fitLinearColumns(std::span<const double> x, std::span<const double> y,
                                               std::span<const double> w, const RobustOptions& robust);

/// The message of a singular problem.
extern const char* const kSingular;

}  // namespace geaware::ident::detail
