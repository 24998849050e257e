// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Physical constants and unit conversions used across geaware. SI everywhere, except rotor
// speed, which is in revolutions per minute (rpm) as in the paper.

#include <numbers>

namespace geaware::model {

/// Standard gravity [m/s^2]. The paper's hover check (m·g = 16.64 N at m = 1.696 kg) uses 9.81.
inline constexpr double kGravity = 9.81;

/// rpm → rad/s.
inline constexpr double kRpmToRadPerSec = 2.0 * std::numbers::pi / 60.0;

/// Degrees → radians.
inline constexpr double kDegToRad = std::numbers::pi / 180.0;

}  // namespace geaware::model
