// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The simulated IMU (the paper's flights: 200 Hz): gyro and specific force with
// white noise and a bias random walk per axis, in the usual continuous-time densities
// (Kalibr / rotors_simulator convention), discretised exactly for the sample interval:
//
//   gyro_B  = ω_B + b_g + σ_g,d·w,            σ_g,d = N_g·√rate        (white noise, per sample)
//   accel_B = Rᵀ(a_W,imu + g·z_W) + b_a + σ_a,d·w
//   b ← b + N_b·√Δt·w                          (random walk: Var[b(t) − b(0)] = N_b²·t)
//
// Δt is the time since the previous sample. Each bias starts from a zero-mean normal draw
// ("turn-on bias"). Readings are clipped to the sensor's range (saturation).
//
// Lever arm: the IMU may sit at `lever_arm_B_m` from the geometric centre (the point PlantState
// describes). Its acceleration is a_W + R(ω̇ × r + ω × (ω × r)), from PlantState::a_W and
// w_dot_B, which the plant publishes at the end of each step. Default: at the centre.
//
// Vibration and the flight controller's filter (docs/world.md; off by default): the true ω and
// specific force plus broadband vibration noise (its own stream, salt::kImuVibration) are
// sampled at filter_rate_Hz and run through a second-order Butterworth low-pass (PX4's and
// ArduPilot's LowPassFilter2p); the 200 Hz output is the filter's latest value plus the bias
// and white noise above. The filter's group delay, ≈ √2/(2π·f_c) (11 ms at 20 Hz), is then real.
// The vibration std parameters are what remains IN THE OUTPUT: the raw per-sample std is
// derived from the filter's white-noise gain (σ_raw = σ/√Σh_k²). Without the filter they are
// added per output sample.
//
// Rotor-harmonic vibration (sim/rotor_vibration.hpp; off by default): the raw vibration at the
// rotors' rotation and blade-passage frequencies, added to the raw samples before the filter
// (or per output sample without it). Unlike the broadband vibration above, its parameters are
// the RAW standard deviation at a reference rotor speed; what the filter leaves of it depends
// on the rotor speed (LowPass2::gainAt).
//
// Defaults: an ADIS16448-class MEMS IMU with densities inflated for the vibration of a
// 7-inch quadrotor (rotors_simulator uses the same order of magnitude): 0.24 °/s and
// 0.057 m/s² white noise per sample at 200 Hz.

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "geaware/model/sensor_data.hpp"
#include "geaware/model/units.hpp"
#include "geaware/model/field_error.hpp"
#include "geaware/sim/plant_state.hpp"
#include "geaware/sim/rotor_vibration.hpp"
#include "geaware/sim/sampling.hpp"

namespace geaware::sim {

struct ImuParams {
  double rate_Hz = 200.0;                                  ///< sample rate [Hz]
  double gyro_noise_density_rad_per_s_sqrtHz = 3.0e-4;     ///< gyro white noise N_g [rad/s/√Hz]
  double gyro_bias_walk_rad_per_s2_sqrtHz = 4.0e-5;        ///< gyro bias random walk [rad/s²/√Hz]
  double gyro_initial_bias_std_rad_per_s = 5.0e-3;         ///< turn-on gyro bias, 1σ per axis [rad/s]
  double accel_noise_density_m_per_s2_sqrtHz = 4.0e-3;     ///< accelerometer white noise N_a [m/s²/√Hz]
  double accel_bias_walk_m_per_s3_sqrtHz = 6.0e-3;         ///< accelerometer bias random walk [m/s³/√Hz]
  double accel_initial_bias_std_m_per_s2 = 5.0e-2;         ///< turn-on accelerometer bias, 1σ per axis [m/s²]
  double gyro_range_rad_per_s = 2000.0 * model::kDegToRad; ///< gyro saturation, ±2000 °/s [rad/s]
  double accel_range_m_per_s2 = 16.0 * model::kGravity;    ///< accelerometer saturation, ±16 g [m/s²]
  Eigen::Vector3d lever_arm_B_m = Eigen::Vector3d::Zero(); ///< IMU position rel. the geometric centre, body [m]
  double gravity_mps2 = model::kGravity;                   ///< g in the specific force [m/s²]
  double vibration_gyro_std_rad_per_s = 0.0;    ///< vibration noise left in the output, 1σ per axis [rad/s]
  double vibration_accel_std_m_per_s2 = 0.0;    ///< vibration noise left in the output, 1σ per axis [m/s²]
  double lowpass_cutoff_Hz = 0.0;               ///< flight controller's 2nd-order low-pass cutoff; 0: off [Hz]
  double filter_rate_Hz = 1000.0;               ///< raw sample rate the filter runs at (call sample() at least this often) [Hz]
  RotorVibrationParams rotor_vibration;         ///< rotor-harmonic vibration (raw σ at a reference speed)

  /// Every offending field (key names as above); empty when usable.
  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

/// Second-order Butterworth low-pass on three axes: bilinear transform with the cutoff
/// pre-warped, direct form II (the biquad of PX4's and ArduPilot's LowPassFilter2p). Gain 1 at
/// DC, 1/√2 at the cutoff. No allocation.
class LowPass2 {
 public:
  /// 0 < cutoff_Hz < sample_rate_Hz/2 (validated by ImuParams).
  LowPass2(double sample_rate_Hz, double cutoff_Hz) noexcept;
  /// Start in steady state at x (the output is x until the input changes).
  void reset(const Eigen::Vector3d& x) noexcept;
  /// One input sample; returns the new output.
  const Eigen::Vector3d& apply(const Eigen::Vector3d& x) noexcept;
  [[nodiscard]] const Eigen::Vector3d& value() const noexcept { return y_; }
  /// Output variance per unit input variance for white input, Σ h_k² [-].
  [[nodiscard]] double noiseGain() const noexcept { return noise_gain_; }
  /// Group delay at DC (a ramp's lag), 1 − (a1 + 2·a2)/(1 + a1 + a2) samples [s].
  [[nodiscard]] double groupDelay_s() const noexcept { return group_delay_s_; }
  /// Amplitude response |H(e^{jω})| at frequency_Hz (ω = 2π·f/f_s), for 0 ≤ f < f_s/2 [-].
  [[nodiscard]] double gainAt(double frequency_Hz) const noexcept;

 private:
  double sample_rate_Hz_ = 1.0;
  double b0_ = 1.0, b1_ = 0.0, b2_ = 0.0, a1_ = 0.0, a2_ = 0.0;
  Eigen::Vector3d d1_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d d2_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d y_ = Eigen::Vector3d::Zero();
  double noise_gain_ = 1.0;
  double group_delay_s_ = 0.0;
};

class Imu {
 public:
  /// Throws model::InvalidParameters listing every invalid field. Noise stream:
  /// (scenario_seed, salt::kImu).
  Imu(const ImuParams& params, std::uint64_t scenario_seed);

  /// A sample when one is due at state.t_s (call at the plant rate, every step, and at least
  /// at filter_rate_Hz when the low-pass is on), else nothing.
  /// A non-finite state gives nothing and is counted in rejected(). No allocation.
  [[nodiscard]] std::optional<model::ImuSample> sample(const PlantState& state) noexcept;

  /// The biases of the last sample (truth, for tests and logs).
  [[nodiscard]] const Eigen::Vector3d& gyroBias_B() const noexcept { return gyro_bias_B_; }
  [[nodiscard]] const Eigen::Vector3d& accelBias_B() const noexcept { return accel_bias_B_; }
  [[nodiscard]] const ImuParams& params() const noexcept { return params_; }
  [[nodiscard]] long rejected() const noexcept { return rejected_; }
  /// The flight controller's filter (null when lowpass_cutoff_Hz = 0).
  [[nodiscard]] const LowPass2* gyroFilter() const noexcept { return gyro_lp_ ? &*gyro_lp_ : nullptr; }

 private:
  /// Specific force at the IMU, Rᵀ(a_imu + g·z_W), a_imu with the lever-arm terms [m/s²].
  [[nodiscard]] Eigen::Vector3d specificForce(const PlantState& s) const noexcept;
  /// One raw sample (truth + vibration) into the filters.
  void filterRaw(const PlantState& s) noexcept;

  ImuParams params_;
  NoiseSource noise_;
  SampleClock clock_;
  double gyro_white_std_;   // per-sample white-noise std [rad/s]
  double accel_white_std_;  // [m/s²]
  Eigen::Vector3d gyro_bias_B_;
  Eigen::Vector3d accel_bias_B_;
  std::optional<double> last_t_s_;
  long rejected_ = 0;
  NoiseSource vibration_noise_;  // (scenario_seed, salt::kImuVibration)
  double gyro_vibration_std_ = 0.0;   // per raw (filtered) or output (unfiltered) sample [rad/s]
  double accel_vibration_std_ = 0.0;  // [m/s²]
  std::optional<RotorVibration> rotor_vibration_;  // null when off
  std::optional<LowPass2> gyro_lp_;
  std::optional<LowPass2> accel_lp_;
  SampleClock raw_clock_;
  bool filter_started_ = false;
};

}  // namespace geaware::sim
