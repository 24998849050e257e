// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/ident/least_squares.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>

#include <ceres/ceres.h>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace geaware::ident {

namespace {

constexpr int kMaxParameters = 8;
/// Smallest eigenvalue, relative to the largest, of the column-scaled normal matrix for which
/// the parameters still count as identifiable.
constexpr double kMinRelativeEigenvalue = 1e-12;

/// Variance of a standard normal truncated at ±k: the residuals kept after dropping those
/// beyond k robust sigmas under-estimate σ² by this factor.
double truncatedVariance(double k) {
  if (!(k > 0.0) || !std::isfinite(k)) return 1.0;
  const double phi = std::exp(-0.5 * k * k) / std::sqrt(2.0 * std::numbers::pi);
  return 1.0 - 2.0 * k * phi / std::erf(k / std::numbers::sqrt2);
}

/// IRLS weight of a residual u, given in units of the loss threshold.
double lossWeight(RobustLoss loss, double u) {
  switch (loss) {
    case RobustLoss::kHuber: return std::abs(u) <= 1.0 ? 1.0 : 1.0 / std::abs(u);
    case RobustLoss::kCauchy: return 1.0 / (1.0 + u * u);
    case RobustLoss::kNone: break;
  }
  return 1.0;
}

/// Inverse of a symmetric positive semi-definite normal matrix, computed on its column-scaled
/// form; nullopt-like (ok = false) when it is (numerically) singular.
bool invertNormal(const Eigen::MatrixXd& A, Eigen::MatrixXd& inverse) {
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
  const Eigen::MatrixXd S_inv =
      eig.eigenvectors() * ev.cwiseInverse().asDiagonal() * eig.eigenvectors().transpose();
  inverse = d.asDiagonal() * S_inv * d.asDiagonal();
  return true;
}

const char* kSingular =
    "the parameters are not identifiable from these samples (a regressor is zero or the "
    "regressors are collinear: the experiment does not excite them)";

}  // namespace

double robustSigma(std::vector<double> v) {
  if (v.empty()) return kNaN;
  auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  const double median = *mid;
  for (double& x : v) x = std::abs(x - median);
  std::nth_element(v.begin(), mid, v.end());
  return 1.482602218505602 * *mid;
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
  [[nodiscard]] std::size_t samples() const noexcept { return data_.size() / stride_; }
  /// Lower triangle of Σ m·x·xᵀ and Σ m·x·y.
  void normal(const std::vector<double>& m, Eigen::MatrixXd& A, Eigen::VectorXd& b) const {
    for (std::size_t i = 0; i < m.size(); ++i) {
      if (m[i] == 0.0) continue;
      const double* d = data_.data() + i * stride_;
      for (int a = 0; a < p_; ++a) {
        const double ma = m[i] * d[a];
        b(a) += ma * d[p_];
        for (int c = 0; c <= a; ++c) A(a, c) += ma * d[c];
      }
    }
  }
  void residuals(const Eigen::VectorXd& beta, std::vector<double>& r) const {
    for (std::size_t i = 0; i < r.size(); ++i) {
      const double* d = data_.data() + i * stride_;
      double pred = 0.0;
      for (int a = 0; a < p_; ++a) pred += d[a] * beta(a);
      r[i] = d[p_] - pred;
    }
  }

 private:
  int p_;
  std::size_t stride_;
  std::vector<double> data_;
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
  void normal(const std::vector<double>& m, Eigen::MatrixXd& A, Eigen::VectorXd& b) const {
    for (std::size_t i = 0; i < m.size(); ++i) {
      if (m[i] == 0.0) continue;
      for (std::size_t e = start_[i]; e < start_[i + 1]; ++e) {
        const double me = m[i] * value_[e];
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
  if (n <= static_cast<std::size_t>(p)) {
    fit.message = "too few samples: " + std::to_string(n) + " for " + std::to_string(p) +
                  (p == 1 ? " parameter" : " parameters");
    return fit;
  }

  std::vector<double> m(n, 1.0);  // robust multipliers of the weights (0: dropped)
  std::vector<double> r(n, 0.0);  // √w-scaled residuals
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(p);
  Eigen::MatrixXd A_inv;

  // Solves the normal equations with multipliers m, then fills r. False when singular.
  auto solve = [&]() -> bool {
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(p, p);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(p);
    design.normal(m, A, b);
    A = A.template selfadjointView<Eigen::Lower>();
    if (!invertNormal(A, A_inv)) return false;
    beta = A_inv * b;
    design.residuals(beta, r);
    return true;
  };

  if (!solve()) {
    fit.message = kSingular;
    return fit;
  }
  // 1. Robust fit by iteratively reweighted least squares. It only has to separate the
  //    outliers from the rest (step 3 refits), so it stops at a small fraction of a standard
  //    error; the residual scale is re-estimated in the first iterations only.
  if (robust.loss != RobustLoss::kNone) {
    double s = 0.0;
    for (int iter = 0; iter < 50; ++iter) {
      if (iter < 3) s = robustSigma(r);
      if (!(s > 0.0)) break;  // exact fit: nothing to down-weight
      const double threshold = robust.loss_scale * s;
      for (std::size_t i = 0; i < n; ++i) m[i] = lossWeight(robust.loss, r[i] / threshold);
      const Eigen::VectorXd previous = beta;
      if (!solve()) {
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
  if (robust.outlier_sigmas > 0.0) {
    const double s = robustSigma(r);
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
  if (fit.stats.count <= static_cast<std::size_t>(p)) {
    fit.message = "too few samples left after removing outliers";
    return fit;
  }
  if (!solve()) {
    fit.message = kSingular;
    return fit;
  }
  // 4. Uncertainty.
  double ssr = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (m[i] != 0.0) ssr += r[i] * r[i];
  }
  const double dof = static_cast<double>(fit.stats.count - static_cast<std::size_t>(p));
  const double sigma2 = ssr / dof / truncatedVariance(k);
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

LeastSquaresFit fitSparseLinear(std::size_t samples, int parameters, const SparseLinearRow& row,
                                const RobustOptions& robust) {
  if (parameters < 1 || parameters > kMaxSparseParameters) {
    throw std::invalid_argument("fitSparseLinear: 1 to " + std::to_string(kMaxSparseParameters) +
                                " parameters");
  }
  return robustLinear(SparseDesign(samples, parameters, row), parameters, robust);
}

// --------------------------------------------------------------------------------- nonlinear

namespace {

/// A block of samples as one Ceres residual block (one block per sample costs Ceres far more
/// than the model). Because a Ceres LossFunction acts on a whole block, the robust loss is
/// applied here, per sample, as the residual √ρ(r²)·sign(r) whose square is ρ(r²); its
/// Gauss–Newton Jacobian is ρ'·|r|/√ρ·∂r/∂x.
class SampleBlock final : public ceres::CostFunction {
 public:
  SampleBlock(const NonlinearProblem& problem, const std::size_t* indices, std::size_t count,
              const ceres::LossFunction* loss)
      : problem_(problem), indices_(indices), count_(count), loss_(loss) {
    set_num_residuals(static_cast<int>(count));
    mutable_parameter_block_sizes()->push_back(problem.parameters);
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const int p = problem_.parameters;
    std::array<double, kMaxParameters> x{};
    for (int k = 0; k < p; ++k) x[k] = parameters[0][k] * problem_.scales[k];
    double* J = jacobians != nullptr ? jacobians[0] : nullptr;
    std::array<double, kMaxParameters> g{};
    for (std::size_t j = 0; j < count_; ++j) {
      double r = 0.0;
      if (!problem_.residual(indices_[j], x.data(), r, J != nullptr ? g.data() : nullptr)) return false;
      double d = 1.0;
      if (loss_ != nullptr) {
        double rho[3];
        loss_->Evaluate(r * r, rho);
        const double rt = std::sqrt(rho[0]);
        d = rt > 0.0 ? rho[1] * std::abs(r) / rt : 1.0;
        r = r < 0.0 ? -rt : rt;
      }
      residuals[j] = r;
      if (J != nullptr) {
        for (int k = 0; k < p; ++k) J[j * p + k] = d * g[k] * problem_.scales[k];
      }
    }
    return true;
  }

 private:
  const NonlinearProblem& problem_;
  const std::size_t* indices_;
  std::size_t count_;
  const ceres::LossFunction* loss_;
};

constexpr std::size_t kBlockSamples = 2048;

/// Least squares of the samples `indices` from x (in place), with an optional loss.
bool solveCeres(const NonlinearProblem& problem, const std::vector<std::size_t>& indices,
                const ceres::LossFunction* loss, Eigen::VectorXd& x, std::string& message) {
  const int p = problem.parameters;
  std::vector<double> xs(static_cast<std::size_t>(p));
  for (int k = 0; k < p; ++k) xs[k] = x(k) / problem.scales[k];
  ceres::Problem cp;
  for (std::size_t start = 0; start < indices.size(); start += kBlockSamples) {
    const std::size_t count = std::min(kBlockSamples, indices.size() - start);
    cp.AddResidualBlock(new SampleBlock(problem, indices.data() + start, count, loss), nullptr,
                        xs.data());
  }
  for (int k = 0; k < p; ++k) {
    if (!problem.lower.empty() && std::isfinite(problem.lower[k])) {
      cp.SetParameterLowerBound(xs.data(), k, problem.lower[k] / problem.scales[k]);
    }
    if (!problem.upper.empty() && std::isfinite(problem.upper[k])) {
      cp.SetParameterUpperBound(xs.data(), k, problem.upper[k] / problem.scales[k]);
    }
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  options.logging_type = ceres::SILENT;
  options.max_num_iterations = 200;
  // Tight tolerances: the optimum must be reached to a small fraction of a standard error.
  options.function_tolerance = 1e-12;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-10;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &cp, &summary);
  if (!summary.IsSolutionUsable()) {
    message = "Ceres did not converge: " + summary.BriefReport();
    return false;
  }
  for (int k = 0; k < p; ++k) x(k) = xs[k] * problem.scales[k];
  return true;
}

std::unique_ptr<ceres::LossFunction> makeLoss(RobustLoss loss, double threshold) {
  switch (loss) {
    case RobustLoss::kHuber: return std::make_unique<ceres::HuberLoss>(threshold);
    case RobustLoss::kCauchy: return std::make_unique<ceres::CauchyLoss>(threshold);
    case RobustLoss::kNone: break;
  }
  return nullptr;
}

}  // namespace

LeastSquaresFit fitNonlinear(const NonlinearProblem& problem, const Eigen::VectorXd& x0,
                             const RobustOptions& robust) {
  LeastSquaresFit fit;
  const int p = problem.parameters;
  if (p < 1 || p > kMaxParameters || x0.size() != p ||
      problem.scales.size() != static_cast<std::size_t>(p)) {
    throw std::invalid_argument("fitNonlinear: inconsistent problem dimensions");
  }
  if (problem.samples <= static_cast<std::size_t>(p)) {
    fit.message = "too few samples: " + std::to_string(problem.samples) + " for " +
                  std::to_string(p) + " parameters";
    return fit;
  }
  std::vector<std::size_t> all(problem.samples);
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  auto residuals = [&](const Eigen::VectorXd& x, std::vector<double>& r) -> bool {
    r.resize(problem.samples);
    for (std::size_t i = 0; i < problem.samples; ++i) {
      if (!problem.residual(i, x.data(), r[i], nullptr)) return false;
    }
    return true;
  };

  Eigen::VectorXd x = x0;
  std::vector<double> r;
  if (!residuals(x, r)) {
    fit.message = "the initial guess lies outside the model's domain";
    return fit;
  }
  // 1. Robust fit; the loss threshold follows the residual scale: set from the initial guess,
  //    and once more from the robust solution if the scale changed by more than 20 %.
  if (robust.loss != RobustLoss::kNone) {
    double previous_s = 0.0;
    for (int round = 0; round < 2; ++round) {
      const double s = robustSigma(r);
      if (!(s > 0.0) || std::abs(s - previous_s) <= 0.2 * s) break;
      previous_s = s;
      const auto loss = makeLoss(robust.loss, robust.loss_scale * s);
      if (!solveCeres(problem, all, loss.get(), x, fit.message)) return fit;
      if (!residuals(x, r)) {
        fit.message = "the robust fit left the model's domain";
        return fit;
      }
    }
  }
  // 2. Outliers.
  std::vector<std::size_t> kept;
  kept.reserve(problem.samples);
  double k = 0.0;
  const double s = robust.outlier_sigmas > 0.0 ? robustSigma(r) : 0.0;
  if (s > 0.0) k = robust.outlier_sigmas;
  for (std::size_t i = 0; i < problem.samples; ++i) {
    if (k == 0.0 || std::abs(r[i]) <= k * s) kept.push_back(i);
  }
  fit.stats.outliers = problem.samples - kept.size();
  fit.stats.count = kept.size();
  if (kept.size() <= static_cast<std::size_t>(p)) {
    fit.message = "too few samples left after removing outliers";
    return fit;
  }
  // 3. Plain least squares on the inliers.
  if (!solveCeres(problem, kept, nullptr, x, fit.message)) return fit;
  // 4. Covariance σ²(JᵀJ)⁻¹ from the analytic Jacobian at the optimum.
  Eigen::MatrixXd JtJ = Eigen::MatrixXd::Zero(p, p);
  double ssr = 0.0;
  std::array<double, kMaxParameters> g{};
  for (const std::size_t i : kept) {
    double ri = 0.0;
    if (!problem.residual(i, x.data(), ri, g.data())) {
      fit.message = "the solution lies outside the model's domain";
      return fit;
    }
    ssr += ri * ri;
    for (int a = 0; a < p; ++a) {
      for (int c = 0; c <= a; ++c) JtJ(a, c) += g[a] * g[c];
    }
  }
  JtJ = JtJ.selfadjointView<Eigen::Lower>();
  Eigen::MatrixXd JtJ_inv;
  if (!invertNormal(JtJ, JtJ_inv)) {
    fit.message = kSingular;
    return fit;
  }
  const double dof = static_cast<double>(kept.size() - static_cast<std::size_t>(p));
  fit.x = x;
  fit.covariance = ssr / dof / truncatedVariance(k) * JtJ_inv;
  fit.stats.residual_rms = std::sqrt(ssr / static_cast<double>(kept.size()));
  fit.ok = true;
  return fit;
}

}  // namespace geaware::ident
