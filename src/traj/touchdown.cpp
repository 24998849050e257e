// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/traj/touchdown.hpp"

#include "param_text.hpp"
#include "smootherstep.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace geaware::traj {
namespace {

using detail::describe;
using detail::nonNegative;
using detail::positive;

template <typename P>
const P& checked(const P& p, const char* what) {
  const std::vector<std::string> problems = p.validate();
  if (!problems.empty()) {
    std::string msg = std::string(what) + ": invalid parameters: ";
    for (std::size_t i = 0; i < problems.size(); ++i) msg += (i ? "; " : "") + problems[i];
    throw std::invalid_argument(msg);
  }
  return p;
}

void commonChecks(std::vector<std::string>& out, const Eigen::Vector2d& xy, double hold_start_s,
                  double hold_end_s, double ramp_time_s, double yaw_rad) {
  if (!xy.allFinite()) {
    std::ostringstream os;
    os << "position_xy_m = (" << xy.x() << ", " << xy.y() << ") (expected finite)";
    out.push_back(os.str());
  }
  // > 0: a zero ramp would step the speed, and these references are continuous up to snap.
  if (!positive(ramp_time_s)) out.push_back(describe("ramp_time_s", ramp_time_s, "finite > 0"));
  if (!nonNegative(hold_start_s)) out.push_back(describe("hold_start_s", hold_start_s, "finite >= 0"));
  if (!nonNegative(hold_end_s)) out.push_back(describe("hold_end_s", hold_end_s, "finite >= 0"));
  if (!std::isfinite(yaw_rad)) out.push_back(describe("yaw_rad", yaw_rad, "finite"));
}

}  // namespace

std::vector<std::string> LandingParams::validate() const {
  std::vector<std::string> out;
  commonChecks(out, position_xy_m, hold_start_s, hold_end_s, ramp_time_s, yaw_rad);
  if (!std::isfinite(from_height_m)) out.push_back(describe("from_height_m", from_height_m, "finite"));
  if (!std::isfinite(touchdown_height_m)) {
    out.push_back(describe("touchdown_height_m", touchdown_height_m, "finite"));
  }
  if (!positive(descent_rate_mps)) {
    out.push_back(describe("descent_rate_mps", descent_rate_mps, "finite > 0"));
  }
  if (!positive(flare_height_m)) out.push_back(describe("flare_height_m", flare_height_m, "finite > 0"));
  if (!positive(touchdown_speed_mps)) {
    out.push_back(describe("touchdown_speed_mps", touchdown_speed_mps, "finite > 0"));
  } else if (positive(descent_rate_mps) && touchdown_speed_mps > descent_rate_mps) {
    std::ostringstream os;
    os.precision(10);
    os << "touchdown_speed_mps = " << touchdown_speed_mps
       << " (expected <= descent_rate_mps = " << descent_rate_mps << ": the flare slows down)";
    out.push_back(os.str());
  }
  if (!positive(press_depth_m)) out.push_back(describe("press_depth_m", press_depth_m, "finite > 0"));
  if (out.empty()) {
    const double room = from_height_m - touchdown_height_m - flare_height_m;
    const double ramp = 0.5 * descent_rate_mps * ramp_time_s;
    if (ramp > room * (1.0 + 1e-12)) {
      std::ostringstream os;
      os.precision(10);
      os << "from_height_m = " << from_height_m << " (expected >= "
         << touchdown_height_m + flare_height_m + ramp
         << ": touchdown_height_m + flare_height_m + the speed-up's descent descent_rate_mps·ramp_time_s/2 = "
         << ramp << " m)";
      out.push_back(os.str());
    }
  }
  return out;
}

Landing::Landing(const LandingParams& params) : params_(checked(params, "Landing")) {
  const LandingParams& p = params_;
  const double v_d = p.descent_rate_mps;
  const double v_td = p.touchdown_speed_mps;
  const double ramp_m = 0.5 * v_d * p.ramp_time_s;
  const double cruise_m = std::max(0.0, p.from_height_m - p.touchdown_height_m - p.flare_height_m - ramp_m);
  const double flare_s = 2.0 * p.flare_height_m / (v_d + v_td);
  const double press_s = 2.0 * p.press_depth_m / v_td;
  seg_[0] = {p.hold_start_s, p.ramp_time_s, 0.0, 0.0, v_d};
  seg_[1] = {seg_[0].t0_s + seg_[0].T_s, cruise_m / v_d, ramp_m, v_d, v_d};
  seg_[2] = {seg_[1].t0_s + seg_[1].T_s, flare_s, ramp_m + cruise_m, v_d, v_td};
  seg_[3] = {seg_[2].t0_s + flare_s, press_s, ramp_m + cruise_m + p.flare_height_m, v_td, 0.0};
  touchdown_t_s_ = seg_[3].t0_s;
  duration_s_ = seg_[3].t0_s + press_s + p.hold_end_s;
}

FlatOutput Landing::sample(double t_s) const noexcept {
  FlatOutput out;
  out.yaw_rad = params_.yaw_rad;
  const double total_m = seg_[3].s0_m + params_.press_depth_m;
  double s = 0.0, v = 0.0, a = 0.0, j = 0.0, snap = 0.0;
  if (std::isnan(t_s)) {
    s = v = a = j = snap = t_s;
  } else if (t_s >= seg_[3].t0_s + seg_[3].T_s) {
    s = total_m;
  } else if (t_s > seg_[0].t0_s) {
    const Segment* g = &seg_[0];
    for (const Segment& c : seg_)
      if (t_s >= c.t0_s) g = &c;
    const double tau = t_s - g->t0_s;
    const double dv = g->v_b_mps - g->v_a_mps;
    if (g->T_s > 0.0 && dv != 0.0) {
      const double T = g->T_s;
      const double x = std::clamp(tau / T, 0.0, 1.0);
      s = g->s0_m + g->v_a_mps * tau + dv * T * detail::sigmaIntegral(x);
      v = g->v_a_mps + dv * detail::sigma(x);
      a = dv * detail::sigmaD1(x) / T;
      j = dv * detail::sigmaD2(x) / (T * T);
      snap = dv * detail::sigmaD3(x) / (T * T * T);
    } else {
      s = g->s0_m + g->v_a_mps * tau;
      v = g->v_a_mps;
    }
  }
  out.p_W = Eigen::Vector3d(params_.position_xy_m.x(), params_.position_xy_m.y(),
                            params_.from_height_m - s);
  out.v_W.z() = -v;
  out.a_W.z() = -a;
  out.j_W.z() = -j;
  out.s_W.z() = -snap;
  return out;
}

std::vector<std::string> TakeOffParams::validate() const {
  std::vector<std::string> out;
  commonChecks(out, position_xy_m, hold_start_s, hold_end_s, ramp_time_s, yaw_rad);
  if (!std::isfinite(touchdown_height_m)) {
    out.push_back(describe("touchdown_height_m", touchdown_height_m, "finite"));
  }
  if (!std::isfinite(to_height_m)) out.push_back(describe("to_height_m", to_height_m, "finite"));
  if (!positive(climb_rate_mps)) out.push_back(describe("climb_rate_mps", climb_rate_mps, "finite > 0"));
  if (out.empty()) {
    const double climb = to_height_m - touchdown_height_m;
    if (!(climb > 0.0) || climb_rate_mps * ramp_time_s > climb * (1.0 + 1e-12)) {
      std::ostringstream os;
      os.precision(10);
      os << "to_height_m = " << to_height_m << " (expected >= touchdown_height_m + climb_rate_mps·ramp_time_s = "
         << touchdown_height_m + climb_rate_mps * ramp_time_s << " and above touchdown_height_m)";
      out.push_back(os.str());
    }
  }
  return out;
}

TakeOff::TakeOff(const TakeOffParams& params)
    : params_(checked(params, "TakeOff")),
      climb_(params.to_height_m - params.touchdown_height_m, params.climb_rate_mps,
             params.ramp_time_s) {}

FlatOutput TakeOff::sample(double t_s) const noexcept {
  const ProfileSample c = climb_.sample(t_s - params_.hold_start_s);
  FlatOutput out;
  out.p_W = Eigen::Vector3d(params_.position_xy_m.x(), params_.position_xy_m.y(),
                            params_.touchdown_height_m + c.s);
  out.v_W.z() = c.s_dot;
  out.a_W.z() = c.s_ddot;
  out.j_W.z() = c.s_dddot;
  out.s_W.z() = c.s_ddddot;
  out.yaw_rad = params_.yaw_rad;
  return out;
}

}  // namespace geaware::traj
