// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/traj/hover_descent.hpp"

#include "param_text.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace geaware::traj {
namespace {

using detail::describe;
using detail::nonNegative;
using detail::positive;

SmoothProfile makeDescent(const HoverDescentParams& p) {
  const std::vector<std::string> problems = p.validate();
  if (!problems.empty()) {
    std::string msg = "HoverDescent: invalid parameters: ";
    for (std::size_t i = 0; i < problems.size(); ++i) msg += (i ? "; " : "") + problems[i];
    throw std::invalid_argument(msg);
  }
  return SmoothProfile(p.from_height_m - p.to_height_m, p.descent_rate_mps, p.ramp_time_s);
}

}  // namespace

std::vector<std::string> HoverDescentParams::validate() const {
  std::vector<std::string> out;
  if (!position_xy_m.allFinite()) {
    std::ostringstream os;
    os << "position_xy_m = (" << position_xy_m.x() << ", " << position_xy_m.y()
       << ") (expected finite)";
    out.push_back(os.str());
  }
  if (!positive(from_height_m)) {
    out.push_back(describe("from_height_m", from_height_m, "finite > 0"));
  }
  if (!positive(to_height_m)) out.push_back(describe("to_height_m", to_height_m, "finite > 0"));
  if (positive(from_height_m) && positive(to_height_m) && !(to_height_m < from_height_m)) {
    std::ostringstream os;
    os.precision(10);
    os << "to_height_m = " << to_height_m << " (expected < from_height_m = " << from_height_m
       << ": the manoeuvre descends)";
    out.push_back(os.str());
  }
  if (!positive(descent_rate_mps)) {
    out.push_back(describe("descent_rate_mps", descent_rate_mps, "finite > 0"));
  }
  if (!nonNegative(ramp_time_s)) out.push_back(describe("ramp_time_s", ramp_time_s, "finite >= 0"));
  if (!nonNegative(hold_start_s)) {
    out.push_back(describe("hold_start_s", hold_start_s, "finite >= 0"));
  }
  if (!nonNegative(hold_end_s)) out.push_back(describe("hold_end_s", hold_end_s, "finite >= 0"));
  if (!std::isfinite(yaw_rad)) out.push_back(describe("yaw_rad", yaw_rad, "finite"));
  if (out.empty()) {
    // The speed-up and slow-down ramps cover rate·T_r of height between them (SmoothProfile).
    const double drop = from_height_m - to_height_m;
    if (descent_rate_mps * ramp_time_s > drop * (1.0 + 1e-12)) {
      std::ostringstream os;
      os.precision(10);
      os << "ramp_time_s = " << ramp_time_s << " (expected <= " << drop / descent_rate_mps
         << ": at descent_rate_mps = " << descent_rate_mps << " the two ramps alone would descend "
         << descent_rate_mps * ramp_time_s << " m, more than from_height_m - to_height_m = " << drop
         << " m)";
      out.push_back(os.str());
    }
  }
  return out;
}

HoverDescent::HoverDescent(const HoverDescentParams& params)
    : params_(params), descent_(makeDescent(params)) {}

FlatOutput HoverDescent::sample(double t_s) const noexcept {
  // The profile clamps its own time, which also covers both holds: before the descent it sits
  // at s = 0, after it at s = from − to, both at rest.
  const ProfileSample d = descent_.sample(t_s - params_.hold_start_s);
  FlatOutput out;
  out.p_W = Eigen::Vector3d(params_.position_xy_m.x(), params_.position_xy_m.y(),
                            params_.from_height_m - d.s);
  out.v_W.z() = -d.s_dot;
  out.a_W.z() = -d.s_ddot;
  out.j_W.z() = -d.s_dddot;
  out.s_W.z() = -d.s_ddddot;
  out.yaw_rad = params_.yaw_rad;
  return out;
}

}  // namespace geaware::traj
