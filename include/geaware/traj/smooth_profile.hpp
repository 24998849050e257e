// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A 1-D progress profile s(t): the rate ṡ ramps from 0 up to a cruise rate V, cruises, and ramps
// back down to 0, covering a total distance S exactly. The ramps follow the degree-7
// "smootherstep" σ(x) = 35x⁴ − 84x⁵ + 70x⁶ − 20x⁷, whose first three derivatives vanish at both
// ends, so ṡ is C³ and s is C⁴: a reference built on s is continuous up to snap, which the
// differential-flatness map needs (snap feeds the angular acceleration, paper eq. 19–22).
//
// s is the integral of ṡ, evaluated in closed form. "Distance" and "rate" are in whatever unit
// the caller gives: metres for a descent, radians for the phase of a closed curve.

namespace geaware::traj {

/// s and its first four time derivatives at one instant. Units: [u], [u/s], ..., [u/s⁴], where
/// [u] is the unit of the profile's distance.
struct ProfileSample {
  double s = 0.0;         ///< progress [u]
  double s_dot = 0.0;     ///< rate ṡ [u/s]
  double s_ddot = 0.0;    ///< s̈ [u/s²]
  double s_dddot = 0.0;   ///< s⃛ [u/s³]
  double s_ddddot = 0.0;  ///< s⁗ [u/s⁴]
};

class SmoothProfile {
 public:
  /// Profile covering `distance` [u] with cruise rate `cruise_rate` [u/s] and ramps of
  /// `ramp_time_s` [s] at each end. Throws std::invalid_argument, naming the field and its
  /// value, unless all are finite, distance > 0, cruise_rate > 0, ramp_time_s ≥ 0 and
  /// distance ≥ cruise_rate·ramp_time_s (the two ramps alone cover V·T_r; a shorter distance
  /// cannot be reached at that cruise rate).
  ///
  /// ramp_time_s = 0 is allowed and gives a rate step: ṡ = V on the open interval
  /// (0, duration), 0 at both ends, and s̈ … s⁗ = 0 everywhere.
  SmoothProfile(double distance, double cruise_rate, double ramp_time_s);

  /// s, ṡ, s̈, s⃛, s⁗ at t [s], t clamped to [0, duration()]. A NaN t gives NaN.
  [[nodiscard]] ProfileSample sample(double t_s) const noexcept;

  /// Total time, S/V + T_r [s].
  [[nodiscard]] double duration() const noexcept { return 2.0 * ramp_time_s_ + cruise_time_s_; }

  [[nodiscard]] double distance() const noexcept { return distance_; }         ///< S [u]
  [[nodiscard]] double cruiseRate() const noexcept { return cruise_rate_; }    ///< V [u/s]
  [[nodiscard]] double rampTime() const noexcept { return ramp_time_s_; }      ///< T_r [s]
  [[nodiscard]] double cruiseTime() const noexcept { return cruise_time_s_; }  ///< T_c [s]

 private:
  double distance_;
  double cruise_rate_;
  double ramp_time_s_;
  double cruise_time_s_;
};

}  // namespace geaware::traj
