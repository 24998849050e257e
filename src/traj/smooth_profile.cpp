// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/traj/smooth_profile.hpp"

#include "param_text.hpp"
#include "smootherstep.hpp"

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

using detail::sigma;
using detail::sigmaD1;
using detail::sigmaD2;
using detail::sigmaD3;
using detail::sigmaIntegral;

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
