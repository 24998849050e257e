// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/flight_setup.hpp"

#include <fmt/format.h>

#include <cmath>

#include "geaware/neural/residual_network.hpp"
#include "geaware/neural/weights_file.hpp"
#include "geaware/traj/hover_descent.hpp"
#include "geaware/traj/lemniscate.hpp"

namespace geaware::experiments {

std::shared_ptr<const traj::Trajectory> makeTrajectory(const TrajectoryOptions& o) {
  if (o.lemniscate) {
    traj::LemniscateParams p;
    p.half_extent_x_m = o.extent_x_m;
    p.half_extent_y_m = o.extent_y_m;
    p.height_m = o.height_m;
    p.peak_speed_mps = o.speed_mps;
    p.laps = o.laps;
    return std::make_shared<traj::Lemniscate>(p);
  }
  traj::HoverDescentParams p;
  p.from_height_m = o.from_height_m;
  p.to_height_m = o.height_m;
  if (std::isfinite(o.speed_mps)) p.descent_rate_mps = o.speed_mps;
  return std::make_shared<traj::HoverDescent>(p);
}

std::string describe(const TrajectoryOptions& o) {
  if (o.lemniscate) {
    return fmt::format("lemniscate ±{} m × ±{} m at {} m, {} m/s peak, {} lap{}", o.extent_x_m,
                       o.extent_y_m, o.height_m, o.speed_mps, o.laps, o.laps == 1 ? "" : "s");
  }
  return fmt::format(
      "hover descent {} m → {} m at {} m/s", o.from_height_m, o.height_m,
      std::isfinite(o.speed_mps) ? o.speed_mps : traj::HoverDescentParams{}.descent_rate_mps);
}

std::shared_ptr<const control::ResidualForceModel> loadResidualNetwork(const std::string& weights_file) {
  return std::make_shared<neural::ResidualNetwork>(neural::loadWeights(weights_file).weights);
}

}  // namespace geaware::experiments
