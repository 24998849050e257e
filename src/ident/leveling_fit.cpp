// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/ident/leveling_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "fit_support.hpp"
#include "geaware/model/mixer.hpp"
#include "geaware/model/units.hpp"

namespace geaware::ident {

using detail::num;

namespace {

/// The denominator h² + g3·h + g4 stays positive for every h ≥ 0 (docs/vehicle-file.md).
bool validShape(double g3, double g4) { return g4 > 0.0 && (g3 >= 0.0 || g3 * g3 < 4.0 * g4); }

}  // namespace

double levelingCoefficient(double g3, double g4, double scale, double h) {
  const double d = h * h + g3 * h + g4;
  return scale * h / (d * d);
}

double levelingCoefficientStdError(const LevelingFit& fit, double h) {
  const double g3 = fit.g3_m.value;
  const double g4 = fit.g4_m2.value;
  const double s = fit.scale_m4.value;
  const double d = h * h + g3 * h + g4;
  const double d3 = d * d * d;
  const Eigen::Vector3d grad(-2.0 * s * h * h / d3, -2.0 * s * h / d3, h / (d * d));
  return std::sqrt(grad.dot(fit.covariance * grad));
}

namespace {

/// The tilted samples a leveling fit uses: h, u = s·T·sin δ and τ_G,y = τ_y − τ_B,y.
struct TiltedSamples {
  std::vector<double> h;
  std::vector<double> u;
  std::vector<double> y;
  std::vector<double> w;  ///< samples behind each (PlatformLog::count; 1 without a count)
  double samples = 0.0;   ///< Σ w
  double h_min_m = std::numeric_limits<double>::infinity();
  double h_max_m = -std::numeric_limits<double>::infinity();
  double tilt_min_deg = std::numeric_limits<double>::infinity();
  double tilt_max_deg = -std::numeric_limits<double>::infinity();
  std::size_t beyond = 0;  ///< samples left out above the tilt limit
};

/// One tilted-board sample of y_Wᵀτ_G = s·M_G(h)·T·sin δ: u = s·T·sin δ and y = τ_G, the
/// measured torque minus the rotors' own τ_B (eq. 2, pitch row with k_TY).
struct TiltedSample {
  double u = 0.0;
  double y = 0.0;
};

TiltedSample tiltedSample(const PlatformLog& log, std::size_t i, double arm,
                          const LevelingInputs& in, double torque_sign) {
  double S = 0.0;
  std::array<double, 4> n2{};
  for (std::size_t k = 0; k < 4; ++k) {
    n2[k] = log.n_rpm[k][i] * log.n_rpm[k][i];
    S += n2[k];
  }
  const double tau_B = arm * in.k_TY_N_per_rpm2 * (-n2[0] + n2[1] - n2[2] + n2[3]);
  return {torque_sign * in.k_T_N_per_rpm2 * S * std::sin(log.tilt_deg[i] * model::kDegToRad),
          log.tau_Nm[1][i] - tau_B};
}

TiltedSamples tiltedSamples(const PlatformLog& log, const LevelingInputs& in,
                            const LevelingFitOptions& options) {
  if (!(in.k_T_N_per_rpm2 > 0.0) || !(in.k_TY_N_per_rpm2 > 0.0) ||
      !(in.diagonal_rotor_distance_m > 0.0)) {
    throw std::invalid_argument("fitLeveling: k_T, k_TY and b must be positive");
  }
  const double arm = model::mixerArm_m(in.diagonal_rotor_distance_m);
  TiltedSamples t;
  for (std::size_t i = 0; i < log.size(); ++i) {
    const double tilt = std::abs(log.tilt_deg[i]);
    if (tilt <= options.level_tilt_deg) continue;
    if (tilt > options.max_tilt_deg) {
      ++t.beyond;
      continue;
    }
    const TiltedSample sample = tiltedSample(log, i, arm, in, options.torque_sign);
    t.h.push_back(log.h_m[i]);
    t.u.push_back(sample.u);
    t.y.push_back(sample.y);
    t.w.push_back(log.samples(i));
    t.samples += log.samples(i);
    t.h_min_m = std::min(t.h_min_m, log.h_m[i]);
    t.h_max_m = std::max(t.h_max_m, log.h_m[i]);
    t.tilt_min_deg = std::min(t.tilt_min_deg, tilt);
    t.tilt_max_deg = std::max(t.tilt_max_deg, tilt);
  }
  if (t.samples < 10.0) {  // rows that are means count as their samples
    throw IdentError(log.source + ": cannot fit the leveling torque: only " +
                     num(t.samples) + " samples with a tilted board (" +
                     num(options.level_tilt_deg) + "° < |tilt| ≤ " + num(options.max_tilt_deg) +
                     "°; " + std::to_string(t.beyond) + " more beyond the tilt limit)");
  }
  return t;
}

std::string beyondWarning(std::size_t beyond, const LevelingFitOptions& options) {
  return std::to_string(beyond) + " samples with |tilt| > " + num(options.max_tilt_deg) +
         "° were left out (the torque saturates)";
}

}  // namespace

LevelingFit fitLeveling(const PlatformLog& log, const LevelingInputs& in,
                        const LevelingFitOptions& options) {
  LevelingFit out;
  const TiltedSamples t = tiltedSamples(log, in, options);
  const std::vector<double>& h = t.h;
  const std::vector<double>& u = t.u;
  const std::vector<double>& y = t.y;
  // Rows that are means weigh as their count: √w on each residual (the fit of the log expanded
  // to its counts; w = 1 leaves every number as it was).
  std::vector<double> sw(t.w.size());
  for (std::size_t j = 0; j < sw.size(); ++j) sw[j] = std::sqrt(t.w[j]);
  out.h_min_m = t.h_min_m;
  out.h_max_m = t.h_max_m;
  out.tilt_min_deg = t.tilt_min_deg;
  out.tilt_max_deg = t.tilt_max_deg;
  const std::size_t beyond = t.beyond;

  // Initial guess by variable projection: for a fixed shape (g3, g4) the scale is linear;
  // scan the valid shapes on a grid (on at most ~20,000 samples) and keep the best. The
  // samples are gathered once into contiguous arrays, Σw·y² (the same for every shape) is
  // summed once, and each shape's regressors are computed before its sums: the same numbers,
  // summed in the same order.
  const std::size_t stride = std::max<std::size_t>(1, h.size() / 20000);
  std::vector<double> hs;
  std::vector<double> us;
  std::vector<double> ws;
  std::vector<double> ys;
  for (std::size_t j = 0; j < h.size(); j += stride) {
    hs.push_back(h[j]);
    us.push_back(u[j]);
    ws.push_back(t.w[j]);
    ys.push_back(y[j]);
  }
  double syy = 0.0;
  for (std::size_t j = 0; j < hs.size(); ++j) syy += ws[j] * ys[j] * ys[j];
  std::vector<double> xs(hs.size());
  double best_sse = std::numeric_limits<double>::infinity();
  Eigen::Vector3d x0(0.0, 0.0, 0.0);
  bool any_positive = false;
  for (int a = 0; a <= 40; ++a) {
    const double g3 = -1.0 + 0.05 * a;
    for (int c = 0; c <= 36; ++c) {
      const double g4 = 1e-3 * std::pow(10.0, c / 12.0);  // 1e-3 … 1 m²
      if (!validShape(g3, g4)) continue;
      for (std::size_t j = 0; j < hs.size(); ++j) xs[j] = levelingCoefficient(g3, g4, 1.0, hs[j]) * us[j];
      double sxx = 0.0;
      double sxy = 0.0;
      for (std::size_t j = 0; j < hs.size(); ++j) {
        sxx += ws[j] * xs[j] * xs[j];
        sxy += ws[j] * xs[j] * ys[j];
      }
      if (!(sxx > 0.0)) continue;
      const double scale = sxy / sxx;
      if (!(scale > 0.0)) continue;
      any_positive = true;
      const double sse = syy - scale * sxy;
      if (sse < best_sse) {
        best_sse = sse;
        x0 = Eigen::Vector3d(g3, g4, scale);
      }
    }
  }
  if (!any_positive) {
    throw IdentError(log.source + ": cannot fit the leveling torque: the measured y torque has "
                     "the wrong sign for a leveling torque with torque_sign = " +
                     num(options.torque_sign) + " (check the tilt or torque sign convention)");
  }

  NonlinearProblem problem;
  problem.samples = h.size();
  problem.parameters = 3;
  const auto residual = [&](std::size_t j, const double* x, double& r, double* g) {
    if (!validShape(x[0], x[1])) return false;
    const double d = h[j] * h[j] + x[0] * h[j] + x[1];
    const double m = h[j] / (d * d);
    r = sw[j] * (y[j] - x[2] * m * u[j]);
    if (g != nullptr) {
      g[0] = sw[j] * (2.0 * x[2] * m * u[j] * h[j] / d);
      g[1] = sw[j] * (2.0 * x[2] * m * u[j] / d);
      g[2] = sw[j] * (-m * u[j]);
    }
    return true;
  };
  problem.residual = residual;
  problem.block = blockResidual(residual, problem.parameters);
  problem.scales = {std::max(std::abs(x0(0)), 0.05), std::max(x0(1), 1e-3), x0(2)};
  problem.lower = {-100.0, 1e-9, 0.0};
  problem.upper = {100.0, 100.0, 100.0};
  const auto fit = fitNonlinear(problem, x0, options.robust);
  detail::require(fit, log.source, "the leveling torque M_G(h) = scale·h/(h² + g3·h + g4)²");
  detail::blockAtBounds(out.blocking, fit, problem, {"g3", "g4", "scale"}, "leveling-torque fit");
  out.g3_m = fit.estimate(0);
  out.g4_m2 = fit.estimate(1);
  out.scale_m4 = fit.estimate(2);
  out.covariance = fit.covariance;
  out.stats = fit.stats;
  const double g3 = out.g3_m.value;
  out.peak_height_m = (-g3 + std::sqrt(g3 * g3 + 12.0 * out.g4_m2.value)) / 6.0;
  detail::warnCurveFit(out.warnings, out.blocking, "leveling fit",
                       {{"g3", &out.g3_m}, {"g4", &out.g4_m2}, {"scale", &out.scale_m4}},
                       out.h_min_m, out.h_max_m, "log heights on both sides of the torque's peak",
                       out.stats);
  if (!(out.peak_height_m > out.h_min_m && out.peak_height_m < out.h_max_m)) {
    out.warnings.push_back("the fitted peak of M_G (" + num(out.peak_height_m) +
                           " m) lies outside the logged heights (" + num(out.h_min_m) + "–" +
                           num(out.h_max_m) + " m): the shape is extrapolated");
  }
  if (beyond > 0) out.warnings.push_back(beyondWarning(beyond, options));
  return out;
}

LevelingTableFit fitLevelingTable(const PlatformLog& log, const LevelingInputs& in,
                                  const LevelingFitOptions& options) {
  LevelingTableFit out;
  const TiltedSamples t = tiltedSamples(log, in, options);
  out.h_min_m = t.h_min_m;
  out.h_max_m = t.h_max_m;
  out.tilt_min_deg = t.tilt_min_deg;
  out.tilt_max_deg = t.tilt_max_deg;
  const std::string what = "the leveling torque M_G as a table";
  const std::vector<double> knots = chooseKnots(t.h, options.table, log.source, what);
  const std::size_t n_knots = knots.size();
  out.M_G.samples.assign(n_knots, 0);
  // τ_G,y = Σ_j M_j·u·φ_j(h): linear in the knot values.
  const auto fit = fitSparseLinear(
      t.h.size(), static_cast<int>(n_knots),
      [&](std::size_t j, int* index, double* value, int& count, double& y, double& w) {
        count = tableBasis(knots, t.h[j], index, value);
        for (int e = 0; e < count; ++e) {
          value[e] *= t.u[j];
          out.M_G.samples[static_cast<std::size_t>(index[e])] += static_cast<std::size_t>(std::llround(t.w[j]));
        }
        y = t.y[j];
        w = t.w[j];  // a row that is a mean weighs as its count
        return true;
      },
      options.robust);
  detail::require(fit, log.source, what + " (" + std::to_string(n_knots) + " knots)");
  out.M_G.heights_m = knots;
  out.M_G.covariance = fit.covariance;
  for (std::size_t j = 0; j < n_knots; ++j) out.M_G.values.push_back(fit.estimate(static_cast<int>(j)));
  out.stats = fit.stats;
  double peak = -std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < n_knots; ++j) {
    if (out.M_G.values[j].value > peak) {
      peak = out.M_G.values[j].value;
      out.peak_height_m = knots[j];
    }
  }
  if (!(peak > 0.0)) {
    throw IdentError(log.source + ": cannot fit " + what + ": the measured y torque has the " +
                     "wrong sign for a leveling torque with torque_sign = " +
                     num(options.torque_sign) + " (check the tilt or torque sign convention)");
  }
  detail::warnSparseKnots(out.warnings, what, out.M_G);
  detail::warnIfManyOutliers(out.warnings, "leveling table fit", out.stats);
  if (t.beyond > 0) out.warnings.push_back(beyondWarning(t.beyond, options));
  return out;
}

std::vector<double> measuredLevelingCoefficient(const PlatformLog& log, const LevelingInputs& in,
                                                const LevelingFitOptions& options) {
  const double arm = std::sqrt(2.0) * in.diagonal_rotor_distance_m / 4.0;
  std::vector<double> m(log.size(), kNaN);
  for (std::size_t i = 0; i < log.size(); ++i) {
    const double tilt = std::abs(log.tilt_deg[i]);
    if (tilt <= options.level_tilt_deg || tilt > options.max_tilt_deg) continue;
    const TiltedSample sample = tiltedSample(log, i, arm, in, options.torque_sign);
    m[i] = sample.y / sample.u;
  }
  return m;
}

}  // namespace geaware::ident
