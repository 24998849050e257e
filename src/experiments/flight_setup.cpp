// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/flight_setup.hpp"

#include <fmt/format.h>

#include <cmath>

#include "geaware/neural/residual_network.hpp"
#include "geaware/neural/weights_file.hpp"
#include "geaware/traj/hover_descent.hpp"
#include "geaware/traj/lemniscate.hpp"
#include "geaware/traj/touchdown.hpp"

namespace geaware::experiments {

std::shared_ptr<const traj::Trajectory> makeTrajectory(const TrajectoryOptions& o) {
  if (o.lemniscate) {
    traj::LemniscateParams p;
    p.half_extent_x_m = o.extent_x_m;
    p.half_extent_y_m = o.extent_y_m;
    p.height_m = o.height_m;
    p.peak_speed_mps = o.speed_mps;
    p.laps = o.laps;
    p.height_swing_m = o.height_swing_m;
    return std::make_shared<traj::Lemniscate>(p);
  }
  if (o.kind == "landing") {
    traj::LandingParams p;
    p.from_height_m = o.from_height_m;
    p.touchdown_height_m = o.touchdown_height_m;
    if (std::isfinite(o.speed_mps)) p.descent_rate_mps = o.speed_mps;
    p.touchdown_speed_mps = o.touchdown_speed_mps;
    p.flare_height_m = o.flare_height_m;
    return std::make_shared<traj::Landing>(p);
  }
  if (o.kind == "takeoff") {
    traj::TakeOffParams p;
    p.touchdown_height_m = o.touchdown_height_m;
    p.to_height_m = o.height_m;
    if (std::isfinite(o.speed_mps)) p.climb_rate_mps = o.speed_mps;
    return std::make_shared<traj::TakeOff>(p);
  }
  traj::HoverDescentParams p;
  p.from_height_m = o.from_height_m;
  p.to_height_m = o.height_m;
  if (std::isfinite(o.speed_mps)) p.descent_rate_mps = o.speed_mps;
  return std::make_shared<traj::HoverDescent>(p);
}

std::string describe(const TrajectoryOptions& o) {
  if (o.lemniscate) {
    const std::string at = o.height_swing_m > 0.0
                               ? fmt::format("{}–{:.6g} m", o.height_m, o.height_m + o.height_swing_m)
                               : fmt::format("{} m", o.height_m);
    return fmt::format("lemniscate ±{} m × ±{} m at {}, {} m/s peak, {} lap{}", o.extent_x_m,
                       o.extent_y_m, at, o.speed_mps, o.laps, o.laps == 1 ? "" : "s");
  }
  if (o.kind == "landing") {
    return fmt::format("landing from {} m at {} m/s, flare from {} m above the gear to {} m/s",
                       o.from_height_m,
                       std::isfinite(o.speed_mps) ? o.speed_mps : traj::LandingParams{}.descent_rate_mps,
                       o.flare_height_m, o.touchdown_speed_mps);
  }
  if (o.kind == "takeoff") {
    return fmt::format("take-off to {} m at {} m/s", o.height_m,
                       std::isfinite(o.speed_mps) ? o.speed_mps : traj::TakeOffParams{}.climb_rate_mps);
  }
  return fmt::format(
      "hover descent {} m → {} m at {} m/s", o.from_height_m, o.height_m,
      std::isfinite(o.speed_mps) ? o.speed_mps : traj::HoverDescentParams{}.descent_rate_mps);
}

std::shared_ptr<const control::ResidualForceModel> loadResidualNetwork(const std::string& weights_file) {
  return std::make_shared<neural::ResidualNetwork>(neural::loadWeights(weights_file).weights);
}

}  // namespace geaware::experiments
