// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Flight scenarios shared by the experiments tests: the paper's lemniscate on the built-in vehicle.

#include <memory>

#include "geaware/experiments/flight.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/traj/lemniscate.hpp"

namespace geaware::experiments::test {

using control::AccelerationCompensation;
using control::TorqueCompensation;

inline std::shared_ptr<const traj::Trajectory> lemniscate(double height_m, double speed_mps) {
  traj::LemniscateParams p;
  p.half_extent_x_m = 1.5;
  p.half_extent_y_m = 0.8;
  p.height_m = height_m;
  p.peak_speed_mps = speed_mps;
  p.laps = 1;
  return std::make_shared<traj::Lemniscate>(p);
}

inline FlightScenario scenario(double height_m, AccelerationCompensation acc, TorqueCompensation torque) {
  FlightScenario s;
  s.vehicle = io::builtinVehicle();
  s.trajectory = lemniscate(height_m, 1.0);
  s.controller.acceleration = acc;
  s.controller.torque = torque;
  return s;
}

}  // namespace geaware::experiments::test
