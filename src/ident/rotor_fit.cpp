// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/ident/rotor_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "fit_support.hpp"
#include "geaware/ident/voltage_fit.hpp"
#include "geaware/model/units.hpp"

namespace geaware::ident {

using detail::num;

std::vector<double> rotorAcceleration(const std::vector<double>& t_s,
                                      const std::vector<double>& n_rpm, double window_s) {
  const std::size_t n = t_s.size();
  std::vector<double> rate(n, 0.0);
  if (n < 2) return rate;
  const double half = 0.5 * window_s;
  std::size_t lo = 0;
  std::size_t hi = 0;
  for (std::size_t i = 0; i < n; ++i) {
    while (t_s[i] - t_s[lo] > half && lo + 1 < i) ++lo;
    if (hi < i + 1 && i + 1 < n) hi = i + 1;
    while (hi + 1 < n && t_s[hi + 1] - t_s[i] <= half) ++hi;
    const std::size_t a = std::min(lo, i > 0 ? i - 1 : 0);
    const std::size_t b = hi;
    // Slope of the least-squares line through the window, with centred sums.
    double tm = 0.0;
    double nm = 0.0;
    for (std::size_t j = a; j <= b; ++j) {
      tm += t_s[j];
      nm += n_rpm[j];
    }
    const double count = static_cast<double>(b - a + 1);
    tm /= count;
    nm /= count;
    double stt = 0.0;
    double stn = 0.0;
    for (std::size_t j = a; j <= b; ++j) {
      stt += (t_s[j] - tm) * (t_s[j] - tm);
      stn += (t_s[j] - tm) * (n_rpm[j] - nm);
    }
    rate[i] = stt > 0.0 ? stn / stt : 0.0;
  }
  return rate;
}

RotorFit fitRotorStand(const RotorStandLog& log, const RotorFitOptions& options) {
  RotorFit fit;
  const std::size_t n = log.size();
  const std::string& src = log.source;

  // 1. Thrust: T = k_T·n².
  {
    const auto ls = fitLinear(
        n, 1,
        [&](std::size_t i, double* x, double& y, double& w) {
          x[0] = log.rpm[i] * log.rpm[i];
          y = log.thrust_N[i];
          w = 1.0;
          return true;
        },
        options.robust);
    detail::require(ls, src, "k_T (thrust vs rpm²)");
    fit.k_T_N_per_rpm2 = ls.estimate(0);
    fit.thrust = ls.stats;
    detail::warnIfManyOutliers(fit.warnings, "thrust fit", ls.stats);
  }

  // 2. Torque: M = k_I·n² + J_R·ṅ. The stand's sign convention may make the reaction torque
  //    negative; the model's M is its magnitude along the spin.
  std::vector<double> torque = log.torque_Nm;
  {
    std::vector<double> tmp = torque;
    auto mid = tmp.begin() + static_cast<std::ptrdiff_t>(tmp.size() / 2);
    std::nth_element(tmp.begin(), mid, tmp.end());
    if (*mid < 0.0) {
      for (double& m : torque) m = -m;
      fit.warnings.push_back("the torque column is mostly negative: its sign is flipped (k_I "
                             "is the magnitude of the reaction torque per rpm²)");
    }
  }
  const std::vector<double> rate = rotorAcceleration(log.t_s, log.rpm, options.rate_window_s);
  auto torqueFit = [&](bool inertia) {
    return fitLinear(
        n, inertia ? 2 : 1,
        [&](std::size_t i, double* x, double& y, double& w) {
          x[0] = log.rpm[i] * log.rpm[i];
          if (inertia) x[1] = rate[i] * model::kRpmToRadPerSec;
          y = torque[i];
          w = 1.0;
          return true;
        },
        options.robust);
  };
  // kAuto keeps J_R only where the log determines it: a fit that is singular (the speed never
  // changes) or gives |J_R| < 3σ (changes too small for J_R·ṅ to stand out of the noise) is
  // redone without it.
  constexpr double kMinSignificance = 3.0;
  bool with_inertia = options.rotor_inertia != RotorInertiaTerm::kNever;
  LeastSquaresFit tq = torqueFit(with_inertia);
  if (with_inertia && options.rotor_inertia == RotorInertiaTerm::kAuto) {
    const bool significant =
        tq.ok && std::abs(tq.x(1)) >= kMinSignificance * std::sqrt(tq.covariance(1, 1));
    if (!significant) {
      fit.warnings.push_back(
          "J_R not fitted: the log does not determine it (" +
          (tq.ok ? "J_R = " + num(tq.x(1)) + " ± " + num(std::sqrt(tq.covariance(1, 1))) + " kg·m²"
                 : std::string("the speed never changes")) +
          "); log speed steps or a sweep to identify it");
      with_inertia = false;
      tq = torqueFit(false);
    }
  }
  detail::require(tq, src, with_inertia ? "k_I, J_R (torque vs rpm², ṅ)" : "k_I (torque vs rpm²)");
  fit.k_I_Nm_per_rpm2 = tq.estimate(0);
  fit.torque = tq.stats;
  detail::warnIfManyOutliers(fit.warnings, "torque fit", tq.stats);
  if (with_inertia) {
    fit.J_R_kgm2 = tq.estimate(1);
    detail::warnIfImprecise(fit.warnings, "J_R", *fit.J_R_kgm2,
                            "the rotor speed hardly changes: log speed steps or a sweep");
  }

  // 3. Throttle curve n² = c2·t² + c1·t + c0 on steady samples. With additive rpm noise σ_n,
  //    var(n²) ≈ 4·n²·σ_n², so the samples are weighted by 1/n² (rpm² residuals are scaled
  //    by 1/n: the stats' RMS is in rpm, about twice the rpm noise).
  std::size_t steady = 0;
  for (const double r : rate) steady += std::abs(r) <= options.throttle_max_rate_rpm_per_s ? 1 : 0;
  double max_rate_used = options.throttle_max_rate_rpm_per_s;
  if (steady < 10) {
    fit.warnings.push_back("only " + std::to_string(steady) + " samples have |ṅ| ≤ " +
                           num(options.throttle_max_rate_rpm_per_s) +
                           " rpm/s: the throttle curve is fitted on all samples, transients included");
    max_rate_used = std::numeric_limits<double>::infinity();
  }
  if (!log.voltage_V.empty()) {
    std::vector<char> use(n, 0);
    for (std::size_t i = 0; i < n; ++i) use[i] = std::abs(rate[i]) <= max_rate_used ? 1 : 0;
    const ThrottleVoltageFit tv =
        fitThrottleVoltage(log.throttle, log.rpm, log.voltage_V, use, options.reference_voltage_V);
    detail::require(tv.fit, src, "the throttle curve with its voltage dependence (rpm² vs throttle, voltage)");
    fit.c2_rpm2 = tv.fit.estimate(0);
    fit.c1_rpm2 = tv.fit.estimate(1);
    fit.c0_rpm2 = tv.fit.estimate(2);
    fit.voltage_exponent = tv.fit.estimate(3);
    fit.reference_voltage_V = tv.reference_voltage_V;
    fit.throttle = tv.fit.stats;
    if (!tv.fit.message.empty()) {
      fit.blocking.push_back("voltage fit: " + tv.fit.message + " (the optimum lies outside the range searched: the "
                             "value is the bound, not a fit)");
    }
    return fit;
  }
  const auto th = fitLinear(
      n, 3,
      [&](std::size_t i, double* x, double& y, double& w) {
        if (!(std::abs(rate[i]) <= max_rate_used)) return false;
        const double t = log.throttle[i];
        x[0] = t * t;
        x[1] = t;
        x[2] = 1.0;
        y = log.rpm[i] * log.rpm[i];
        w = 1.0 / std::max(y, 1.0);
        return true;
      },
      options.robust);
  detail::require(th, src, "the throttle curve (rpm² vs throttle)");
  fit.c2_rpm2 = th.estimate(0);
  fit.c1_rpm2 = th.estimate(1);
  fit.c0_rpm2 = th.estimate(2);
  fit.throttle = th.stats;
  detail::warnIfManyOutliers(fit.warnings, "throttle-curve fit", th.stats);
  const double c1 = fit.c1_rpm2.value;
  const double c2 = fit.c2_rpm2.value;
  if (!(c1 > 0.0 && c1 + 2.0 * c2 > 0.0)) {
    fit.warnings.push_back("the fitted throttle curve does not rise over the whole range "
                           "(c1 = " + num(c1) + ", c1 + 2·c2 = " + num(c1 + 2.0 * c2) +
                           "): does the log cover throttle 0 to 1?");
  }
  return fit;
}

}  // namespace geaware::ident
