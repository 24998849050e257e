// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/ident/platform_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "fit_support.hpp"
#include "least_squares_support.hpp"
#include "geaware/model/mixer.hpp"

namespace geaware::ident {

using detail::num;

namespace {

double sumSquares(const PlatformLog& log, std::size_t i) {
  double s = 0.0;
  for (const auto& n : log.n_rpm) s += n[i] * n[i];
  return s;
}

/// A·N² rows 2–4 of the mixer (eq. 2): roll, pitch and yaw combinations of the squared speeds.
std::array<double, 3> mixingCombinations(const PlatformLog& log, std::size_t i) {
  const double n1 = log.n_rpm[0][i] * log.n_rpm[0][i];
  const double n2 = log.n_rpm[1][i] * log.n_rpm[1][i];
  const double n3 = log.n_rpm[2][i] * log.n_rpm[2][i];
  const double n4 = log.n_rpm[3][i] * log.n_rpm[3][i];
  return {-n1 + n2 + n3 - n4, -n1 + n2 - n3 + n4, -n1 - n2 + n3 + n4};
}

/// Rows that are means count as their samples (PlatformLog::count): the thresholds of the fits
/// ("at least 10 level samples") count samples, not rows.
std::vector<std::size_t> levelSamples(const PlatformLog& log, double level_tilt_deg, double* samples = nullptr) {
  std::vector<std::size_t> idx;
  idx.reserve(log.size());
  double total = 0.0;
  for (std::size_t i = 0; i < log.size(); ++i) {
    if (std::abs(log.tilt_deg[i]) > level_tilt_deg) continue;
    idx.push_back(i);
    total += log.samples(i);
  }
  if (samples != nullptr) *samples = total;
  return idx;
}

/// The robust options of a fit of f_z: its weights are known variances when the stds are given.
RobustOptions fzRobust(const PlatformLog& log, RobustOptions robust) {
  robust.known_variances = log.fzVariancesKnown();
  return robust;
}

}  // namespace

std::vector<double> measuredAdditionalThrust(const PlatformLog& log, double k_T) {
  std::vector<double> out(log.size());
  for (std::size_t i = 0; i < log.size(); ++i) {
    const double T = k_T * sumSquares(log, i);
    out[i] = T > 0.0 ? log.f_N[2][i] / T - 1.0 : kNaN;
  }
  return out;
}

double additionalThrustStdError(const AdditionalThrustFit& fit, double h) {
  const double g1 = fit.g1_m2.value;
  const double g2 = fit.g2_m2.value;
  const double d = h * h + g1;
  const Eigen::Vector3d grad(0.0, -g2 / (d * d), 1.0 / d);  // ∂F_G/∂(k_T, g1, g2)
  return std::sqrt(grad.dot(fit.covariance * grad));
}

namespace detail {

AdditionalThrustFit fitThrustWithGroundEffect(const std::vector<double>& S,
                                              const std::vector<double>& h,
                                              const std::vector<double>& fz,
                                              const std::vector<double>& w,
                                              const RobustOptions& robust,
                                              const std::string& source, const std::string& what) {
  AdditionalThrustFit out;
  out.h_min_m = *std::min_element(h.begin(), h.end());
  out.h_max_m = *std::max_element(h.begin(), h.end());
  std::vector<double> h2(h.size());
  std::vector<double> sw(h.size(), 1.0);  // √w
  std::vector<double> swfz(h.size());     // √w·f_z, for the robust scale's floor
  for (std::size_t j = 0; j < h.size(); ++j) {
    h2[j] = h[j] * h[j];
    if (!w.empty()) sw[j] = std::sqrt(w[j]);
    swfz[j] = sw[j] * fz[j];
  }
  // Initial guess by variable projection: for a fixed g1 the model is linear in k_T and
  // k_T·g2, so scan g1 on a log grid (on at most ~20,000 samples) and keep the best.
  const std::size_t stride = std::max<std::size_t>(1, S.size() / 20000);
  double best_sse = std::numeric_limits<double>::infinity();
  Eigen::Vector3d x0(0.0, 0.02, 0.0);
  for (int k = 0; k <= 60; ++k) {
    const double g1 = 1e-4 * std::pow(10.0, k / 12.0);  // 1e-4 … 10 m²
    Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
    Eigen::Vector2d b = Eigen::Vector2d::Zero();
    double yy = 0.0;
    for (std::size_t j = 0; j < S.size(); j += stride) {
      const Eigen::Vector2d x = sw[j] * Eigen::Vector2d(S[j], S[j] / (h2[j] + g1));
      A += x * x.transpose();
      b += x * swfz[j];
      yy += swfz[j] * swfz[j];
    }
    if (!(A.determinant() > 1e-12 * A(0, 0) * A(1, 1))) continue;
    const Eigen::Vector2d beta = A.ldlt().solve(b);
    const double sse = yy - beta.dot(b);
    if (sse < best_sse && beta(0) > 0.0) {
      best_sse = sse;
      x0 = Eigen::Vector3d(beta(0), g1, std::max(beta(1) / beta(0), 1e-6));
    }
  }
  if (!(x0(0) > 0.0)) {
    throw IdentError(source + ": cannot fit F_G: the thrust does not grow with Σn² "
                                  "(are the rotor speeds or the force columns right?)");
  }

  NonlinearProblem problem;
  problem.samples = S.size();
  problem.parameters = 3;
  const auto residual = [&](std::size_t j, const double* x, double& r, double* g) {
    if (!(x[1] > 0.0)) return false;
    const double d = h2[j] + x[1];
    const double F = x[2] / d;
    const double s = sw[j] * S[j];
    r = swfz[j] - x[0] * s * (1.0 + F);
    if (g != nullptr) {
      g[0] = -s * (1.0 + F);
      g[1] = x[0] * s * x[2] / (d * d);
      g[2] = -x[0] * s / d;
    }
    return true;
  };
  problem.residual = residual;
  problem.block = blockResidual(residual, problem.parameters);
  problem.scale_floor = scaleFloor(swfz);
  problem.scales = {x0(0), std::max(x0(1), 1e-4), std::max(x0(2), 1e-4)};
  problem.lower = {0.0, 1e-9, 0.0};
  problem.upper = {std::numeric_limits<double>::infinity(), 100.0, 100.0};
  const auto fit = fitNonlinear(problem, x0, robust);
  detail::require(fit, source, what);
  detail::blockAtBounds(out.blocking, fit, problem, {"k_T", "g1", "g2"}, "fit of " + what);
  out.k_T_N_per_rpm2 = fit.estimate(0);
  out.g1_m2 = fit.estimate(1);
  out.g2_m2 = fit.estimate(2);
  out.covariance = fit.covariance;
  out.stats = fit.stats;
  return out;
}

}  // namespace detail

AdditionalThrustFit fitAdditionalThrust(const PlatformLog& log, const PlatformFitOptions& options) {
  double level = 0.0;
  const std::vector<std::size_t> idx = levelSamples(log, options.level_tilt_deg, &level);
  if (level < 10.0 || idx.size() < 3) {
    throw IdentError(log.source + ": cannot fit F_G: only " + num(level) +
                     " samples with a level board (|tilt| ≤ " + num(options.level_tilt_deg) +
                     "°), at least 10 are needed");
  }
  // Per sample: Σn², h, f_z.
  std::vector<double> S(idx.size());
  std::vector<double> h(idx.size());
  std::vector<double> fz(idx.size());
  std::vector<double> w(idx.size());
  for (std::size_t j = 0; j < idx.size(); ++j) {
    S[j] = sumSquares(log, idx[j]);
    h[j] = log.h_m[idx[j]];
    fz[j] = log.f_N[2][idx[j]];
    w[j] = log.fzWeight(idx[j]);
  }
  AdditionalThrustFit out = detail::fitThrustWithGroundEffect(
      S, h, fz, w, fzRobust(log, options.robust), log.source, "k_T, g1, g2 (F_G(h) = g2/(h² + g1) on the level board)");
  detail::warnCurveFit(out.warnings, out.blocking, "F_G fit", {{"g1", &out.g1_m2}, {"g2", &out.g2_m2}},
                       out.h_min_m, out.h_max_m,
                       "log heights from the lowest flyable to well out of ground effect", out.stats);
  return out;
}

AdditionalThrustTableFit fitAdditionalThrustTable(const PlatformLog& log,
                                                  const PlatformFitOptions& options) {
  AdditionalThrustTableFit out;
  const std::string what = "F_G as a table";
  double level = 0.0;
  const std::vector<std::size_t> idx = levelSamples(log, options.level_tilt_deg, &level);
  if (level < 10.0) {
    throw IdentError(log.source + ": cannot fit " + what + ": only " + num(level) +
                     " samples with a level board (|tilt| ≤ " + num(options.level_tilt_deg) +
                     "°), at least 10 are needed");
  }
  std::vector<double> h(idx.size());
  for (std::size_t j = 0; j < idx.size(); ++j) h[j] = log.h_m[idx[j]];
  out.h_min_m = *std::min_element(h.begin(), h.end());
  out.h_max_m = *std::max_element(h.begin(), h.end());
  const std::vector<double> knots = chooseKnots(h, options.thrust_table, log.source, what);
  const std::size_t n_knots = knots.size();
  const auto samples = [&](std::size_t j) { return static_cast<std::size_t>(std::llround(log.samples(idx[j]))); };
  for (std::size_t j = 0; j < h.size(); ++j) out.tail_samples += h[j] > knots.back() ? samples(j) : 0;
  if (out.tail_samples == 0) {
    throw IdentError(log.source + ": cannot fit " + what + ": no level sample lies above the top " +
                     "knot (" + num(knots.back()) + " m). Only there, where F_G follows its 1/h² " +
                     "tail, can k_T be told apart from F_G: log heights above it, or set the top " +
                     "knot lower");
  }
  // Parameters (k_T, k_T·F_0, …, k_T·F_{N−1}): f̃_z = k_T·S + Σ_j (k_T·F_j)·S·φ_j(h).
  out.F_G.samples.assign(n_knots, 0);
  for (std::size_t j = 0; j < h.size(); ++j) {
    int index[2];
    double weight[2];
    const int c = tableBasis(knots, h[j], index, weight);
    for (int e = 0; e < c; ++e) out.F_G.samples[static_cast<std::size_t>(index[e])] += samples(j);
  }
  const auto fit = fitSparseLinear(
      idx.size(), static_cast<int>(n_knots) + 1,
      [&](std::size_t j, int* index, double* value, int& count, double& y, double& w) {
        const double S = sumSquares(log, idx[j]);
        int k[2];
        double phi[2];
        const int c = tableBasis(knots, h[j], k, phi);
        index[0] = 0;
        value[0] = S;
        for (int e = 0; e < c; ++e) {
          index[e + 1] = k[e] + 1;
          value[e + 1] = S * phi[e];
        }
        count = c + 1;
        y = log.f_N[2][idx[j]];
        w = log.fzWeight(idx[j]);
        return S > 0.0;
      },
      fzRobust(log, options.robust));
  detail::require(fit, log.source, "k_T and " + what + " (" + std::to_string(n_knots) + " knots)");
  // F_j = b_j/k_T, covariance by the delta method.
  const double a = fit.x(0);
  const auto p = static_cast<Eigen::Index>(n_knots + 1);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(p, p);
  J(0, 0) = 1.0;
  for (Eigen::Index j = 1; j < p; ++j) {
    J(j, 0) = -fit.x(j) / (a * a);
    J(j, j) = 1.0 / a;
  }
  const Eigen::MatrixXd C = J * fit.covariance * J.transpose();
  out.k_T_N_per_rpm2 = {a, std::sqrt(C(0, 0))};
  out.F_G.heights_m = knots;
  out.F_G.covariance = C.bottomRightCorner(p - 1, p - 1);
  for (Eigen::Index j = 1; j < p; ++j) out.F_G.values.push_back({fit.x(j) / a, std::sqrt(C(j, j))});
  out.stats = fit.stats;
  detail::warnIfImprecise(out.warnings, "k_T", out.k_T_N_per_rpm2,
                          "log more heights above " + num(knots.back()) + " m");
  detail::warnSparseKnots(out.warnings, what, out.F_G);
  detail::warnIfManyOutliers(out.warnings, what + " fit", out.stats);
  return out;
}

ThrustAloneFit fitThrustAlone(const PlatformLog& log, const PlatformFitOptions& options) {
  ThrustAloneFit out;
  double level = 0.0;
  const std::vector<std::size_t> idx = levelSamples(log, options.level_tilt_deg, &level);
  if (level < 2.0 || idx.empty()) {
    throw IdentError(log.source + ": cannot fit k_T: only " + num(level) + " samples with a level board (|tilt| ≤ " +
                     num(options.level_tilt_deg) + "°)");
  }
  const auto fit = fitLinear(
      idx.size(), 1,
      [&](std::size_t j, double* x, double& y, double& w) {
        x[0] = sumSquares(log, idx[j]);
        y = log.f_N[2][idx[j]];
        w = log.fzWeight(idx[j]);
        return x[0] > 0.0;
      },
      fzRobust(log, options.robust));
  detail::require(fit, log.source, "k_T (f_z = k_T·Σn², F_G taken as 0)");
  out.k_T_N_per_rpm2 = fit.estimate(0);
  out.stats = fit.stats;
  out.h_min_m = log.h_m[idx.front()];
  out.h_max_m = out.h_min_m;
  for (const std::size_t i : idx) {
    out.h_min_m = std::min(out.h_min_m, log.h_m[i]);
    out.h_max_m = std::max(out.h_max_m, log.h_m[i]);
  }
  detail::warnIfImprecise(out.warnings, "k_T", out.k_T_N_per_rpm2, "log more samples or a wider rotor-speed range");
  detail::warnIfManyOutliers(out.warnings, "k_T fit", out.stats);
  return out;
}

MixingFit fitMixing(const PlatformLog& log, double b, const PlatformFitOptions& options) {
  MixingFit out;
  const double arm = model::mixerArm_m(b);
  double level = 0.0;
  const std::vector<std::size_t> idx = levelSamples(log, options.level_tilt_deg, &level);
  if (level < 10.0) {
    throw IdentError(log.source + ": cannot fit the mixing coefficients: only " + num(level) +
                     " samples with a level board");
  }
  // Regressors of the four coefficients per level sample: thrust Σn² (k_T), roll and pitch
  // arm·(A·N²) (k_TX, k_TY), yaw A·N² (k_I); and the measured f_z, τ_x, τ_y, τ_z; the weights
  // of f_z (1/σ² when the stds are given) and of the torques (the samples behind the row). As
  // columns, which the fits take as they are.
  struct Columns {
    std::array<std::vector<double>, 4> x;
    std::array<std::vector<double>, 4> y;
    std::vector<double> w_fz;
    std::vector<double> w_tau;
    [[nodiscard]] std::array<std::vector<double>*, 10> all() { return {&x[0], &x[1], &x[2], &x[3], &y[0], &y[1], &y[2], &y[3], &w_fz, &w_tau}; }
  };
  Columns cols;
  for (auto* c : cols.all()) c->resize(idx.size());
  for (std::size_t j = 0; j < idx.size(); ++j) {
    const std::size_t i = idx[j];
    const auto c = mixingCombinations(log, i);
    cols.x[0][j] = sumSquares(log, i);
    cols.x[1][j] = arm * c[0];
    cols.x[2][j] = arm * c[1];
    cols.x[3][j] = c[2];
    cols.y[0][j] = log.f_N[2][i];
    cols.y[1][j] = log.tau_Nm[0][i];
    cols.y[2][j] = log.tau_Nm[1][i];
    cols.y[3][j] = log.tau_Nm[2][i];
    cols.w_fz[j] = log.fzWeight(i);
    cols.w_tau[j] = log.samples(i);
  }
  // One-coefficient fit of column `k` on the rows [first, last).
  auto fitOne = [&](int k, std::size_t first, std::size_t last, FitStats* stats) -> std::optional<Estimate> {
    const auto rows = [&](const std::vector<double>& v) { return std::span<const double>(v).subspan(first, last - first); };
    const auto c = static_cast<std::size_t>(k);
    const auto ls = detail::fitLinearColumns(rows(cols.x[c]), rows(cols.y[c]), rows(k == 0 ? cols.w_fz : cols.w_tau),
                                             k == 0 ? fzRobust(log, options.robust) : options.robust);
    if (!ls.ok) return std::nullopt;
    if (stats != nullptr) *stats = ls.stats;
    return ls.estimate(0);
  };

  static constexpr std::array<const char*, 3> kName = {"k_TX", "k_TY", "k_I"};
  static constexpr std::array<const char*, 3> kPattern = {
      "roll: −n1²+n2²+n3²−n4²", "pitch: −n1²+n2²−n3²+n4²", "yaw: −n1²−n2²+n3²+n4²"};
  std::array<std::optional<Estimate>*, 3> targets = {&out.k_TX_N_per_rpm2, &out.k_TY_N_per_rpm2,
                                                     &out.k_I_Nm_per_rpm2};
  std::array<FitStats*, 3> stats = {&out.roll, &out.pitch, &out.yaw};
  for (int k = 0; k < 3; ++k) {
    *targets[static_cast<std::size_t>(k)] = fitOne(k + 1, 0, idx.size(), stats[static_cast<std::size_t>(k)]);
    if (!*targets[static_cast<std::size_t>(k)]) {
      out.warnings.push_back(std::string(kName[static_cast<std::size_t>(k)]) +
                             " not fitted: the rotor speeds never differ in the " +
                             kPattern[static_cast<std::size_t>(k)] +
                             " pattern on the level board (run the mixing experiments)");
    } else {
      detail::warnIfImprecise(out.warnings, kName[static_cast<std::size_t>(k)],
                              **targets[static_cast<std::size_t>(k)],
                              "too little rotor-speed difference in the mixing experiments");
      detail::warnIfManyOutliers(out.warnings, std::string(kName[static_cast<std::size_t>(k)]) + " fit",
                                 *stats[static_cast<std::size_t>(k)]);
    }
  }

  // Height bands of equal sample count; samples at one height never straddle two bands. The
  // columns are put into height order once, so that each band's rows are contiguous.
  std::vector<double> level_h(idx.size());
  for (std::size_t j = 0; j < idx.size(); ++j) level_h[j] = log.h_m[idx[j]];
  std::vector<std::size_t> order(idx.size());
  for (std::size_t j = 0; j < order.size(); ++j) order[j] = j;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t c) { return level_h[a] < level_h[c]; });
  std::vector<double> sorted_h(order.size());
  std::vector<double> sorted_samples(order.size());
  for (std::size_t m = 0; m < order.size(); ++m) {
    sorted_h[m] = level_h[order[m]];
    sorted_samples[m] = log.samples(idx[order[m]]);
  }
  std::vector<double> sorted(order.size());
  for (auto* c : cols.all()) {
    for (std::size_t m = 0; m < order.size(); ++m) sorted[m] = (*c)[order[m]];
    c->swap(sorted);
  }
  for (const auto& [first, last] : detail::bandRanges(sorted_h, options.height_bands, sorted_samples)) {
    HeightBand hb;
    hb.h_min_m = sorted_h[first];
    hb.h_max_m = sorted_h[last - 1];
    double sum = 0.0;
    double samples = 0.0;
    for (std::size_t m = first; m < last; ++m) {
      sum += sorted_samples[m] * sorted_h[m];
      samples += sorted_samples[m];
    }
    hb.count = static_cast<std::size_t>(std::llround(samples));
    hb.h_mean_m = sum / samples;
    if (hb.count >= options.min_band_samples) {
      hb.k_T_N_per_rpm2 = fitOne(0, first, last, nullptr);
      hb.k_TX_N_per_rpm2 = fitOne(1, first, last, nullptr);
      hb.k_TY_N_per_rpm2 = fitOne(2, first, last, nullptr);
      hb.k_I_Nm_per_rpm2 = fitOne(3, first, last, nullptr);
    }
    out.bands.push_back(hb);
  }
  if (out.bands.empty() || !out.bands.back().k_T_N_per_rpm2) {
    throw IdentError(log.source + ": cannot fit k_T in the top height band (too few samples)");
  }
  out.k_T_top_N_per_rpm2 = *out.bands.back().k_T_N_per_rpm2;
  if (out.bands.size() < 2) {
    out.warnings.push_back("all level samples are at one height: no per-height coefficients");
  }
  return out;
}

}  // namespace geaware::ident
