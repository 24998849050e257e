// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/traj/smooth_profile.hpp"

#include "param_text.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace geaware::traj {
namespace {

using detail::describe;
using detail::nonNegative;
using detail::positive;

// The smootherstep σ(x) = 35x⁴ − 84x⁵ + 70x⁶ − 20x⁷ on x ∈ [0, 1], its integral Σ and its
// derivatives, each in Horner form. σ' = 140x³(1 − x)³, so σ', σ'', σ''' vanish at 0 and 1;
// σ(1 − x) = 1 − σ(x), hence Σ(1) = ∫₀¹σ = 1/2.
double sigmaIntegral(double x) noexcept {  // Σ(x) = 7x⁵ − 14x⁶ + 10x⁷ − 5/2·x⁸
  const double x2 = x * x;
  return x2 * x2 * x * (7.0 + x * (-14.0 + x * (10.0 - 2.5 * x)));
}
double sigma(double x) noexcept {
  const double x2 = x * x;
  return x2 * x2 * (35.0 + x * (-84.0 + x * (70.0 - 20.0 * x)));
}
double sigmaD1(double x) noexcept {
  const double y = x * (1.0 - x);
  return 140.0 * y * y * y;
}
double sigmaD2(double x) noexcept {  // 420x² − 1680x³ + 2100x⁴ − 840x⁵
  return x * x * (420.0 + x * (-1680.0 + x * (2100.0 - 840.0 * x)));
}
double sigmaD3(double x) noexcept {  // 840x − 5040x² + 8400x³ − 4200x⁴
  return x * (840.0 + x * (-5040.0 + x * (8400.0 - 4200.0 * x)));
}

}  // namespace

SmoothProfile::SmoothProfile(double distance, double cruise_rate, double ramp_time_s)
    : distance_(distance),
      cruise_rate_(cruise_rate),
      ramp_time_s_(ramp_time_s),
      cruise_time_s_(0.0) {
  std::string problems;
  const auto add = [&problems](const std::string& p) {
    problems += problems.empty() ? p : "; " + p;
  };
  if (!(std::isfinite(distance) && distance > 0.0)) {
    add(describe("distance", distance, "finite > 0"));
  }
  if (!(std::isfinite(cruise_rate) && cruise_rate > 0.0)) {
    add(describe("cruise_rate", cruise_rate, "finite > 0"));
  }
  if (!(std::isfinite(ramp_time_s) && ramp_time_s >= 0.0)) {
    add(describe("ramp_time_s", ramp_time_s, "finite >= 0"));
  }
  if (problems.empty()) {
    // The two ramps together cover exactly V·T_r (each covers V·T_r·Σ(1) = V·T_r/2); the
    // cruise must cover the rest, so S/V − T_r ≥ 0. A relative slack of 1e-12 accepts
    // S = V·T_r computed with rounding.
    const double cruise_time_s = distance / cruise_rate - ramp_time_s;
    if (cruise_time_s < -1e-12 * (distance / cruise_rate)) {
      std::ostringstream os;
      os.precision(10);
      os << "impossible profile: distance = " << distance << " is shorter than cruise_rate * "
         << "ramp_time_s = " << cruise_rate << " * " << ramp_time_s << " = "
         << cruise_rate * ramp_time_s
         << ", the distance the two ramps alone cover; lower cruise_rate or ramp_time_s";
      add(os.str());
    } else {
      cruise_time_s_ = std::max(0.0, cruise_time_s);
    }
  }
  if (!problems.empty()) throw std::invalid_argument("SmoothProfile: " + problems);
}

ProfileSample SmoothProfile::sample(double t_s) const noexcept {
  const double v = cruise_rate_;
  const double t_end = duration();
  ProfileSample out;
  if (std::isnan(t_s)) {
    const double nan = std::nan("");
    return {nan, nan, nan, nan, nan};
  }
  const double t = std::clamp(t_s, 0.0, t_end);
  if (t <= 0.0) return out;  // at rest at the start (also for T_r = 0, see header)
  if (t >= t_end) {
    out.s = distance_;
    return out;
  }
  const double tr = ramp_time_s_;
  if (t < tr) {
    // Ramp up: ṡ = V·σ(t/T_r), s = V·T_r·Σ(t/T_r); each further derivative brings 1/T_r.
    const double x = t / tr;
    out.s = v * tr * sigmaIntegral(x);
    out.s_dot = v * sigma(x);
    out.s_ddot = v * sigmaD1(x) / tr;
    out.s_dddot = v * sigmaD2(x) / (tr * tr);
    out.s_ddddot = v * sigmaD3(x) / (tr * tr * tr);
  } else if (t <= tr + cruise_time_s_) {
    out.s = v * (0.5 * tr + (t - tr));
    out.s_dot = v;
  } else {
    // Ramp down, mirrored: with u = (T − t)/T_r, ṡ = V·σ(u) and s = S − V·T_r·Σ(u), so the
    // profile ends on S exactly. d/dt = −(1/T_r)·d/du flips the sign of the odd derivatives.
    const double u = (t_end - t) / tr;
    out.s = distance_ - v * tr * sigmaIntegral(u);
    out.s_dot = v * sigma(u);
    out.s_ddot = -v * sigmaD1(u) / tr;
    out.s_dddot = v * sigmaD2(u) / (tr * tr);
    out.s_ddddot = -v * sigmaD3(u) / (tr * tr * tr);
  }
  return out;
}

}  // namespace geaware::traj
