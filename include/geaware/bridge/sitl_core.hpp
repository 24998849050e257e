// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The truth side of a flight without DDS, for `geaware sitl`: the stepped world of the
// experiments layer (experiments/stepped_world.hpp), the plant, disturbances and sensors of the
// scenario's world stepped like the in-process runner with the throttles PX4 would send. The
// estimator and controller are somewhere else (a bridge process).

#include "geaware/experiments/stepped_world.hpp"

namespace geaware::bridge {

using SitlCore = experiments::SteppedWorld;

}  // namespace geaware::bridge
