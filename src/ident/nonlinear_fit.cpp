// SPDX-License-Identifier: BSD-3-Clause
// The nonlinear solver of least_squares.hpp: Ceres with the robust scheme and the uncertainty
// of the linear one (least_squares.cpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include <ceres/ceres.h>

#include "geaware/ident/least_squares.hpp"
#include "least_squares_support.hpp"

namespace geaware::ident {

using detail::invertNormal;
using detail::kMaxParameters;
using detail::kSingular;
using detail::knownVarianceFactor;
using detail::truncatedVariance;

// --------------------------------------------------------------------------------- nonlinear

namespace {

/// A block of samples as one Ceres residual block (one block per sample costs Ceres far more
/// than the model). Because a Ceres LossFunction acts on a whole block, the robust loss is
/// applied here, per sample, as the residual √ρ(r²)·sign(r) whose square is ρ(r²); its
/// Gauss–Newton Jacobian is ρ'·|r|/√ρ·∂r/∂x.
class SampleBlock final : public ceres::CostFunction {
 public:
  /// `huber_a` > 0: `loss` is ceres::HuberLoss(huber_a), evaluated here inline (below).
  SampleBlock(const NonlinearProblem& problem, const std::size_t* indices, std::size_t count,
              const ceres::LossFunction* loss, double huber_a)
      : problem_(problem), indices_(indices), count_(count), loss_(loss), huber_a_(huber_a) {
    set_num_residuals(static_cast<int>(count));
    mutable_parameter_block_sizes()->push_back(problem.parameters);
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const int p = problem_.parameters;
    std::array<double, kMaxParameters> x{};
    for (int k = 0; k < p; ++k) x[k] = parameters[0][k] * problem_.scales[k];
    double* J = jacobians != nullptr ? jacobians[0] : nullptr;
    // With a block residual: all residuals (and gradients, in J's row-major layout) in one call,
    // then each scaled below exactly as the per-sample path scales its own.
    const bool block = static_cast<bool>(problem_.block);
    if (block && !problem_.block(indices_, count_, x.data(), residuals, J)) return false;
    std::array<double, kMaxParameters> g{};
    for (std::size_t j = 0; j < count_; ++j) {
      double r = 0.0;
      if (block) {
        r = residuals[j];
        if (J != nullptr) std::copy_n(J + j * static_cast<std::size_t>(p), p, g.data());
      } else if (!problem_.residual(indices_[j], x.data(), r, J != nullptr ? g.data() : nullptr)) {
        return false;
      }
      double d = 1.0;
      if (loss_ != nullptr) {
        double rho[3];
        if (huber_a_ > 0.0) {
          huber(r * r, rho);
        } else {
          loss_->Evaluate(r * r, rho);
        }
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
  double huber_a_;

  // ρ and ρ' of ceres::HuberLoss(huber_a_) (Ceres 2.1, loss_function.cc), the same operations,
  // without the virtual call per sample and the ρ'' this block never uses.
  void huber(double s, double rho[3]) const {
    const double b = huber_a_ * huber_a_;
    if (s > b) {
      const double r = std::sqrt(s);
      rho[0] = 2.0 * huber_a_ * r - b;
      rho[1] = std::max(std::numeric_limits<double>::min(), huber_a_ / r);
    } else {
      rho[0] = s;
      rho[1] = 1.0;
    }
    rho[2] = 0.0;
  }
};

constexpr std::size_t kBlockSamples = 2048;

/// Least squares of the samples `indices` from x (in place), with an optional loss.
bool solveCeres(const NonlinearProblem& problem, const std::vector<std::size_t>& indices,
                const ceres::LossFunction* loss, double huber_a, Eigen::VectorXd& x, std::string& message) {
  const int p = problem.parameters;
  std::vector<double> xs(static_cast<std::size_t>(p));
  for (int k = 0; k < p; ++k) xs[k] = x(k) / problem.scales[k];
  ceres::Problem cp;
  for (std::size_t start = 0; start < indices.size(); start += kBlockSamples) {
    const std::size_t count = std::min(kBlockSamples, indices.size() - start);
    cp.AddResidualBlock(new SampleBlock(problem, indices.data() + start, count, loss, huber_a), nullptr,
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
  const bool known = robust.known_variances;
  if (problem.samples < static_cast<std::size_t>(p) + (known ? 0 : 1)) {
    fit.message = "too few samples: " + std::to_string(problem.samples) + " for " +
                  std::to_string(p) + " parameters";
    return fit;
  }
  std::vector<std::size_t> all(problem.samples);
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  auto residuals = [&](const Eigen::VectorXd& x, std::vector<double>& r) -> bool {
    r.resize(problem.samples);
    if (problem.block) return problem.block(all.data(), all.size(), x.data(), r.data(), nullptr);
    for (std::size_t i = 0; i < problem.samples; ++i) {
      if (!problem.residual(i, x.data(), r[i], nullptr)) return false;
    }
    return true;
  };

  Eigen::VectorXd x = x0;
  std::vector<double> r;
  const double floor = problem.scale_floor;
  RobustScale robust_scale;
  auto scale = [&] { return std::max(robust_scale.sigma(r), floor); };
  if (!residuals(x, r)) {
    fit.message = "the initial guess lies outside the model's domain";
    return fit;
  }
  // 1. Robust fit; the loss threshold follows the residual scale: set from the initial guess,
  //    and once more from the robust solution if the scale changed by more than 20 %.
  if (robust.loss != RobustLoss::kNone && !known) {
    double previous_s = 0.0;
    for (int round = 0; round < 2; ++round) {
      const double s = scale();
      if (!(s > 0.0) || std::abs(s - previous_s) <= 0.2 * s) break;
      previous_s = s;
      const double threshold = robust.loss_scale * s;
      const auto loss = makeLoss(robust.loss, threshold);
      const double huber_a = robust.loss == RobustLoss::kHuber ? threshold : 0.0;
      if (!solveCeres(problem, all, loss.get(), huber_a, x, fit.message)) return fit;
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
  const double s = robust.outlier_sigmas > 0.0 && !known ? scale() : 0.0;
  if (s > 0.0) k = robust.outlier_sigmas;
  for (std::size_t i = 0; i < problem.samples; ++i) {
    if (k == 0.0 || std::abs(r[i]) <= k * s) kept.push_back(i);
  }
  fit.stats.outliers = problem.samples - kept.size();
  fit.stats.count = kept.size();
  if (kept.size() < static_cast<std::size_t>(p) + (known ? 0 : 1)) {
    fit.message = "too few samples left after removing outliers";
    return fit;
  }
  // 3. Plain least squares on the inliers.
  if (!solveCeres(problem, kept, nullptr, 0.0, x, fit.message)) return fit;
  // Parameters that ended at a bound: the optimum lies outside the allowed range.
  for (int q = 0; q < p; ++q) {
    const auto i = static_cast<std::size_t>(q);
    const double tol = 1e-6 * std::abs(problem.scales[i]);
    const bool low = !problem.lower.empty() && std::isfinite(problem.lower[i]) &&
                     x(q) <= problem.lower[i] + std::max(tol, 1e-6 * std::abs(problem.lower[i]));
    const bool high = !problem.upper.empty() && std::isfinite(problem.upper[i]) &&
                      x(q) >= problem.upper[i] - std::max(tol, 1e-6 * std::abs(problem.upper[i]));
    if (low || high) fit.at_bound.push_back(q);
  }
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
  if (!invertNormal(JtJ, JtJ_inv, &fit.stats.condition_number)) {
    fit.message = kSingular;
    if (!fit.at_bound.empty()) {
      fit.message += "; parameter " + std::to_string(fit.at_bound.front() + 1) +
                     " ended at a bound of the fit, where the others lose their effect";
    }
    return fit;
  }
  const double dof = static_cast<double>(kept.size() - static_cast<std::size_t>(p));
  fit.x = x;
  fit.covariance = (known ? knownVarianceFactor(ssr, dof, k) : ssr / dof / truncatedVariance(k)) * JtJ_inv;
  fit.stats.residual_rms = std::sqrt(ssr / static_cast<double>(kept.size()));
  fit.ok = true;
  return fit;
}

}  // namespace geaware::ident
