// SPDX-License-Identifier: BSD-3-Clause
// geaware's simulator from user code: the paper's quadrotor as built (a truth file, or the
// built-in one) flies the 0.12 m, 1 m/s lemniscate with the recommended controller; an observer
// sees every control tick, the result has the tracking error and any ground strike.
#include <algorithm>
#include <cstdio>
#include <memory>

#include <geaware/experiments/flight.hpp>
#include <geaware/experiments/world_setup.hpp>
#include <geaware/io/truth_file.hpp>
#include <geaware/io/vehicle_file.hpp>
#include <geaware/traj/lemniscate.hpp>

namespace {
// Lowest true rotor-plane height during the trajectory.
struct LowestHeight final : geaware::experiments::FlightObserver {
  double min_m = 1e9;
  void onTick(const geaware::experiments::FlightTick& t) noexcept override {
    if (t.in_trajectory) min_m = std::min(min_m, t.true_height_m);
  }
};
}  // namespace

int main(int argc, char** argv) {
  using namespace geaware;
  const sim::World world = argc > 1 ? io::loadTruthFile(argv[1]) : io::builtinTruth("as_built");
  experiments::FlightScenario s;
  s.vehicle = io::builtinVehicle();  // what the controller believes
  experiments::applyWorld(s, world);  // what it flies in
  traj::LemniscateParams path;
  path.half_extent_x_m = 1.5;
  path.half_extent_y_m = 0.8;
  path.height_m = 0.12;
  path.peak_speed_mps = 1.0;
  s.trajectory = std::make_shared<traj::Lemniscate>(path);
  s.controller = control::recommendedControllerParams();
  s.seed = 1;

  LowestHeight lowest;
  const experiments::FlightResult r = experiments::runFlight(s, &lowest);
  std::printf("world: %s\n", world.source.c_str());
  std::printf("RMSE all %.2f cm, lowest rotor plane %.3f m, %s\n",
              100.0 * r.tracking.rmse_all_m, lowest.min_m,
              r.crash ? r.crash_description.c_str() : "no strike");
  return r.completed ? 0 : 1;
}
