// SPDX-License-Identifier: BSD-3-Clause
// The ESKF's parameter checks and status names (kept apart from the filter's arithmetic).
#include <cmath>
#include <string>

#include "geaware/estimation/eskf.hpp"
#include "geaware/model/field_check.hpp"

namespace geaware::estimation {

const char* toString(EskfStatus s) noexcept {
  switch (s) {
    case EskfStatus::kOk:
      return "ok";
    case EskfStatus::kNotInitialised:
      return "not initialised";
    case EskfStatus::kInitialised:
      return "initialised";
    case EskfStatus::kNonFinite:
      return "non-finite sample";
    case EskfStatus::kTimeNotIncreasing:
      return "time not increasing";
    case EskfStatus::kTooOld:
      return "too old";
    case EskfStatus::kDeferred:
      return "deferred";
    case EskfStatus::kGateRejected:
      return "gate rejected";
    case EskfStatus::kQueueFull:
      return "deferred queue full";
  }
  return "?";
}

std::vector<model::FieldError> EskfParams::validate() const {
  std::vector<model::FieldError> e;
  model::FieldChecker c(e);
  c.positive("eskf.imu_rate_hz", imu_rate_hz);
  c.positive("eskf.accel_noise_density", accel_noise_density);
  c.positive("eskf.gyro_noise_density", gyro_noise_density);
  c.positive("eskf.accel_bias_random_walk", accel_bias_random_walk);
  c.positive("eskf.gyro_bias_random_walk", gyro_bias_random_walk);
  c.positive("eskf.mocap_position_std_m", mocap_position_std_m);
  c.positive("eskf.mocap_attitude_std_rad", mocap_attitude_std_rad);
  c.positive("eskf.init_position_std_m", init_position_std_m);
  c.positive("eskf.init_velocity_std_mps", init_velocity_std_mps);
  c.positive("eskf.init_attitude_std_rad", init_attitude_std_rad);
  c.positive("eskf.init_accel_bias_std_mps2", init_accel_bias_std_mps2);
  c.positive("eskf.init_gyro_bias_std_radps", init_gyro_bias_std_radps);
  c.positive("eskf.gate_chi2", gate_chi2);
  c.positive("eskf.max_imu_gap_s", max_imu_gap_s);
  c.positive("eskf.pose_timeout_s", pose_timeout_s);
  c.positive("eskf.imu_gyro_range_rad_per_s", imu_gyro_range_rad_per_s);
  c.positive("eskf.imu_accel_range_m_per_s2", imu_accel_range_m_per_s2);
  c.positive("eskf.gravity_mps2", gravity_mps2);
  if (max_consecutive_rejections < 0) {
    c.fail("eskf.max_consecutive_rejections", std::to_string(max_consecutive_rejections),
           "an integer ≥ 0 (0 disables the recovery)");
  }
  // The history must reach back over the largest latency, with a margin of two samples for the
  // interpolation and for jitter.
  const double reach_s = (Eskf::kHistory - 2) / imu_rate_hz;
  if (!(std::isfinite(max_mocap_latency_s) && max_mocap_latency_s >= 0.0 &&
        max_mocap_latency_s <= reach_s)) {
    c.fail(
        "eskf.max_mocap_latency_s", model::formatValue(max_mocap_latency_s),
        "a number in [0, " + model::formatValue(reach_s) + "] (the history buffer at imu_rate_hz)");
  }
  return e;
}

}  // namespace geaware::estimation
