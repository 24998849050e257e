// SPDX-License-Identifier: BSD-3-Clause
// The ground effect's forward-flight fade from a flight near the ground (ident/fade_fit.hpp).

#include "geaware/ident/fade_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>

#include "fit_support.hpp"
#include "geaware/model/ground_effect.hpp"

namespace geaware::ident {

using detail::num;

namespace {

/// Fewer samples near the ground than this do not fit a fade.
constexpr std::size_t kMinNearGround = 20;

}  // namespace

ForwardFadeFit fitForwardFade(const FlightLog& log, const model::VehicleParams& base, const RobustOptions& robust) {
  const std::size_t n = log.size();
  if (log.v_W[0].size() != n || log.q_WB[0].size() != n || log.a_ext_W[2].size() != n || log.a_ext_W[0].size() != n) {
    throw std::invalid_argument("fitForwardFade: the log lacks velocity, attitude or a_ext columns");
  }
  const double m = base.mass_kg;
  const double k_T = base.rotor.k_T_N_per_rpm2;
  if (!(m > 0.0) || !(k_T > 0.0)) throw std::invalid_argument("fitForwardFade: mass and k_T must be positive");
  const model::GroundEffectModel ge(base);
  // Per sample: Σn², F_G(h), V² and the whole force along z_B, m·z_Bᵀa_ext + k_T·Σn².
  std::vector<double> S, F, V2, y;
  ForwardFadeFit out;
  for (std::size_t i = 0; i < n; ++i) {
    double s = 0.0;
    for (const auto& c : log.n_rpm) s += c[i] * c[i];
    const Eigen::Quaterniond q(log.q_WB[0][i], log.q_WB[1][i], log.q_WB[2][i], log.q_WB[3][i]);
    if (!(s > 0.0) || !(q.norm() > 0.5)) continue;
    const Eigen::Vector3d z_B = q.normalized().toRotationMatrix().col(2);
    const Eigen::Vector3d a(log.a_ext_W[0][i], log.a_ext_W[1][i], log.a_ext_W[2][i]);
    const double v2 = log.v_W[0][i] * log.v_W[0][i] + log.v_W[1][i] * log.v_W[1][i];
    const double f = ge.thrustRatio(log.h_m[i]);
    S.push_back(s);
    F.push_back(f);
    V2.push_back(v2);
    y.push_back(m * z_B.dot(a) + k_T * s);
    if (f < kFadeMinThrustRatio && v2 > 1.0) ++out.far_from_ground;
    if (f >= kFadeMinThrustRatio) {
      ++out.near_ground;
      out.max_speed_near_ground_mps = std::max(out.max_speed_near_ground_mps, std::sqrt(v2));
    }
  }
  if (out.near_ground < kMinNearGround) {
    throw IdentError(log.source + ": cannot fit the forward-flight fade: " + std::to_string(out.near_ground) +
                     " samples near the ground (F_G(h) >= " + num(kFadeMinThrustRatio) + " of the vehicle's curve), " +
                     std::to_string(kMinNearGround) + " needed: fly near the ground at two or more speeds");
  }
  NonlinearProblem problem;
  problem.samples = S.size();
  problem.parameters = 4;
  const auto residual = [&](std::size_t j, const double* x, double& r, double* g) {
    const double d = 1.0 + x[2] * V2[j];
    if (!(d > 0.0)) return false;
    const double cushion = F[j] / d;
    const double ratio = 1.0 + x[3] * V2[j] + x[1] * cushion;
    r = x[0] * S[j] * ratio - y[j];
    if (g != nullptr) {
      g[0] = S[j] * ratio;
      g[1] = x[0] * S[j] * cushion;
      g[2] = -x[0] * S[j] * x[1] * F[j] * V2[j] / (d * d);
      g[3] = x[0] * S[j] * V2[j];
    }
    return true;
  };
  problem.residual = residual;
  problem.block = blockResidual(residual, problem.parameters);
  problem.scale_floor = scaleFloor(y);
  // Start: the hover's k_T, the cushion as the vehicle's, v_i = 5 m/s (w = 0.04 s²/m²), no
  // translational lift.
  const Eigen::Vector4d x0(k_T, 1.0, 0.04, 0.0);
  problem.scales = {k_T, 1.0, 0.04, 0.002};
  problem.lower = {0.0, 0.0, 0.0, -0.1};
  problem.upper = {std::numeric_limits<double>::infinity(), 10.0, 100.0, 0.1};
  const LeastSquaresFit fit = fitNonlinear(problem, x0, robust);
  detail::require(fit, log.source, "the forward-flight fade");
  out.k_T_N_per_rpm2 = fit.estimate(0);
  out.cushion_scale = fit.estimate(1);
  out.w_s2_per_m2 = fit.estimate(2);
  out.translational_lift_per_mps2 = fit.estimate(3);
  out.stats = fit.stats;
  const double w = out.w_s2_per_m2.value;
  if (w > 0.0) {
    out.induced_velocity_mps = {1.0 / std::sqrt(w), 0.5 * out.w_s2_per_m2.std_error / (w * std::sqrt(w))};
  } else {
    out.induced_velocity_mps = {kNaN, kNaN};
  }
  const char* const names[] = {"k_T", "s", "w", "c_TL"};
  for (const int k : fit.at_bound) {
    if (k == 2 && !(w > 0.0)) {
      out.blocking.push_back("no forward-flight fade in the data: w = 1/v_i^2 ended at 0 (the cushion does not weaken "
                             "with speed up to " + num(out.max_speed_near_ground_mps) + " m/s near the ground)");
    } else if (k == 1) {
      out.blocking.push_back("the cushion scale s = " + num(out.cushion_scale.value) +
                             " ended at a bound of [0, 10]: the log shows no ground cushion to fade");
    } else if (k >= 0 && k < 4) {
      const auto i = static_cast<std::size_t>(k);
      out.blocking.push_back(std::string(names[i]) + " = " + num(fit.x(k)) + " ended at its bound (allowed [" +
                             num(problem.lower[i]) + ", " + num(problem.upper[i]) +
                             "]) in the fit of the forward-flight fade: the value is the bound, not a fit");
    }
  }
  // No fade (w = 0) is the paper's model: a fade is adopted only when the data tell it from none
  // by two standard errors.
  if (w > 0.0 && !(2.0 * out.w_s2_per_m2.std_error < w)) {
    out.blocking.push_back("v_i = " + num(out.induced_velocity_mps.value) + " m/s is not determined by the data (w = " +
                           num(w) + " ± " + num(out.w_s2_per_m2.std_error) + " s²/m², within 2 standard errors of "
                           "no fade; fly near the ground faster: the fastest sample there is " +
                           num(out.max_speed_near_ground_mps) + " m/s)");
  } else if (w > 0.0) {
    detail::warnIfImprecise(out.warnings, "v_i", out.induced_velocity_mps,
                            "fly near the ground at more speeds, up to v_i and beyond");
  }
  if (std::abs(out.cushion_scale.value - 1.0) > std::max(0.1, 3.0 * out.cushion_scale.std_error)) {
    out.warnings.push_back("the cushion in this flight is s = " + num(out.cushion_scale.value) + " ± " +
                           num(out.cushion_scale.std_error) + " times the vehicle's F_G(h) at rest: F_G was not "
                           "fitted in flight (identify flight --hover gives it); v_i is fitted against s·F_G");
  }
  if (out.far_from_ground < kMinNearGround) {
    out.warnings.push_back("only " + std::to_string(out.far_from_ground) + " samples out of ground effect: the "
                           "translational lift c_TL·V² (all heights) and the fade (near the ground only) are told "
                           "apart by flying the same speeds high up too");
  }
  detail::warnIfManyOutliers(out.warnings, "forward-fade fit", out.stats);
  return out;
}

}  // namespace geaware::ident
