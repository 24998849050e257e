#include "geaware/ident/flight_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <Eigen/Geometry>

#include "fit_support.hpp"

namespace geaware::ident {

using detail::num;

HoverThrustFit fitHoverAdditionalThrust(const FlightLog& log, double mass_kg, double k_T,
                                        const RobustOptions& robust) {
  HoverThrustFit out;
  if (!(mass_kg > 0.0) || !(k_T > 0.0)) {
    throw std::invalid_argument("fitHoverAdditionalThrust: mass and k_T must be positive");
  }
  const std::size_t n = log.size();
  if (log.a_ext_W[2].size() != n) throw std::invalid_argument("fitHoverAdditionalThrust: no az_ext");
  // Per sample: T̃ = k_T·Σn², h², and the external z force m·a_ext,z.
  std::vector<double> T(n);
  std::vector<double> h2(n);
  std::vector<double> f(n);
  out.h_min_m = std::numeric_limits<double>::infinity();
  out.h_max_m = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    double S = 0.0;
    for (const auto& c : log.n_rpm) S += c[i] * c[i];
    T[i] = k_T * S;
    h2[i] = log.h_m[i] * log.h_m[i];
    f[i] = mass_kg * log.a_ext_W[2][i];
    out.h_min_m = std::min(out.h_min_m, log.h_m[i]);
    out.h_max_m = std::max(out.h_max_m, log.h_m[i]);
  }
  // Initial guess: for fixed g1 the model is linear in g2; scan g1 on a log grid.
  const std::size_t stride = std::max<std::size_t>(1, n / 20000);
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector2d x0(0.02, 0.0);
  for (int k = 0; k <= 60; ++k) {
    const double g1 = 1e-4 * std::pow(10.0, k / 12.0);
    double sxx = 0.0;
    double sxy = 0.0;
    double syy = 0.0;
    for (std::size_t i = 0; i < n; i += stride) {
      const double x = T[i] / (h2[i] + g1);
      sxx += x * x;
      sxy += x * f[i];
      syy += f[i] * f[i];
    }
    if (!(sxx > 0.0)) continue;
    const double g2 = sxy / sxx;
    const double sse = syy - g2 * sxy;
    if (g2 > 0.0 && sse < best) {
      best = sse;
      x0 = Eigen::Vector2d(g1, g2);
    }
  }
  if (!(x0(1) > 0.0)) {
    throw IdentError(log.source + ": cannot fit F_G from the hover log: the external z force "
                                  "never rises towards the ground (heights " +
                     num(out.h_min_m) + "–" + num(out.h_max_m) + " m)");
  }
  NonlinearProblem problem;
  problem.samples = n;
  problem.parameters = 2;
  problem.residual = [&](std::size_t i, const double* x, double& r, double* g) {
    if (!(x[0] > 0.0)) return false;
    const double d = h2[i] + x[0];
    r = f[i] - T[i] * x[1] / d;
    if (g != nullptr) {
      g[0] = T[i] * x[1] / (d * d);
      g[1] = -T[i] / d;
    }
    return true;
  };
  problem.scales = {std::max(x0(0), 1e-4), x0(1)};
  problem.lower = {1e-9, 0.0};
  problem.upper = {100.0, 100.0};
  const auto fit = fitNonlinear(problem, x0, robust);
  detail::require(fit, log.source, "g1, g2 of F_G(h) = g2/(h² + g1) from the hover descent");
  out.g1_m2 = fit.estimate(0);
  out.g2_m2 = fit.estimate(1);
  out.covariance = fit.covariance;
  out.stats = fit.stats;
  const std::string hint = "heights " + num(out.h_min_m) + "–" + num(out.h_max_m) +
                           " m; descend from out of ground effect to the lowest height";
  detail::warnIfImprecise(out.warnings, "g1", out.g1_m2, hint);
  detail::warnIfImprecise(out.warnings, "g2", out.g2_m2, hint);
  detail::warnIfManyOutliers(out.warnings, "hover F_G fit", out.stats);
  return out;
}

DragFit fitDrag(const FlightLog& log, double mass_kg, const DragFitOptions& options) {
  DragFit out;
  const std::size_t n = log.size();
  if (log.v_W[0].size() != n || log.q_WB[0].size() != n || log.a_ext_W[0].size() != n) {
    throw std::invalid_argument("fitDrag: the log lacks velocity, attitude or a_ext columns");
  }
  // Body-frame velocity and in-plane external force per sample.
  std::vector<Eigen::Vector2d> v_B(n);
  std::vector<Eigen::Vector2d> f_B(n);
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Quaterniond q(log.q_WB[0][i], log.q_WB[1][i], log.q_WB[2][i], log.q_WB[3][i]);
    if (!(q.norm() > 0.5)) {
      throw IdentError(log.source + ":" + std::to_string(log.first_data_line + i) +
                       ": the attitude quaternion is not normalised (norm " + num(q.norm()) + ")");
    }
    const Eigen::Matrix3d R_WB = q.normalized().toRotationMatrix();
    const Eigen::Vector3d v(log.v_W[0][i], log.v_W[1][i], log.v_W[2][i]);
    const Eigen::Vector3d a(log.a_ext_W[0][i], log.a_ext_W[1][i], log.a_ext_W[2][i]);
    v_B[i] = (R_WB.transpose() * v).head<2>();
    f_B[i] = mass_kg * (R_WB.transpose() * a).head<2>();
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return log.h_m[a] < log.h_m[b]; });
  std::vector<double> sorted_h(n);
  for (std::size_t m = 0; m < n; ++m) sorted_h[m] = log.h_m[order[m]];
  for (const auto& [first, last] : detail::bandRanges(sorted_h, options.height_bands)) {
    DragBand band;
    band.count = last - first;
    band.h_min_m = sorted_h[first];
    band.h_max_m = sorted_h[last - 1];
    band.h_mean_m = std::accumulate(sorted_h.begin() + static_cast<std::ptrdiff_t>(first),
                                    sorted_h.begin() + static_cast<std::ptrdiff_t>(last), 0.0) /
                    static_cast<double>(band.count);
    const std::string where = "height band " + num(band.h_min_m) + "–" + num(band.h_max_m) + " m";
    if (band.count < options.min_band_samples) {
      out.warnings.push_back(where + ": only " + std::to_string(band.count) + " samples, not fitted");
      continue;
    }
    bool ok = true;
    for (int axis = 0; axis < 2; ++axis) {
      const auto ls = fitLinear(
          band.count, 1,
          [&](std::size_t m, double* x, double& y, double& w) {
            const std::size_t i = order[first + m];
            x[0] = -v_B[i](axis);
            y = f_B[i](axis);
            w = 1.0;
            return true;
          },
          options.robust);
      if (!ls.ok) {
        out.warnings.push_back(where + ": d_" + (axis == 0 ? "x" : "y") +
                               " not fitted (" + ls.message + "): fly faster along that axis");
        ok = false;
        break;
      }
      (axis == 0 ? band.d_x_N_per_mps : band.d_y_N_per_mps) = ls.estimate(0);
      (axis == 0 ? band.x : band.y) = ls.stats;
    }
    if (!ok) continue;
    detail::warnIfImprecise(out.warnings, where + ": d_x", band.d_x_N_per_mps,
                            "too little body-x speed");
    detail::warnIfImprecise(out.warnings, where + ": d_y", band.d_y_N_per_mps,
                            "too little body-y speed");
    out.bands.push_back(band);
  }
  if (out.bands.empty()) {
    throw IdentError(log.source + ": cannot fit the drag table: no height band could be fitted");
  }
  return out;
}

model::DragTableParams dragTable(const DragFit& fit) {
  model::DragTableParams t;
  for (const auto& b : fit.bands) {
    // Bands are disjoint and sorted, so the mean heights increase strictly.
    t.heights_m.push_back(b.h_min_m == b.h_max_m ? b.h_min_m : b.h_mean_m);
    t.d_x_N_per_mps.push_back(std::max(0.0, b.d_x_N_per_mps.value));
    t.d_y_N_per_mps.push_back(std::max(0.0, b.d_y_N_per_mps.value));
  }
  return t;
}

}  // namespace geaware::ident
