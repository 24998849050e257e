// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Minimum-snap piecewise polynomials through waypoints, with fixed segment durations.
//
// Each of the four flat outputs (x, y, z, ψ) is, on each segment, the degree-7 polynomial that
// the Euler–Lagrange equation of min ∫‖p⁗‖² dt gives (p⁽⁸⁾ = 0). The 8 coefficients per segment
// and dimension are fixed by:
//   - start and end: the waypoint, and zero velocity, acceleration and jerk (rest to rest);
//   - each interior waypoint: the position, and continuity of derivatives 0…6.
// Continuity up to 2·4 − 2 = 6 is the optimality condition of the unconstrained problem with
// interior positions fixed (Wang et al., "Geometrically Constrained Trajectory Optimization for
// Multicopters", IEEE T-RO 2022: MINCO; GCOPTER's MINCO_S4NU in minco.hpp builds the same
// system and solves it with a banded LU). Here the 8M×8M system is built once, at
// construction, with time normalised per segment, and solved by a dense partial-pivot LU for
// all four dimensions at once; M is a few tens at most for our scenarios.
//
// Note the ends: velocity, acceleration and jerk start and end at 0 but snap does not, so a
// controller fed from rest sees a step in snap at t = 0 and at the end. Yaw is interpolated
// as the numbers given (no wrapping): unwrap the waypoints' yaw before building.

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geaware/traj/trajectory.hpp"

namespace geaware::traj {

/// One waypoint of a minimum-snap trajectory.
struct Waypoint {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  ///< position, world frame [m]
  double yaw_rad = 0.0;                           ///< yaw ψ [rad], not wrapped
};

class MinSnapTrajectory final : public Trajectory {
 public:
  /// Trajectory through `waypoints` with segment i (from waypoint i to i+1) lasting
  /// segment_durations_s[i] [s]. Throws std::invalid_argument listing every problem
  /// validate() reports; throws std::runtime_error if the linear solve fails numerically
  /// (durations of wildly different magnitudes).
  MinSnapTrajectory(std::vector<Waypoint> waypoints, std::vector<double> segment_durations_s);

  /// Durations proportional to the position distance between consecutive waypoints,
  /// T_i = max(‖p_{i+1} − p_i‖ / average_speed_mps, min_segment_duration_s), so a repeated
  /// waypoint (or a yaw-only turn) gets the floor. The actual peak speed is higher than the
  /// average: each segment is traversed on a smooth polynomial, and the ends are at rest.
  /// Throws std::invalid_argument as the constructor, and unless both numbers are finite > 0.
  [[nodiscard]] static MinSnapTrajectory fromAverageSpeed(std::vector<Waypoint> waypoints,
                                                          double average_speed_mps,
                                                          double min_segment_duration_s = 0.5);

  /// Every problem with the inputs as "field = value (expected ...)"; empty when usable.
  [[nodiscard]] static std::vector<std::string> validate(
      const std::vector<Waypoint>& waypoints, const std::vector<double>& segment_durations_s);

  /// Flat outputs at t [s]. Evaluates the segment's polynomial (Horner) on [0, duration()];
  /// strictly outside it returns the end state at rest (all derivatives 0, including snap,
  /// which is not 0 at the ends themselves). Does not allocate.
  [[nodiscard]] FlatOutput sample(double t_s) const noexcept override;
  [[nodiscard]] double duration() const noexcept override { return start_times_s_.back(); }

  [[nodiscard]] const std::vector<Waypoint>& waypoints() const noexcept { return waypoints_; }
  [[nodiscard]] const std::vector<double>& segmentDurations() const noexcept {
    return durations_s_;
  }
  /// Time at which each waypoint is reached [s]: 0, T_0, T_0 + T_1, …, duration().
  [[nodiscard]] const std::vector<double>& waypointTimes() const noexcept { return start_times_s_; }

 private:
  static constexpr int kOrder = 8;   // coefficients per segment (degree 7)
  static constexpr int kDims = 4;    // x, y, z, ψ
  static constexpr int kDerivs = 5;  // derivatives 0…4 kept for sampling
  using Coeffs = Eigen::Matrix<double, kOrder, kDims>;

  std::vector<Waypoint> waypoints_;
  std::vector<double> durations_s_;
  std::vector<double> start_times_s_;  // size M + 1, cumulative
  // Per segment, per derivative r: row k holds the coefficient of x^k in dʳp/dxʳ, with
  // x = τ/T ∈ [0, 1] the normalised segment time (normalising keeps the system well scaled).
  std::vector<std::array<Coeffs, kDerivs>> derivative_coeffs_;
};

}  // namespace geaware::traj
