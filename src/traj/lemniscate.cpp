// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/traj/lemniscate.hpp"

#include "param_text.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace geaware::traj {
namespace {

using detail::describe;
using detail::nonNegative;
using detail::positive;

// Peak of |dP/dθ| = √(A²cos²θ + 4B²cos²2θ), reached at θ = 0 [m/rad].
double peakCurveSpeed(const LemniscateParams& p) {
  return std::hypot(p.half_extent_x_m, 2.0 * p.half_extent_y_m);
}

// Phase profile of validated parameters.
SmoothProfile makePhase(const LemniscateParams& p) {
  const std::vector<std::string> problems = p.validate();
  if (!problems.empty()) {
    std::string msg = "Lemniscate: invalid parameters: ";
    for (std::size_t i = 0; i < problems.size(); ++i) msg += (i ? "; " : "") + problems[i];
    throw std::invalid_argument(msg);
  }
  return SmoothProfile(2.0 * std::numbers::pi * p.laps, p.peak_speed_mps / peakCurveSpeed(p),
                       p.ramp_time_s);
}

}  // namespace

std::vector<std::string> LemniscateParams::validate() const {
  std::vector<std::string> out;
  if (!centre_xy_m.allFinite()) {
    std::ostringstream os;
    os << "(" << centre_xy_m.x() << ", " << centre_xy_m.y() << ")";
    out.push_back(describe("centre_xy_m", os.str(), "finite"));
  }
  if (!positive(half_extent_x_m)) {
    out.push_back(describe("half_extent_x_m", half_extent_x_m, "finite > 0"));
  }
  if (!positive(half_extent_y_m)) {
    out.push_back(describe("half_extent_y_m", half_extent_y_m, "finite > 0"));
  }
  if (!positive(height_m)) out.push_back(describe("height_m", height_m, "finite > 0"));
  if (!nonNegative(height_swing_m)) {
    out.push_back(describe("height_swing_m", height_swing_m, "finite >= 0"));
  } else if (positive(half_extent_x_m) && height_swing_m > 2.0 * half_extent_x_m) {
    // |dP/dθ|² = A²·cos²θ + 4B²·cos²2θ + (S/2)²·sin²θ peaks at θ = 0 only while S ≤ 2A: beyond,
    // the cruise rate from v_peak/√(A² + 4B²) would fly faster than v_peak.
    out.push_back(describe("height_swing_m", height_swing_m, "at most 2·half_extent_x_m"));
  }
  if (!positive(peak_speed_mps)) {
    out.push_back(describe("peak_speed_mps", peak_speed_mps, "finite > 0"));
  }
  if (laps < 1) out.push_back(describe("laps", laps, ">= 1"));
  if (!(std::isfinite(ramp_time_s) && ramp_time_s >= 0.0)) {
    out.push_back(describe("ramp_time_s", ramp_time_s, "finite >= 0"));
  }
  if (!std::isfinite(yaw_rad)) out.push_back(describe("yaw_rad", yaw_rad, "finite"));
  if (out.empty()) {
    // The two ramps of θ̇ cover Ω·T_r of phase between them (see SmoothProfile); they must fit
    // in the laps, else the vehicle cannot reach the requested peak speed.
    const double omega = peak_speed_mps / peakCurveSpeed(*this);
    const double total = 2.0 * std::numbers::pi * laps;
    if (omega * ramp_time_s > total * (1.0 + 1e-12)) {
      std::ostringstream os;
      os.precision(10);
      os << "ramp_time_s = " << ramp_time_s << " (expected <= " << total / omega
         << ": at peak_speed_mps = " << peak_speed_mps << " the two ramps alone would cover "
         << omega * ramp_time_s << " rad of phase, more than the " << total
         << " rad of laps = " << laps << "; lower peak_speed_mps or ramp_time_s, or add laps)";
      out.push_back(os.str());
    }
  }
  return out;
}

Lemniscate::Lemniscate(const LemniscateParams& params)
    : params_(params), phase_(makePhase(params)) {}

FlatOutput Lemniscate::sample(double t_s) const noexcept {
  const ProfileSample th = phase_.sample(t_s);
  const double a = params_.half_extent_x_m;
  const double b = params_.half_extent_y_m;
  const double s1 = std::sin(th.s);
  const double c1 = std::cos(th.s);
  const double s2 = std::sin(2.0 * th.s);
  const double c2 = std::cos(2.0 * th.s);

  // Derivatives of the curve with respect to θ, P⁽ᵏ⁾(θ) [m/radᵏ].
  Eigen::Vector3d p0(a * s1, b * s2, 0.0);
  Eigen::Vector3d p1(a * c1, 2.0 * b * c2, 0.0);
  Eigen::Vector3d p2(-a * s1, -4.0 * b * s2, 0.0);
  Eigen::Vector3d p3(-a * c1, -8.0 * b * c2, 0.0);
  Eigen::Vector3d p4(a * s1, 16.0 * b * s2, 0.0);
  if (params_.height_swing_m > 0.0) {
    // z = swing·(1 − cos θ)/2 and its θ-derivatives; skipped for a level flight, whose z terms
    // stay exactly +0 (a −0 would change nothing but the bits).
    const double h = 0.5 * params_.height_swing_m;
    p0.z() = h * (1.0 - c1);
    p1.z() = h * s1;
    p2.z() = h * c1;
    p3.z() = -h * s1;
    p4.z() = -h * c1;
  }

  // Chain rule up to the fourth derivative (Faà di Bruno) for p(t) = P(θ(t)).
  const double w1 = th.s_dot;
  const double w2 = th.s_ddot;
  const double w3 = th.s_dddot;
  const double w4 = th.s_ddddot;
  FlatOutput out;
  out.p_W =
      Eigen::Vector3d(params_.centre_xy_m.x(), params_.centre_xy_m.y(), params_.height_m) + p0;
  out.v_W = p1 * w1;
  out.a_W = p2 * (w1 * w1) + p1 * w2;
  out.j_W = p3 * (w1 * w1 * w1) + p2 * (3.0 * w1 * w2) + p1 * w3;
  out.s_W = p4 * (w1 * w1 * w1 * w1) + p3 * (6.0 * w1 * w1 * w2) +
            p2 * (3.0 * w2 * w2 + 4.0 * w1 * w3) + p1 * w4;
  out.yaw_rad = params_.yaw_rad;
  return out;
}

}  // namespace geaware::traj
