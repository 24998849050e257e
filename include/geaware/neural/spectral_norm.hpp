// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Spectral norm of a weight matrix: exact (SVD) for certificates and tests, and the power
// iteration of spectral normalisation (Miyato et al. 2018, used by Shi et al. 2019 §IV-B) for
// the cheap per-step estimate during training.

#include <Eigen/Core>
#include <Eigen/SVD>
#include <cmath>

namespace geaware::neural {

/// Relative slack on ∏σ_max(W_l) ≤ γ: the exact projection leaves a few ulps of rounding.
inline constexpr double kLipschitzTolerance = 1e-6;

/// Largest singular value σ_max(W), exact (Jacobi SVD). 0 for an empty matrix.
template <typename Derived>
[[nodiscard]] double spectralNorm(const Eigen::MatrixBase<Derived>& w) {
  if (w.size() == 0) return 0.0;
  const Eigen::MatrixXd wd = w.template cast<double>();
  return Eigen::JacobiSVD<Eigen::MatrixXd>(wd).singularValues()(0);
}

/// Power-iteration estimate of σ_max(W) (W: m × n). `v` (size n) is the persistent estimate of
/// the leading right singular vector: warm-started from the previous training step, one or two
/// iterations track σ_max as W changes slowly (Miyato et al. 2018, Alg. 1). The estimate
/// ‖Wᵀu‖ with ‖u‖ = 1 never exceeds σ_max: it is a lower bound, which is why the trainer ends
/// with an exact projection (see trainer.cpp).
template <typename Derived, typename Vector>
[[nodiscard]] double powerIterationNorm(const Eigen::MatrixBase<Derived>& w,
                                        Eigen::MatrixBase<Vector>& v, int iterations) {
  using Scalar = typename Derived::Scalar;
  using Col = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  if (v.size() != w.cols() || !(v.norm() > Scalar(0)) || !v.allFinite()) {
    v.derived().setConstant(w.cols(), Scalar(1) / std::sqrt(static_cast<Scalar>(w.cols())));
  }
  double sigma = 0.0;
  for (int i = 0; i < iterations; ++i) {
    Col u = w * v;  // 1. u ← W v / ‖W v‖
    const Scalar nu = u.norm();
    if (!(nu > Scalar(0))) return 0.0;  // v in the null space: W v = 0 (e.g. W = 0)
    u /= nu;
    Col wt_u = w.transpose() * u;  // 2. v ← Wᵀu / ‖Wᵀu‖, σ ≈ ‖Wᵀu‖
    const Scalar nv = wt_u.norm();
    if (!(nv > Scalar(0))) return 0.0;
    v = wt_u / nv;
    sigma = static_cast<double>(nv);
  }
  return sigma;
}

}  // namespace geaware::neural
