// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The hover-descent manoeuvre of the paper's leveling-torque experiments: hover at a safe
// height, descend slowly into ground effect, hold near the ground. The descent follows a
// SmoothProfile, z(t) = from_height − s(t), so the references are continuous up to snap and
// the vertical speed equals descent_rate_mps between the ramps (the angle error E(h) is binned
// by height over that quasi-static part).
//
//   [0, hold_start]                 hover at from_height
//   [hold_start, hold_start + T_d]  descent, T_d = (from − to)/rate + ramp_time_s
//   [.., + hold_end]                hover at to_height

#include <string>
#include <vector>

#include <Eigen/Core>

#include "geaware/traj/smooth_profile.hpp"
#include "geaware/traj/trajectory.hpp"

namespace geaware::traj {

struct HoverDescentParams {
  Eigen::Vector2d position_xy_m = Eigen::Vector2d::Zero();  ///< hover point (x, y), world [m]
  double from_height_m = 1.5;                               ///< start height z, world frame [m]
  double to_height_m = 0.1;       ///< end height z, world frame [m]; < from_height_m
  double descent_rate_mps = 0.1;  ///< vertical speed during the cruise of the descent [m/s]
  double ramp_time_s = 1.0;       ///< duration of the speed-up and of the slow-down [s]
  double hold_start_s = 2.0;      ///< hover before the descent [s]
  double hold_end_s = 2.0;        ///< hover after the descent [s]
  double yaw_rad = 0.0;           ///< constant yaw ψ [rad]

  /// Every offending field as "field = value (expected ...)"; empty when usable. Includes the
  /// joint condition that the two ramps fit into the height change:
  /// descent_rate_mps·ramp_time_s ≤ from_height_m − to_height_m.
  [[nodiscard]] std::vector<std::string> validate() const;
};

class HoverDescent final : public Trajectory {
 public:
  /// Throws std::invalid_argument listing every problem validate() reports.
  explicit HoverDescent(const HoverDescentParams& params);

  [[nodiscard]] FlatOutput sample(double t_s) const noexcept override;
  [[nodiscard]] double duration() const noexcept override {
    return params_.hold_start_s + descent_.duration() + params_.hold_end_s;
  }

  [[nodiscard]] const HoverDescentParams& params() const noexcept { return params_; }
  /// The descent profile s(t − hold_start) [m], z = from_height − s.
  [[nodiscard]] const SmoothProfile& descent() const noexcept { return descent_; }

 private:
  HoverDescentParams params_;
  SmoothProfile descent_;
};

}  // namespace geaware::traj
