// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/ident/voltage_fit.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Dense>

namespace geaware::ident {
namespace {

/// The samples of one fit: regressors φ = (t², t, 1), ln(V/V_ref), n², weights 1/n².
struct Samples {
  Eigen::MatrixXd phi;
  Eigen::VectorXd log_ratio;
  Eigen::VectorXd n2;
  Eigen::VectorXd sqrt_w;
};

/// The coefficients at exponent p and the weighted residual sum of squares.
double coefficientsAt(const Samples& s, double p, Eigen::Vector3d& c) {
  const Eigen::VectorXd scale = (2.0 * p * s.log_ratio.array()).exp();
  const Eigen::MatrixXd A = (s.phi.array().colwise() * (scale.array() * s.sqrt_w.array())).matrix();
  const Eigen::VectorXd b = (s.n2.array() * s.sqrt_w.array()).matrix();
  c = A.colPivHouseholderQr().solve(b);
  return (A * c - b).squaredNorm();
}

}  // namespace

ThrottleVoltageFit fitThrottleVoltage(const std::vector<double>& throttle,
                                      const std::vector<double>& n_rpm,
                                      const std::vector<double>& voltage_V,
                                      const std::vector<char>& use, double reference_voltage_V) {
  ThrottleVoltageFit out;
  LeastSquaresFit& f = out.fit;
  std::vector<std::size_t> idx;
  std::vector<double> volts;
  for (std::size_t i = 0; i < use.size(); ++i) {
    if (use[i] != 0 && voltage_V[i] > 0.0 && std::isfinite(voltage_V[i]) && n_rpm[i] > 0.0) {
      idx.push_back(i);
      volts.push_back(voltage_V[i]);
    }
  }
  if (idx.size() < 8) {
    f.message = "only " + std::to_string(idx.size()) + " samples with a voltage > 0 (8 needed)";
    return out;
  }
  std::sort(volts.begin(), volts.end());
  const double v_ref = reference_voltage_V > 0.0 ? reference_voltage_V : volts[volts.size() / 2];
  out.reference_voltage_V = v_ref;
  if (volts.back() / volts.front() < 1.02) {
    f.message = "the battery voltage varies by only " +
                std::to_string(100.0 * (volts.back() / volts.front() - 1.0)) +
                " % in the log: its influence cannot be separated (log a discharge or a supply sweep)";
    return out;
  }
  const auto m = static_cast<Eigen::Index>(idx.size());
  Samples s{Eigen::MatrixXd(m, 3), Eigen::VectorXd(m), Eigen::VectorXd(m), Eigen::VectorXd(m)};
  for (Eigen::Index k = 0; k < m; ++k) {
    const std::size_t i = idx[static_cast<std::size_t>(k)];
    const double t = throttle[i];
    s.phi.row(k) << t * t, t, 1.0;
    s.log_ratio(k) = std::log(voltage_V[i] / v_ref);
    s.n2(k) = n_rpm[i] * n_rpm[i];
    s.sqrt_w(k) = 1.0 / n_rpm[i];
  }
  // Golden section on p ∈ [0, 4] (the vehicle file's range).
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = 0.0, b = 4.0;
  Eigen::Vector3d c;
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = coefficientsAt(s, x1, c), f2 = coefficientsAt(s, x2, c);
  for (int it = 0; it < 80 && b - a > 1e-10; ++it) {
    if (f1 < f2) {
      b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = coefficientsAt(s, x1, c);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = coefficientsAt(s, x2, c);
    }
  }
  const double p = 0.5 * (a + b);
  const double rss = coefficientsAt(s, p, c);
  // Jacobian of the weighted model in (c2, c1, c0, p) at the optimum.
  const Eigen::ArrayXd scale = (2.0 * p * s.log_ratio.array()).exp();
  Eigen::MatrixXd J(m, 4);
  J.leftCols(3) = (s.phi.array().colwise() * (scale * s.sqrt_w.array())).matrix();
  J.col(3) = ((s.phi * c).array() * scale * 2.0 * s.log_ratio.array() * s.sqrt_w.array()).matrix();
  // Columns scaled to unit norm first: coefficients of 1e8 rpm² and an exponent of order 1 make
  // JᵀJ span many decades that carry no information about its conditioning.
  const Eigen::Vector4d norms = J.colwise().norm().transpose();
  if (!(norms.minCoeff() > 0.0)) {
    f.message = "the design in (c2, c1, c0, p) has an empty column";
    return out;
  }
  const Eigen::MatrixXd Js = J * norms.cwiseInverse().asDiagonal();
  const Eigen::Matrix4d JtJ = Js.transpose() * Js;
  Eigen::FullPivLU<Eigen::Matrix4d> lu(JtJ);
  lu.setThreshold(1e-12);
  if (!lu.isInvertible()) {
    f.message = "the design in (c2, c1, c0, p) is singular: does the log cover the throttle range?";
    return out;
  }
  const double sigma2 = rss / static_cast<double>(m - 4);
  f.x = Eigen::VectorXd(4);
  f.x << c(0), c(1), c(2), p;
  const Eigen::Matrix4d inv_norms = norms.cwiseInverse().asDiagonal();
  f.covariance = sigma2 * inv_norms * lu.inverse() * inv_norms;
  f.stats.residual_rms = std::sqrt(rss / static_cast<double>(m));
  f.stats.count = idx.size();
  f.ok = true;
  if (p <= 1e-6 || p >= 4.0 - 1e-6) {
    f.message = "the exponent p is at the bound of [0, 4]";
  }
  return out;
}

}  // namespace geaware::ident
