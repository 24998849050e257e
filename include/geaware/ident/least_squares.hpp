// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The two solvers behind every fit of ident/: linear least squares and nonlinear least squares
// (Ceres), both with the same robust scheme and the same uncertainty (docs/identification.md,
// "Robust loss" and "Uncertainty"):
//
//  1. a robust fit: iteratively reweighted least squares (linear) or Ceres with a Huber or
//     Cauchy loss on every sample (nonlinear), with the loss threshold set in units of the
//     residuals' robust standard deviation s = 1.4826·MAD;
//  2. samples whose residual exceeds `outlier_sigmas`·s are declared outliers (counted in the
//     result) and dropped;
//  3. a plain least-squares fit of the remaining samples, from the robust solution;
//  4. covariance σ²·(JᵀWJ)⁻¹ with the Jacobian J at the optimum and σ² = Σ w·r²/(n − p) from
//     the residuals, corrected for the truncation of a normal distribution at ±outlier_sigmas.
//
// With clean Gaussian data (almost) nothing is dropped and the result is the ordinary least-
// squares estimate with its textbook standard errors; with gross outliers the robust step
// keeps them from pulling the fit, and step 4 reports the uncertainty of the inliers.

#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace geaware::ident {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A fit that cannot be done (too few samples, data that do not constrain the parameters):
/// what() names the log and the parameter.
class IdentError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A fitted parameter: its value and standard error, in the parameter's unit.
struct Estimate {
  double value = kNaN;
  double std_error = kNaN;
  [[nodiscard]] bool valid() const noexcept { return value == value && std_error == std_error; }
};

/// Residual statistics of one fit.
struct FitStats {
  double residual_rms = kNaN;   ///< RMS of the (weighted) residuals of the samples kept [output unit]
  std::size_t count = 0;        ///< samples kept in the final fit
  std::size_t outliers = 0;     ///< samples dropped as outliers
  /// Condition number of the design (the Jacobian at the optimum, columns scaled to unit
  /// norm): √(λmax/λmin) of the scaled normal matrix. 1 for orthogonal regressors; large when
  /// the parameters trade off against each other (kIllConditioned) [-].
  double condition_number = kNaN;
};

/// Above this condition number a fit is flagged as ill-conditioned. With unit-norm columns the
/// standard error of the worst-determined combination of parameters is κ times what orthogonal
/// regressors with the same data would give; κ = 1e4 (variance inflation 1e8) is far beyond the
/// ~1e2–1e3 of the closed-form curves g2/(h² + g1) fitted over a full height sweep, and a decade
/// below the 1e6 (eigenvalue ratio 1e-12) where the fits refuse as "not identifiable". The
/// estimates of such a fit are determined only as a combination: report it, do not trust each.
inline constexpr double kIllConditioned = 1e4;

enum class RobustLoss { kNone, kHuber, kCauchy };

struct RobustOptions {
  RobustLoss loss = RobustLoss::kHuber;
  /// Loss threshold in robust standard deviations of the residuals (Huber's 1.345 gives 95 %
  /// efficiency on normal data; 2.385 is the usual choice for Cauchy) [-].
  double loss_scale = 1.345;
  /// Residuals beyond this many robust standard deviations are outliers; ≤ 0 keeps all [-].
  double outlier_sigmas = 4.0;
  /// The weights are inverse variances 1/σ² of known measurement errors (rows of a table given
  /// as mean ± std with a count: σ = std/√count), not relative weights: the covariance is
  /// (JᵀWJ)⁻¹, multiplied by the reduced χ² = Σw·r²/(n − p) only where that exceeds 1 (means
  /// that scatter more than their stds say: the model misses them), and n = p samples suffice.
  /// The robust loss and the outlier test are not applied: each row is already a mean of many
  /// samples, and a handful of rows gives no robust scale (a loss fitted to 10 rows dropped the
  /// lowest, most informative one). Nonlinear fits take the residuals already divided by σ.
  bool known_variances = false;
};

/// Result of a linear or nonlinear fit.
struct LeastSquaresFit {
  Eigen::VectorXd x;            ///< parameters
  Eigen::MatrixXd covariance;   ///< σ²·(JᵀWJ)⁻¹
  FitStats stats;
  bool ok = false;              ///< false: not enough samples or a singular problem (see message)
  std::string message;
  /// Nonlinear fits: the parameters that ended at one of their bounds (within 1e-6 of the
  /// bound's scale): the optimum lies outside the range allowed, the value is not a fit.
  std::vector<int> at_bound;

  [[nodiscard]] Estimate estimate(int i) const {
    return {x(i), std::sqrt(covariance(i, i))};
  }
};

/// Sample i of a linear problem y = xᵀβ with weight w: fills `row` (p values), `y` and `w`
/// (1 for unweighted samples). Return false to leave the sample out.
using LinearRow = std::function<bool(std::size_t i, double* row, double& y, double& w)>;

/// Weighted linear least squares of `samples` rows with `parameters` unknowns (robust as above).
[[nodiscard]] LeastSquaresFit fitLinear(std::size_t samples, int parameters, const LinearRow& row,
                                        const RobustOptions& robust = {});

/// Residual of sample i of a nonlinear problem at parameters x, and its gradient dr/dx
/// (`gradient` may be null). Return false when x lies outside the model's domain.
using NonlinearResidual =
    std::function<bool(std::size_t i, const double* x, double& r, double* gradient)>;

/// The residuals r[m] of the samples indices[0 … count−1] at x, and their gradients (row m at
/// gradients + m·parameters; null: none). Return false when x lies outside the model's domain.
using NonlinearBlockResidual = std::function<bool(const std::size_t* indices, std::size_t count,
                                                  const double* x, double* r, double* gradients)>;

/// A block form of `residual` (the same per-sample computation in a loop, e.g. both calling one
/// lambda), for speed: the solver then makes one call per block of samples instead of one per
/// sample. The numbers must be those `residual` gives.
template <class PerSample>
[[nodiscard]] NonlinearBlockResidual blockResidual(PerSample per_sample, int parameters) {
  return [per_sample, parameters](const std::size_t* indices, std::size_t count, const double* x, double* r,
                                  double* gradients) {
    for (std::size_t m = 0; m < count; ++m) {
      double* g = gradients != nullptr ? gradients + m * static_cast<std::size_t>(parameters) : nullptr;
      if (!per_sample(indices[m], x, r[m], g)) return false;
    }
    return true;
  };
}

struct NonlinearProblem {
  std::size_t samples = 0;
  int parameters = 0;
  NonlinearResidual residual;
  /// Optional (empty: `residual` per sample): `residual` for a block of samples at once.
  NonlinearBlockResidual block;
  /// Typical magnitude of each parameter; Ceres works on x/scale so that all are O(1).
  std::vector<double> scales;
  std::vector<double> lower;  ///< bounds, −inf/+inf for none (empty: unbounded)
  std::vector<double> upper;
  /// Smallest robust scale of the residuals [output unit]; 0: none. Exact data (noise-free, or
  /// rows copied to their counts) leave residuals at rounding noise, and a robust scale of that
  /// size would make every sample an outlier: set it to kRelativeScaleFloor times the size of
  /// the outputs (scaleFloor). Linear fits set theirs from y themselves.
  double scale_floor = 0.0;
};

/// The robust scale's floor relative to the RMS of the (weighted) outputs [-]. Rounding leaves
/// residuals of ~1e-16 of the outputs times the problem's condition; any measurement scatters
/// far more than 1e-9 of its value (a load cell resolves ~1e-5 of its range at best). Below the
/// floor the data are taken as exact: no sample is down-weighted or dropped.
inline constexpr double kRelativeScaleFloor = 1e-6;

/// kRelativeScaleFloor times the RMS of `y` (0 for no samples).
[[nodiscard]] double scaleFloor(const std::vector<double>& y);

/// Most non-zero regressors in one row of a sparse linear problem, and most parameters.
inline constexpr int kMaxRowEntries = 8;
inline constexpr int kMaxSparseParameters = 1000;

/// Sample i of a sparse linear problem y = Σ_e value[e]·β[index[e]]: fills up to
/// kMaxRowEntries (index, value) pairs and sets `count`, `y` and `w`. Return false to leave
/// the sample out. For curves given at many knots (a tabulated F_G), where each sample touches
/// only its neighbouring knots.
using SparseLinearRow = std::function<bool(std::size_t i, int* index, double* value, int& count,
                                           double& y, double& w)>;

/// The same robust weighted linear least squares as fitLinear for up to
/// kMaxSparseParameters parameters; each sample costs O(count²), the solve O(p³).
[[nodiscard]] LeastSquaresFit fitSparseLinear(std::size_t samples, int parameters,
                                              const SparseLinearRow& row,
                                              const RobustOptions& robust = {});

/// Robust nonlinear least squares with Ceres from the initial guess x0.
[[nodiscard]] LeastSquaresFit fitNonlinear(const NonlinearProblem& problem,
                                           const Eigen::VectorXd& x0,
                                           const RobustOptions& robust = {});

/// Robust standard deviation 1.4826·median(|v − median(v)|) (normal-consistent MAD).
[[nodiscard]] double robustSigma(std::vector<double> v);

namespace detail {
/// Room for n doubles, grown as needed and never initialized: a pass that writes only the
/// first part touches (and pays for) only those pages.
class ValueBuffer {
 public:
  [[nodiscard]] double* get(std::size_t n) {
    if (size_ < n) {
      data_ = std::make_unique_for_overwrite<double[]>(n);
      size_ = n;
    }
    return data_.get();
  }

 private:
  std::unique_ptr<double[]> data_;
  std::size_t size_ = 0;
};
}  // namespace detail

/// robustSigma for many vectors in a row (the iterations of one fit), with its buffers kept
/// between calls: after the first call it allocates nothing, and v is read, not copied.
class RobustScale {
 public:
  /// robustSigma(v), the same value bit for bit.
  [[nodiscard]] double sigma(std::span<const double> v);
  /// The k-th smallest (0-based) of v, k < v.size(): for values without NaN, the value
  /// std::nth_element puts at position k of a copy of v (any exact selection gives it; of a −0
  /// and a +0, which compare equal, either may come). With NaN there is no order, and the value
  /// is the one robustSigma's selection always gave (from the sampled window on ≥ 8192 values).
  [[nodiscard]] double kthSmallest(std::span<const double> v, std::size_t k);

 private:
  detail::ValueBuffer window_;  ///< the values inside the sample's bracket
  detail::ValueBuffer inner_;   ///< the values inside a second bracket, within the window
  std::vector<double> values_;  ///< a copy of v when all of v must be selected from
};

}  // namespace geaware::ident
