// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/ident/least_squares.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "least_squares_support.hpp"

namespace geaware::ident {

namespace detail {

double truncatedVariance(double k) {
  if (!(k > 0.0) || !std::isfinite(k)) return 1.0;
  const double phi = std::exp(-0.5 * k * k) / std::sqrt(2.0 * std::numbers::pi);
  return 1.0 - 2.0 * k * phi / std::erf(k / std::numbers::sqrt2);
}

double knownVarianceFactor(double ssr, double dof, double k) {
  return dof > 0.0 ? std::max(1.0, ssr / dof / truncatedVariance(k)) : 1.0;
}

double lossWeight(RobustLoss loss, double u) {
  switch (loss) {
    case RobustLoss::kHuber: return std::abs(u) <= 1.0 ? 1.0 : 1.0 / std::abs(u);
    case RobustLoss::kCauchy: return 1.0 / (1.0 + u * u);
    case RobustLoss::kNone: break;
  }
  return 1.0;
}

bool invertNormal(const Eigen::MatrixXd& A, Eigen::MatrixXd& inverse, double* condition) {
  const Eigen::Index p = A.rows();
  Eigen::VectorXd d(p);
  for (Eigen::Index i = 0; i < p; ++i) {
    if (!(A(i, i) > 0.0) || !std::isfinite(A(i, i))) return false;
    d(i) = 1.0 / std::sqrt(A(i, i));
  }
  const Eigen::MatrixXd S = d.asDiagonal() * A * d.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(S);
  const Eigen::VectorXd ev = eig.eigenvalues();
  if (!(ev.minCoeff() > kMinRelativeEigenvalue * ev.maxCoeff())) return false;
  if (condition != nullptr) *condition = std::sqrt(ev.maxCoeff() / ev.minCoeff());
  const Eigen::MatrixXd S_inv =
      eig.eigenvectors() * ev.cwiseInverse().asDiagonal() * eig.eigenvectors().transpose();
  inverse = d.asDiagonal() * S_inv * d.asDiagonal();
  return true;
}

const char* const kSingular =
    "the parameters are not identifiable from these samples (a regressor is zero or the "
    "regressors are collinear: the experiment does not excite them)";

}  // namespace detail

using detail::invertNormal;
using detail::kMaxParameters;
using detail::kSingular;
using detail::knownVarianceFactor;
using detail::lossWeight;
using detail::truncatedVariance;

double scaleFloor(const std::vector<double>& y) {
  if (y.empty()) return 0.0;
  double ss = 0.0;
  for (double v : y) ss += v * v;
  return kRelativeScaleFloor * std::sqrt(ss / static_cast<double>(y.size()));
}

// ------------------------------------------------------------------------------------ linear

namespace {

/// Dense rows of at most kMaxParameters regressors, stored once as √w-scaled [√w·x, √w·y]
/// records: the iterations are then tight loops over contiguous memory.
class DenseDesign {
 public:
  DenseDesign(std::size_t samples, int p, const LinearRow& row)
      : p_(p), stride_(static_cast<std::size_t>(p + 1)) {
    data_.reserve(samples * stride_);
    std::array<double, kMaxParameters> x{};
    for (std::size_t i = 0; i < samples; ++i) {
      double y = 0.0;
      double w = 1.0;
      if (!row(i, x.data(), y, w) || !(w > 0.0)) continue;
      const double sw = std::sqrt(w);
      for (int a = 0; a < p; ++a) data_.push_back(sw * x[static_cast<std::size_t>(a)]);
      data_.push_back(sw * y);
    }
  }
  /// One regressor from columns: what a row returning x[i], y[i], w[i] gives.
  DenseDesign(std::span<const double> x, std::span<const double> y, std::span<const double> w)
      : p_(1), stride_(2) {
    data_.resize(2 * x.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (!(w[i] > 0.0)) continue;
      const double sw = std::sqrt(w[i]);
      data_[k++] = sw * x[i];
      data_[k++] = sw * y[i];
    }
    data_.resize(k);
  }
  [[nodiscard]] std::size_t samples() const noexcept { return data_.size() / stride_; }
  /// The robust scale's floor from the √w-scaled outputs: scaleFloor's sum, read in place.
  [[nodiscard]] double floor() const {
    const std::size_t n = samples();
    if (n == 0) return 0.0;
    double ss = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double v = data_[i * stride_ + static_cast<std::size_t>(p_)];
      ss += v * v;
    }
    return kRelativeScaleFloor * std::sqrt(ss / static_cast<double>(n));
  }
  /// Lower triangle of Σ m·x·xᵀ and Σ m·x·y, m of sample i from weight(i).
  template <class Weight>
  void normal(const Weight& weight, Eigen::MatrixXd& A, Eigen::VectorXd& b) const {
    dispatch([&]<int P>() { normalFixed<P>(weight, A, b); });
  }
  void residuals(const Eigen::VectorXd& beta, std::vector<double>& r) const {
    dispatch([&]<int P>() { residualsFixed<P>(beta, r); });
  }

 private:
  int p_;
  std::size_t stride_;
  std::vector<double> data_;

  /// f.template operator()<p_>(): the loops below with the number of parameters known to the
  /// compiler (they then keep the sums in registers; each sum takes the same terms in the same
  /// order as with p_ read at run time).
  template <class F>
  void dispatch(F&& f) const {
    switch (p_) {
      case 1: f.template operator()<1>(); return;
      case 2: f.template operator()<2>(); return;
      case 3: f.template operator()<3>(); return;
      case 4: f.template operator()<4>(); return;
      case 5: f.template operator()<5>(); return;
      case 6: f.template operator()<6>(); return;
      case 7: f.template operator()<7>(); return;
      default: f.template operator()<8>(); return;
    }
  }
  template <int P, class Weight>
  void normalFixed(const Weight& weight, Eigen::MatrixXd& A, Eigen::VectorXd& b) const {
    static_assert(P >= 1 && P <= kMaxParameters);
    std::array<double, P * P> a{};
    std::array<double, P> bb{};
    for (int i = 0; i < P; ++i) {
      bb[i] = b(i);
      for (int c = 0; c <= i; ++c) a[i * P + c] = A(i, c);
    }
    const double* d = data_.data();
    const std::size_t n = samples();
    for (std::size_t i = 0; i < n; ++i, d += P + 1) {
      const double mi = weight(i);
      if (mi == 0.0) continue;
      for (int k = 0; k < P; ++k) {
        const double mk = mi * d[k];
        bb[k] += mk * d[P];
        for (int c = 0; c <= k; ++c) a[k * P + c] += mk * d[c];
      }
    }
    for (int i = 0; i < P; ++i) {
      b(i) = bb[i];
      for (int c = 0; c <= i; ++c) A(i, c) = a[i * P + c];
    }
  }
  template <int P>
  void residualsFixed(const Eigen::VectorXd& beta, std::vector<double>& r) const {
    std::array<double, P> x{};
    for (int k = 0; k < P; ++k) x[k] = beta(k);
    const double* d = data_.data();
    for (std::size_t i = 0; i < r.size(); ++i, d += P + 1) {
      double pred = 0.0;
      for (int k = 0; k < P; ++k) pred += d[k] * x[k];
      r[i] = d[P] - pred;
    }
  }
};

/// Rows with at most kMaxRowEntries non-zero regressors out of many parameters (compressed
/// rows): the normal matrix costs O(k²) per sample instead of O(p²).
class SparseDesign {
 public:
  SparseDesign(std::size_t samples, int p, const SparseLinearRow& row) {
    start_.reserve(samples + 1);
    y_.reserve(samples);
    start_.push_back(0);
    std::array<int, kMaxRowEntries> index{};
    std::array<double, kMaxRowEntries> value{};
    for (std::size_t i = 0; i < samples; ++i) {
      double y = 0.0;
      double w = 1.0;
      int count = 0;
      if (!row(i, index.data(), value.data(), count, y, w) || !(w > 0.0)) continue;
      if (count < 0 || count > kMaxRowEntries) {
        throw std::invalid_argument("fitSparseLinear: a row has " + std::to_string(count) +
                                    " entries, at most " + std::to_string(kMaxRowEntries));
      }
      const double sw = std::sqrt(w);
      for (std::size_t e = 0; e < static_cast<std::size_t>(count); ++e) {
        if (index[e] < 0 || index[e] >= p) {
          throw std::invalid_argument("fitSparseLinear: parameter index " +
                                      std::to_string(index[e]) + " outside [0, " +
                                      std::to_string(p) + ")");
        }
        index_.push_back(index[e]);
        value_.push_back(sw * value[e]);
      }
      start_.push_back(index_.size());
      y_.push_back(sw * y);
    }
  }
  [[nodiscard]] std::size_t samples() const noexcept { return y_.size(); }
  [[nodiscard]] double floor() const { return scaleFloor(y_); }
  template <class Weight>
  void normal(const Weight& weight, Eigen::MatrixXd& A, Eigen::VectorXd& b) const {
    for (std::size_t i = 0; i < y_.size(); ++i) {
      const double mi = weight(i);
      if (mi == 0.0) continue;
      for (std::size_t e = start_[i]; e < start_[i + 1]; ++e) {
        const double me = mi * value_[e];
        b(index_[e]) += me * y_[i];
        for (std::size_t f = start_[i]; f < start_[i + 1]; ++f) {
          // Lower triangle only (row ≥ column), as the dense design fills it.
          if (index_[f] <= index_[e]) A(index_[e], index_[f]) += me * value_[f];
        }
      }
    }
  }
  void residuals(const Eigen::VectorXd& beta, std::vector<double>& r) const {
    for (std::size_t i = 0; i < r.size(); ++i) {
      double pred = 0.0;
      for (std::size_t e = start_[i]; e < start_[i + 1]; ++e) pred += value_[e] * beta(index_[e]);
      r[i] = y_[i] - pred;
    }
  }

 private:
  std::vector<std::size_t> start_;
  std::vector<int> index_;
  std::vector<double> value_;
  std::vector<double> y_;
};

/// Steps 1–4 of the header on a design (DenseDesign or SparseDesign) with p parameters.
template <class Design>
LeastSquaresFit robustLinear(const Design& design, int p, const RobustOptions& robust) {
  LeastSquaresFit fit;
  const std::size_t n = design.samples();
  const bool known = robust.known_variances;
  if (n < static_cast<std::size_t>(p) + (known ? 0 : 1)) {
    fit.message = "too few samples: " + std::to_string(n) + " for " + std::to_string(p) +
                  (p == 1 ? " parameter" : " parameters");
    return fit;
  }

  std::vector<double> m(n, 1.0);  // robust multipliers of the weights (0: dropped)
  std::vector<double> r(n, 0.0);  // √w-scaled residuals
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(p);
  Eigen::MatrixXd A_inv;

  // The residuals' robust scale, never below the floor (exact data).
  const double floor = design.floor();
  RobustScale robust_scale;
  auto scale = [&] { return std::max(robust_scale.sigma(r), floor); };
  // Solves the normal equations with multipliers weight(i) (by default m), then fills r. False
  // when singular.
  const auto stored = [&m](std::size_t i) { return m[i]; };
  auto solve = [&](const auto& weight) -> bool {
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(p, p);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(p);
    design.normal(weight, A, b);
    A = A.template selfadjointView<Eigen::Lower>();
    if (!invertNormal(A, A_inv, &fit.stats.condition_number)) return false;
    beta = A_inv * b;
    design.residuals(beta, r);
    return true;
  };

  if (!solve(stored)) {
    fit.message = kSingular;
    return fit;
  }
  // The IRLS multipliers lossWeight(loss, r[i]/threshold) of the residuals r before a solve,
  // computed as the normal equations take them. Huber's is 1 where |u| = |r|/threshold ≤ 1;
  // with a finite threshold > 0 that holds wherever |r| ≤ threshold (division rounds
  // monotonically and 1 is a double), so only the others need lossWeight's two divisions.
  auto solveReweighted = [&](double threshold) -> bool {
    switch (robust.loss) {
      case RobustLoss::kHuber: {
        const bool finite = threshold > 0.0 && threshold < std::numeric_limits<double>::infinity();
        return solve([&](std::size_t i) {
          return finite && std::abs(r[i]) <= threshold ? 1.0 : lossWeight(RobustLoss::kHuber, r[i] / threshold);
        });
      }
      case RobustLoss::kCauchy:
        return solve([&](std::size_t i) { return lossWeight(RobustLoss::kCauchy, r[i] / threshold); });
      case RobustLoss::kNone: break;
    }
    return solve([&](std::size_t i) { return lossWeight(RobustLoss::kNone, r[i] / threshold); });
  };
  // 1. Robust fit by iteratively reweighted least squares. It only has to separate the
  //    outliers from the rest (step 3 refits), so it stops at a small fraction of a standard
  //    error; the residual scale is re-estimated in the first iterations only.
  if (robust.loss != RobustLoss::kNone && !known) {
    double s = 0.0;
    for (int iter = 0; iter < 50; ++iter) {
      if (iter < 3) s = scale();
      if (!(s > 0.0)) break;  // exact fit: nothing to down-weight
      const double threshold = robust.loss_scale * s;
      const Eigen::VectorXd previous = beta;
      if (!solveReweighted(threshold)) {
        fit.message = kSingular;
        return fit;
      }
      const Eigen::VectorXd sd = A_inv.diagonal().cwiseSqrt() * s;
      if (iter >= 2 && ((beta - previous).cwiseAbs().array() <= 1e-3 * sd.array()).all()) break;
    }
  }
  // 2. Outliers, 3. plain least squares on the rest.
  std::fill(m.begin(), m.end(), 1.0);
  double k = 0.0;
  if (robust.outlier_sigmas > 0.0 && !known) {
    const double s = scale();
    if (s > 0.0) {
      k = robust.outlier_sigmas;
      for (std::size_t i = 0; i < n; ++i) {
        if (std::abs(r[i]) > k * s) {
          m[i] = 0.0;
          ++fit.stats.outliers;
        }
      }
    }
  }
  fit.stats.count = n - fit.stats.outliers;
  if (fit.stats.count < static_cast<std::size_t>(p) + (known ? 0 : 1)) {
    fit.message = "too few samples left after removing outliers";
    return fit;
  }
  if (!solve(stored)) {
    fit.message = kSingular;
    return fit;
  }
  // 4. Uncertainty.
  double ssr = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (m[i] != 0.0) ssr += r[i] * r[i];
  }
  const double dof = static_cast<double>(fit.stats.count - static_cast<std::size_t>(p));
  const double sigma2 = known ? knownVarianceFactor(ssr, dof, k) : ssr / dof / truncatedVariance(k);
  fit.x = beta;
  fit.covariance = sigma2 * A_inv;
  fit.stats.residual_rms = std::sqrt(ssr / static_cast<double>(fit.stats.count));
  fit.ok = true;
  return fit;
}

}  // namespace

LeastSquaresFit fitLinear(std::size_t samples, int parameters, const LinearRow& row,
                          const RobustOptions& robust) {
  if (parameters < 1 || parameters > kMaxParameters) {
    throw std::invalid_argument("fitLinear: 1 to 8 parameters");
  }
  return robustLinear(DenseDesign(samples, parameters, row), parameters, robust);
}

namespace detail {

LeastSquaresFit fitLinearColumns(std::span<const double> x, std::span<const double> y,
                                 std::span<const double> w, const RobustOptions& robust) {
  if (y.size() != x.size() || w.size() != x.size()) {
    throw std::invalid_argument("fitLinearColumns: columns of different lengths");
  }
  return robustLinear(DenseDesign(x, y, w), 1, robust);
}

}  // namespace detail

LeastSquaresFit fitSparseLinear(std::size_t samples, int parameters, const SparseLinearRow& row,
                                const RobustOptions& robust) {
  if (parameters < 1 || parameters > kMaxSparseParameters) {
    throw std::invalid_argument("fitSparseLinear: 1 to " + std::to_string(kMaxSparseParameters) +
                                " parameters");
  }
  return robustLinear(SparseDesign(samples, parameters, row), parameters, robust);
}

}  // namespace geaware::ident
