// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Landing and take-off references (issue 13 item 5). Heights are the rotor-plane centre's z in
// the world frame; `touchdown_height_m` is where the landing gear meets the surface (the
// surface's z plus the vehicle file's min_rotor_plane_height_m).
//
// Landing: the vertical speed v(t) is a chain of segments, each a degree-7 smootherstep
// σ(x) = 35x⁴ − 84x⁵ + 70x⁶ − 20x⁷ between two speeds (first three derivatives zero at both
// ends), so z(t) is continuous up to snap, as the flat map needs:
//   hold        [0, hold_start]                   at from_height
//   speed-up    T_r = ramp_time_s                 0 → v_d, descends v_d·T_r/2
//   cruise      v_d                               down to touchdown + flare_height
//   flare       T_f = 2·h_f/(v_d + v_td)          v_d → v_td, descends h_f: at touchdown v = v_td
//   press       T_p = 2·d_p/v_td                  v_td → 0, d_p = press_depth_m BELOW touchdown
//   hold        hold_end_s                        at touchdown − d_p
// The reference keeps sinking past the touchdown height on purpose: the gear stops the vehicle
// and the position loop presses it onto the surface until the land detector
// (control/land_detector.hpp) takes the motors down. The press is bounded (d_p, 3 cm default),
// so a vehicle that never detects its landing rests on its legs rather than driving into them.
//
// Take-off: on the ground at touchdown_height for hold_start_s, a SmoothProfile climb to
// to_height_m at climb_rate_mps, then a hover for hold_end_s.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "geaware/traj/smooth_profile.hpp"
#include "geaware/traj/trajectory.hpp"

namespace geaware::traj {

struct LandingParams {
  Eigen::Vector2d position_xy_m = Eigen::Vector2d::Zero();  ///< landing point (x, y), world [m]
  double from_height_m = 1.0;         ///< start hover height, world z [m]
  double touchdown_height_m = 0.072;  ///< rotor-plane z when the feet touch [m]
  double descent_rate_mps = 0.5;      ///< cruise descent speed v_d [m/s]
  double flare_height_m = 0.3;        ///< flare start above touchdown_height_m, h_f [m]
  double touchdown_speed_mps = 0.1;   ///< the reference's descent speed at touchdown, v_td [m/s]
  double press_depth_m = 0.03;        ///< how far below touchdown the reference comes to rest [m]
  double ramp_time_s = 1.0;           ///< the speed-up to v_d [s]
  double hold_start_s = 1.0;          ///< hover before the descent [s]
  double hold_end_s = 2.0;            ///< after the press [s]
  double yaw_rad = 0.0;               ///< constant yaw ψ [rad]

  /// Every offending field as "field = value (expected ...)"; empty when usable. Includes
  /// v_td ≤ v_d and that the speed-up and the flare fit into from − touchdown.
  [[nodiscard]] std::vector<std::string> validate() const;
};

class Landing final : public Trajectory {
 public:
  /// Throws std::invalid_argument listing every problem validate() reports.
  explicit Landing(const LandingParams& params);

  [[nodiscard]] FlatOutput sample(double t_s) const noexcept override;
  [[nodiscard]] double duration() const noexcept override { return duration_s_; }

  /// Trajectory time at which the reference reaches touchdown_height_m [s].
  [[nodiscard]] double touchdownTime() const noexcept { return touchdown_t_s_; }
  [[nodiscard]] const LandingParams& params() const noexcept { return params_; }

 private:
  /// One segment of the descent speed: from v_a to v_b over [t0, t0 + T], having descended s0.
  struct Segment {
    double t0_s, T_s, s0_m, v_a_mps, v_b_mps;
  };
  LandingParams params_;
  Segment seg_[4]{};  // speed-up, cruise, flare, press
  double touchdown_t_s_ = 0.0;
  double duration_s_ = 0.0;
};

struct TakeOffParams {
  Eigen::Vector2d position_xy_m = Eigen::Vector2d::Zero();  ///< take-off point (x, y), world [m]
  double touchdown_height_m = 0.072;  ///< rotor-plane z standing on the gear (unloaded) [m]
  double to_height_m = 1.0;           ///< hover height after the climb, world z [m]
  double climb_rate_mps = 0.5;        ///< cruise climb speed [m/s]
  double ramp_time_s = 1.0;           ///< speed-up and slow-down of the climb [s]
  double hold_start_s = 1.0;          ///< on the ground before the climb [s]
  double hold_end_s = 2.0;            ///< hover after the climb [s]
  double yaw_rad = 0.0;               ///< constant yaw ψ [rad]

  [[nodiscard]] std::vector<std::string> validate() const;
};

class TakeOff final : public Trajectory {
 public:
  explicit TakeOff(const TakeOffParams& params);

  [[nodiscard]] FlatOutput sample(double t_s) const noexcept override;
  [[nodiscard]] double duration() const noexcept override {
    return params_.hold_start_s + climb_.duration() + params_.hold_end_s;
  }
  [[nodiscard]] const TakeOffParams& params() const noexcept { return params_; }

 private:
  TakeOffParams params_;
  SmoothProfile climb_;
};

}  // namespace geaware::traj
