#include "geaware/sim/imu.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "geaware/model/field_check.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::sim {

std::vector<model::FieldError> ImuParams::validate() const {
  std::vector<model::FieldError> out;
  model::FieldChecker c(out);
  using enum model::LowerBound;
  c.range("rate_Hz", rate_Hz, 0.0, 1e5, kExclusive, "Hz");
  c.nonNegative("gyro_noise_density_rad_per_s_sqrtHz", gyro_noise_density_rad_per_s_sqrtHz, "rad/s/√Hz");
  c.nonNegative("gyro_bias_walk_rad_per_s2_sqrtHz", gyro_bias_walk_rad_per_s2_sqrtHz, "rad/s²/√Hz");
  c.nonNegative("gyro_initial_bias_std_rad_per_s", gyro_initial_bias_std_rad_per_s, "rad/s");
  c.nonNegative("accel_noise_density_m_per_s2_sqrtHz", accel_noise_density_m_per_s2_sqrtHz, "m/s²/√Hz");
  c.nonNegative("accel_bias_walk_m_per_s3_sqrtHz", accel_bias_walk_m_per_s3_sqrtHz, "m/s³/√Hz");
  c.nonNegative("accel_initial_bias_std_m_per_s2", accel_initial_bias_std_m_per_s2, "m/s²");
  c.range("gyro_range_rad_per_s", gyro_range_rad_per_s, 0.0, 1e4, kExclusive, "rad/s");
  c.range("accel_range_m_per_s2", accel_range_m_per_s2, 0.0, 1e5, kExclusive, "m/s²");
  c.finite("lever_arm_B_m", lever_arm_B_m, "m");
  c.range("gravity_mps2", gravity_mps2, 0.0, 100.0, kInclusive, "m/s²");
  return out;
}

Imu::Imu(const ImuParams& params, std::uint64_t scenario_seed)
    : params_(model::validated(params)),
      noise_(scenario_seed, salt::kImu),
      clock_(params_.rate_Hz),
      gyro_white_std_(params_.gyro_noise_density_rad_per_s_sqrtHz * std::sqrt(params_.rate_Hz)),
      accel_white_std_(params_.accel_noise_density_m_per_s2_sqrtHz * std::sqrt(params_.rate_Hz)) {
  gyro_bias_B_ = params_.gyro_initial_bias_std_rad_per_s * noise_.normal3();
  accel_bias_B_ = params_.accel_initial_bias_std_m_per_s2 * noise_.normal3();
}

std::optional<model::ImuSample> Imu::sample(const PlantState& s) noexcept {
  if (!isFinite(s)) {
    ++rejected_;
    return std::nullopt;
  }
  if (!clock_.due(s.t_s)) return std::nullopt;

  // 1. Bias random walk over the time since the last sample (none before the first).
  const double dt_s = last_t_s_ ? std::max(0.0, s.t_s - *last_t_s_) : 0.0;
  last_t_s_ = s.t_s;
  const double sqrt_dt = std::sqrt(dt_s);
  gyro_bias_B_ += params_.gyro_bias_walk_rad_per_s2_sqrtHz * sqrt_dt * noise_.normal3();
  accel_bias_B_ += params_.accel_bias_walk_m_per_s3_sqrtHz * sqrt_dt * noise_.normal3();

  // 2. Specific force at the IMU: Rᵀ(a_imu + g·z_W), a_imu including the lever-arm terms.
  const Eigen::Matrix3d R_WB = s.q_WB.normalized().toRotationMatrix();
  const Eigen::Vector3d& r = params_.lever_arm_B_m;
  Eigen::Vector3d a_B = R_WB.transpose() * s.a_W + s.w_dot_B.cross(r) + s.w_B.cross(s.w_B.cross(r));
  a_B += R_WB.row(2).transpose() * params_.gravity_mps2;  // Rᵀ·g·z_W

  // 3. Bias, white noise and saturation.
  model::ImuSample out;
  out.t_s = s.t_s;
  const double g_max = params_.gyro_range_rad_per_s;
  const double a_max = params_.accel_range_m_per_s2;
  out.gyro_B = (s.w_B + gyro_bias_B_ + gyro_white_std_ * noise_.normal3()).cwiseMax(-g_max).cwiseMin(g_max);
  out.accel_B = (a_B + accel_bias_B_ + accel_white_std_ * noise_.normal3()).cwiseMax(-a_max).cwiseMin(a_max);
  return out;
}

}  // namespace geaware::sim
