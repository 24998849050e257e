// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Identification's fits as a vehicle-file update: each function sets the keys its fit
// determines, with their standard errors, in an io::VehicleUpdate that io::writeVehicleFile
// merges into a base vehicle file (include/geaware/io/vehicle_writer.hpp).

#include <string>

#include "geaware/ident/flight_fit.hpp"
#include "geaware/ident/least_squares.hpp"
#include "geaware/ident/leveling_fit.hpp"
#include "geaware/ident/platform_fit.hpp"
#include "geaware/ident/rotor_fit.hpp"
#include "geaware/io/vehicle_writer.hpp"

namespace geaware::ident {

/// Sets a scalar key to an estimate and its standard error.
inline void setEstimate(io::VehicleUpdate& update, const std::string& key, const Estimate& e) {
  update.set(key, e.value, e.std_error);
}

/// k_T, k_I, J_R (when fitted) and the throttle curve.
void addRotorFit(io::VehicleUpdate& update, const RotorFit& fit);
/// g1, g2 and, with include_k_T, the k_T fitted with them.
void addAdditionalThrust(io::VehicleUpdate& update, const AdditionalThrustFit& fit,
                         bool include_k_T = true);
/// k_TX, k_TY, k_I where fitted.
void addMixing(io::VehicleUpdate& update, const MixingFit& fit);
/// g3, g4, scale (the scale belongs to the k_T the fit used: merge that k_T with it).
void addLeveling(io::VehicleUpdate& update, const LevelingFit& fit);
void addDrag(io::VehicleUpdate& update, const DragFit& fit);

}  // namespace geaware::ident
