// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Plausibility limits of IMU readings: the widest full-scale ranges of MEMS IMUs, ±4000 °/s and
// ±32 g (TDK ICM-42686-P; the BMI088 of the estimator's noise model reads ±2000 °/s and ±24 g).
// A larger value is no measurement: the controller and the estimators refuse it like a NaN,
// before it reaches a filter (issue 16 item 3, docs/reliability.md §6).

#include <Eigen/Core>

#include "geaware/model/finite.hpp"
#include "geaware/model/units.hpp"

namespace geaware::model {

inline constexpr double kImuMaxRateRadps = 4000.0 * kDegToRad;   ///< gyro full scale [rad/s]
inline constexpr double kImuMaxSpecificForceMps2 = 32.0 * kGravity;  ///< accel full scale [m/s²]

/// Whether a gyro and an accelerometer reading are finite and within the full scales above.
[[nodiscard]] inline bool plausibleImu(const Eigen::Vector3d& gyro_radps,
                                       const Eigen::Vector3d& accel_mps2) noexcept {
  return model::allFinite(gyro_radps) && model::allFinite(accel_mps2) &&
         gyro_radps.cwiseAbs().maxCoeff() <= kImuMaxRateRadps &&
         accel_mps2.cwiseAbs().maxCoeff() <= kImuMaxSpecificForceMps2;
}

}  // namespace geaware::model
