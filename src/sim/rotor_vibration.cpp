// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/sim/rotor_vibration.hpp"

#include <cmath>
#include <algorithm>
#include <numbers>

namespace geaware::sim {

RotorVibration::RotorVibration(const RotorVibrationParams& params, std::uint64_t scenario_seed) noexcept
    : params_(params) {
  const double per_rotor = std::sqrt(2.0 / kRotors);
  accel_amplitude_ = params_.accel_std_m_per_s2 * per_rotor;
  gyro_amplitude_ = params_.gyro_std_rad_per_s * per_rotor;
  NoiseSource draw(scenario_seed, salt::kImuRotorVibration);
  for (auto& rotor : offset_rad_) {
    for (double& o : rotor) o = 2.0 * std::numbers::pi * draw.uniformHalfOpen();
  }
}

void RotorVibration::advance(const PlantState& s) noexcept {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  const double dt_s = started_ ? std::max(0.0, s.t_s - last_t_s_) : 0.0;
  started_ = true;
  last_t_s_ = s.t_s;
  const double blades = params_.blade_count;
  accel_B_.setZero();
  gyro_B_.setZero();
  for (int i = 0; i < kRotors; ++i) {
    const double n_rpm = s.n_rpm[static_cast<std::size_t>(i)];
    double& phi = phase_rad_[static_cast<std::size_t>(i)];
    phi = std::fmod(phi + kTwoPi * (n_rpm / 60.0) * dt_s, kTwoPi);
    const double r = n_rpm / params_.reference_rpm;
    const double scale = r * r;
    const auto& o = offset_rad_[static_cast<std::size_t>(i)];
    const double passage = blades * phi;
    // Only the streams that are on: the trigonometry is most of this function's cost.
    if (accel_amplitude_ > 0.0) {
      const double once = phi + o[0];
      accel_B_ += accel_amplitude_ * scale *
                  Eigen::Vector3d(std::cos(once), std::sin(once), std::cos(passage + o[1]));
    }
    if (gyro_amplitude_ > 0.0) {
      gyro_B_ += gyro_amplitude_ * scale *
                 Eigen::Vector3d(std::cos(passage + o[2]), std::cos(passage + o[3]), std::cos(phi + o[4]));
    }
  }
}

}  // namespace geaware::sim
