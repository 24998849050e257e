// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Building a flight from the command line's terms: the trajectory from a few numbers, its
// one-line description, the Neural-Lander network from a weight file.

#include <memory>
#include <string>

#include "geaware/control/residual_force.hpp"
#include "geaware/traj/trajectory.hpp"

namespace geaware::experiments {

/// A lemniscate (Table I), a hover descent (the hover experiment), a landing or a take-off
/// (issue 13 item 5; traj/touchdown.hpp).
struct TrajectoryOptions {
  bool lemniscate = true;
  /// When not a lemniscate: "hover-descent", "landing" or "takeoff".
  std::string kind = "hover-descent";
  double height_m = 0.0;     ///< lemniscate height / final height of the descent [m]
  double speed_mps = 0.0;    ///< lemniscate peak speed / descent rate (NaN: default) [m/s]
  double extent_x_m = 1.5;   ///< lemniscate half extents [m]
  double extent_y_m = 0.8;
  int laps = 1;
  double height_swing_m = 0.0;  ///< lemniscate: the height's swing over each lap (traj::LemniscateParams) [m]
  double from_height_m = 1.5;  ///< descent (and landing) start height [m]
  /// Landing and take-off: the rotor plane's z standing on the gear, the vehicle file's
  /// min_rotor_plane_height_m over flat ground at z = 0 [m].
  double touchdown_height_m = 0.0;
  double touchdown_speed_mps = 0.1;  ///< landing: the reference's sinking speed at touchdown [m/s]
  double flare_height_m = 0.3;       ///< landing: flare start above the touchdown height [m]
};


[[nodiscard]] std::shared_ptr<const traj::Trajectory> makeTrajectory(const TrajectoryOptions& o);

/// e.g. "lemniscate ±1.5 m × ±0.8 m at 0.12 m, 1 m/s peak, 1 lap".
[[nodiscard]] std::string describe(const TrajectoryOptions& o);

/// The Neural-Lander residual network of a weight file (neural::saveWeights' format).
[[nodiscard]] std::shared_ptr<const control::ResidualForceModel> loadResidualNetwork(
    const std::string& weights_file);

}  // namespace geaware::experiments
