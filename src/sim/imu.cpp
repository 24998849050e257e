// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/sim/imu.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <numbers>
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
  c.nonNegative("vibration_gyro_std_rad_per_s", vibration_gyro_std_rad_per_s, "rad/s");
  c.nonNegative("vibration_accel_std_m_per_s2", vibration_accel_std_m_per_s2, "m/s²");
  const bool rate_ok = c.range("filter_rate_Hz", filter_rate_Hz, 0.0, 1e5, kExclusive, "Hz");
  if (rate_ok && c.range("lowpass_cutoff_Hz", lowpass_cutoff_Hz, 0.0, 0.45 * filter_rate_Hz,
                         kInclusive, "Hz (0: off; below 0.45·filter_rate_Hz)")) {
    if (lowpass_cutoff_Hz > 0.0 && std::isfinite(rate_Hz) && filter_rate_Hz < rate_Hz) {
      c.fail("filter_rate_Hz", model::formatValue(filter_rate_Hz),
             "at least rate_Hz = " + model::formatValue(rate_Hz));
    }
  }
  const RotorVibrationParams& rv = rotor_vibration;
  c.range("rotor_vibration_accel_std_m_per_s2", rv.accel_std_m_per_s2, 0.0, 1e3, kInclusive, "m/s²");
  c.range("rotor_vibration_gyro_std_rad_per_s", rv.gyro_std_rad_per_s, 0.0, 100.0, kInclusive, "rad/s");
  c.range("rotor_vibration_reference_rpm", rv.reference_rpm, 0.0, 1e6, kExclusive, "rpm");
  if (rv.blade_count < 1 || rv.blade_count > 12) {
    c.fail("rotor_vibration_blade_count", std::to_string(rv.blade_count), "an integer in [1, 12]");
  }
  return out;
}

LowPass2::LowPass2(double sample_rate_Hz, double cutoff_Hz) noexcept : sample_rate_Hz_(sample_rate_Hz) {
  const double ohm = std::tan(std::numbers::pi * cutoff_Hz / sample_rate_Hz);
  const double k = 2.0 * std::cos(std::numbers::pi / 4.0) * ohm;  // √2·Ω
  const double c = 1.0 + k + ohm * ohm;
  b0_ = ohm * ohm / c;
  b1_ = 2.0 * b0_;
  b2_ = b0_;
  a1_ = 2.0 * (ohm * ohm - 1.0) / c;
  a2_ = (1.0 - k + ohm * ohm) / c;
  group_delay_s_ = (1.0 - (a1_ + 2.0 * a2_) / (1.0 + a1_ + a2_)) / sample_rate_Hz;
  // Σ h_k² from the impulse response (decays geometrically; the sum settles long before).
  double w1 = 0.0;
  double w2 = 0.0;
  double sum = 0.0;
  for (int k_s = 0; k_s < 1'000'000; ++k_s) {
    const double w0 = (k_s == 0 ? 1.0 : 0.0) - a1_ * w1 - a2_ * w2;
    const double h = b0_ * w0 + b1_ * w1 + b2_ * w2;
    sum += h * h;
    w2 = w1;
    w1 = w0;
    if (k_s > 8 && h * h < 1e-20 * sum && w1 * w1 + w2 * w2 < 1e-20) break;
  }
  noise_gain_ = sum;
}

double LowPass2::gainAt(double frequency_Hz) const noexcept {
  // H(z) = (b0 + b1 z⁻¹ + b2 z⁻²)/(1 + a1 z⁻¹ + a2 z⁻²) on the unit circle.
  const std::complex<double> z1 = std::polar(1.0, -2.0 * std::numbers::pi * frequency_Hz / sample_rate_Hz_);
  const std::complex<double> z2 = z1 * z1;
  return std::abs((b0_ + b1_ * z1 + b2_ * z2) / (1.0 + a1_ * z1 + a2_ * z2));
}

void LowPass2::reset(const Eigen::Vector3d& x) noexcept {
  d1_ = x / (1.0 + a1_ + a2_);  // the steady state of the delay line for a constant input
  d2_ = d1_;
  y_ = x;
}

const Eigen::Vector3d& LowPass2::apply(const Eigen::Vector3d& x) noexcept {
  const Eigen::Vector3d d0 = x - a1_ * d1_ - a2_ * d2_;
  y_ = b0_ * d0 + b1_ * d1_ + b2_ * d2_;
  d2_ = d1_;
  d1_ = d0;
  return y_;
}

Imu::Imu(const ImuParams& params, std::uint64_t scenario_seed)
    : params_(model::validated(params)),
      noise_(scenario_seed, salt::kImu),
      clock_(params_.rate_Hz),
      gyro_white_std_(params_.gyro_noise_density_rad_per_s_sqrtHz * std::sqrt(params_.rate_Hz)),
      accel_white_std_(params_.accel_noise_density_m_per_s2_sqrtHz * std::sqrt(params_.rate_Hz)),
      vibration_noise_(scenario_seed, salt::kImuVibration),
      raw_clock_(params_.filter_rate_Hz) {
  gyro_bias_B_ = params_.gyro_initial_bias_std_rad_per_s * noise_.normal3();
  accel_bias_B_ = params_.accel_initial_bias_std_m_per_s2 * noise_.normal3();
  gyro_vibration_std_ = params_.vibration_gyro_std_rad_per_s;
  accel_vibration_std_ = params_.vibration_accel_std_m_per_s2;
  if (params_.rotor_vibration.enabled()) rotor_vibration_.emplace(params_.rotor_vibration, scenario_seed);
  if (params_.lowpass_cutoff_Hz > 0.0) {
    gyro_lp_.emplace(params_.filter_rate_Hz, params_.lowpass_cutoff_Hz);
    accel_lp_.emplace(params_.filter_rate_Hz, params_.lowpass_cutoff_Hz);
    // The std asked for is what the filter lets through: scale the raw noise up by 1/√gain.
    const double raw_per_output = 1.0 / std::sqrt(gyro_lp_->noiseGain());
    gyro_vibration_std_ *= raw_per_output;
    accel_vibration_std_ *= raw_per_output;
  }
}

Eigen::Vector3d Imu::specificForce(const PlantState& s) const noexcept {
  const Eigen::Matrix3d R_WB = s.q_WB.normalized().toRotationMatrix();
  const Eigen::Vector3d& r = params_.lever_arm_B_m;
  Eigen::Vector3d a_B = R_WB.transpose() * s.a_W + s.w_dot_B.cross(r) + s.w_B.cross(s.w_B.cross(r));
  a_B += R_WB.row(2).transpose() * params_.gravity_mps2;  // Rᵀ·g·z_W
  return a_B;
}

void Imu::filterRaw(const PlantState& s) noexcept {
  Eigen::Vector3d w = s.w_B;
  Eigen::Vector3d a = specificForce(s);
  if (!filter_started_) {
    // Start in the steady state of the vibration-free signal (the vibration's mean is 0); a
    // start on a vibrated sample would hold its offset (tens of m/s² at the rotor harmonics)
    // through the filter's first time constants.
    gyro_lp_->reset(w);
    accel_lp_->reset(a);
    filter_started_ = true;
  }
  if (gyro_vibration_std_ > 0.0) w += gyro_vibration_std_ * vibration_noise_.normal3();
  if (accel_vibration_std_ > 0.0) a += accel_vibration_std_ * vibration_noise_.normal3();
  if (rotor_vibration_) {
    rotor_vibration_->advance(s);
    w += rotor_vibration_->gyro_B();
    a += rotor_vibration_->accel_B();
  }
  (void)gyro_lp_->apply(w);
  (void)accel_lp_->apply(a);
}

std::optional<model::ImuSample> Imu::sample(const PlantState& s) noexcept {
  if (!isFinite(s)) {
    ++rejected_;
    return std::nullopt;
  }
  if (gyro_lp_ && raw_clock_.due(s.t_s)) filterRaw(s);
  if (!clock_.due(s.t_s)) return std::nullopt;

  // 1. Bias random walk over the time since the last sample (none before the first).
  const double dt_s = last_t_s_ ? std::max(0.0, s.t_s - *last_t_s_) : 0.0;
  last_t_s_ = s.t_s;
  const double sqrt_dt = std::sqrt(dt_s);
  gyro_bias_B_ += params_.gyro_bias_walk_rad_per_s2_sqrtHz * sqrt_dt * noise_.normal3();
  accel_bias_B_ += params_.accel_bias_walk_m_per_s3_sqrtHz * sqrt_dt * noise_.normal3();

  // 2. Rate and specific force at the IMU: the flight controller's filtered values, or the
  //    truth (plus vibration, per output sample, when there is no filter).
  Eigen::Vector3d w_B = s.w_B;
  Eigen::Vector3d a_B;
  if (gyro_lp_) {
    w_B = gyro_lp_->value();
    a_B = accel_lp_->value();
  } else {
    a_B = specificForce(s);
    if (gyro_vibration_std_ > 0.0) w_B += gyro_vibration_std_ * vibration_noise_.normal3();
    if (accel_vibration_std_ > 0.0) a_B += accel_vibration_std_ * vibration_noise_.normal3();
    if (rotor_vibration_) {
      rotor_vibration_->advance(s);
      w_B += rotor_vibration_->gyro_B();
      a_B += rotor_vibration_->accel_B();
    }
  }

  // 3. Bias, white noise and saturation.
  model::ImuSample out;
  out.t_s = s.t_s;
  const double g_max = params_.gyro_range_rad_per_s;
  const double a_max = params_.accel_range_m_per_s2;
  out.gyro_B = (w_B + gyro_bias_B_ + gyro_white_std_ * noise_.normal3()).cwiseMax(-g_max).cwiseMin(g_max);
  out.accel_B = (a_B + accel_bias_B_ + accel_white_std_ * noise_.normal3()).cwiseMax(-a_max).cwiseMin(a_max);
  return out;
}

}  // namespace geaware::sim
