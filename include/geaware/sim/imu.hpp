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

  /// Every offending field (key names as above); empty when usable.
  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

class Imu {
 public:
  /// Throws model::InvalidParameters listing every invalid field. Noise stream:
  /// (scenario_seed, salt::kImu).
  Imu(const ImuParams& params, std::uint64_t scenario_seed);

  /// A sample when one is due at state.t_s (call at the plant rate, every step), else nothing.
  /// A non-finite state gives nothing and is counted in rejected(). No allocation.
  [[nodiscard]] std::optional<model::ImuSample> sample(const PlantState& state) noexcept;

  /// The biases of the last sample (truth, for tests and logs).
  [[nodiscard]] const Eigen::Vector3d& gyroBias_B() const noexcept { return gyro_bias_B_; }
  [[nodiscard]] const Eigen::Vector3d& accelBias_B() const noexcept { return accel_bias_B_; }
  [[nodiscard]] const ImuParams& params() const noexcept { return params_; }
  [[nodiscard]] long rejected() const noexcept { return rejected_; }

 private:
  ImuParams params_;
  NoiseSource noise_;
  SampleClock clock_;
  double gyro_white_std_;   // per-sample white-noise std [rad/s]
  double accel_white_std_;  // [m/s²]
  Eigen::Vector3d gyro_bias_B_;
  Eigen::Vector3d accel_bias_B_;
  std::optional<double> last_t_s_;
  long rejected_ = 0;
};

}  // namespace geaware::sim
