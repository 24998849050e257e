// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The calibration's flights in the world (experiments/calibration.hpp, steps 7 and 8): a hover
// out of ground effect for k_T in flight, and the drag flights at two heights for D(h). Each is
// flown with the belief as it stands, logged as a team logs it (the controller's own inputs:
// ranger height, estimated velocity and attitude, bias-corrected IMU, rotor telemetry; never the
// truth) and identified with ident's flight fits.

#include <vector>

#include "geaware/experiments/calibration.hpp"
#include "geaware/ident/flight_fit.hpp"
#include "geaware/ident/imu_noise.hpp"
#include "geaware/model/vehicle_params.hpp"

namespace geaware::experiments::detail {

struct HoverCalibration {
  ident::HoverThrustFit fit;
  ident::ImuNoiseFit imu_noise;  ///< the estimator's process noise, from the same hover
  CalibrationFlight flight;
};

/// Step 7: flies the hover with `belief` in `world` and fits k_T (belief's mass, k_T and F_G
/// for the observer's split). Throws std::runtime_error on a strike, ident::IdentError when the
/// fit fails.
[[nodiscard]] HoverCalibration calibrateHover(const model::VehicleParams& belief,
                                              const CalibrationWorld& world,
                                              const CalibrationSweeps& sweeps);

struct DragCalibration {
  std::vector<ident::DragBand> bands;  ///< one per height, lowest first
  std::vector<CalibrationFlight> flights;
  std::vector<std::string> warnings;
};

/// Step 8: the drag flights with `belief`, one band fitted per flight. Throws as calibrateHover.
[[nodiscard]] DragCalibration calibrateDrag(const model::VehicleParams& belief,
                                            const CalibrationWorld& world,
                                            const CalibrationSweeps& sweeps);

}  // namespace geaware::experiments::detail
