// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The external disturbance observer of the paper (eq. 6, "Real-world flight"):
//   ã_ext = (a − g)_f^imu − z_B·T_f/m,
//   τ̃_ext = J·ω̇_f + ω_f × J·ω_f − τ_B,f,
// with T and τ_B from the measured rotor speeds through the mixer (eq. 2), and every input
// passed through the same second-order low-pass (model::LowPass2, one cut-off) so that the
// filtered quantities are delayed alike. (a − g)^imu is the IMU's specific force; in the body
// frame it is compared with T_f/m along z_B, and the difference is rotated to the world.
// Also the paper's flight estimate of the additional-thrust ratio (its equation
// "equ_fgh_realflight", in the F_G section):
//   F̃_G = m·z_Wᵀ·ã_ext / T̃.
//
// Timing: ω̇_f is the difference of consecutive filtered rates, which is exact (to second
// order) at the middle of the IMU interval, so every output is evaluated there: the filtered
// ω, τ_B, specific force and thrust are averaged over the last two samples. Consistent data
// then gives zero up to O(dt²) and the non-commuting ω_f × Jω_f term (docs/estimation.md).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "geaware/model/low_pass.hpp"
#include "geaware/model/mixer.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::estimation {

struct DisturbanceObserverParams {
  double rate_hz = 200.0;          ///< update rate, the IMU's [Hz]
  double filter_cutoff_hz = 30.0;  ///< shared low-pass cut-off (the controller's) [Hz]
  /// F̃_G is reported only when the filtered thrust exceeds this fraction of the weight [-].
  double min_thrust_fraction = 0.2;

  /// Every offending field with its value and expectation; empty when usable.
  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

struct DisturbanceObserverInput {
  double t_s = 0.0;                                   ///< sample time [s]
  Eigen::Vector3d gyro_B = Eigen::Vector3d::Zero();   ///< bias-corrected body rates [rad/s]
  Eigen::Vector3d accel_B = Eigen::Vector3d::Zero();  ///< bias-corrected specific force [m/s²]
  Eigen::Vector4d rotor_speeds_rpm = Eigen::Vector4d::Zero();  ///< measured, mixer order [rpm]
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();    ///< attitude estimate
};

struct DisturbanceEstimate {
  bool valid = false;  ///< false until two samples went through, or on bad input
  double t_s = 0.0;    ///< time the estimate refers to: middle of the last interval [s]
  Eigen::Vector3d a_ext_W = Eigen::Vector3d::Zero();    ///< ã_ext, world frame [m/s²]
  Eigen::Vector3d a_ext_B = Eigen::Vector3d::Zero();    ///< ã_ext, body frame [m/s²]
  Eigen::Vector3d tau_ext_B = Eigen::Vector3d::Zero();  ///< τ̃_ext [N·m]
  double thrust_f_N = 0.0;                              ///< T_f [N]
  Eigen::Vector3d tau_B_f = Eigen::Vector3d::Zero();    ///< τ_B,f from the rotor speeds [N·m]
  Eigen::Vector3d w_f_B = Eigen::Vector3d::Zero();      ///< ω_f [rad/s]
  Eigen::Vector3d w_dot_f_B = Eigen::Vector3d::Zero();  ///< ω̇_f [rad/s²]
  bool f_g_valid = false;                               ///< thrust large enough for F̃_G
  double f_g_ratio = 0.0;  ///< F̃_G = m·z_Wᵀ·ã_ext / T_f, the paper's flight estimate [-]
};

/// What the last update did.
enum class ObserverStatus : std::uint8_t { kOk, kWarmingUp, kNonFinite, kTimeNotIncreasing };

class DisturbanceObserver {
 public:
  /// Mass, inertia and mixer from the vehicle; validates params (throws model::InvalidParameters).
  DisturbanceObserver(const model::VehicleModel& vehicle, DisturbanceObserverParams params);

  /// One IMU-rate step. Non-finite inputs and non-increasing times leave the filters untouched
  /// and return the previous estimate marked invalid. No allocation.
  DisturbanceEstimate update(const DisturbanceObserverInput& in) noexcept;

  void reset() noexcept;

  /// After this many non-increasing times in a row the observer assumes its own time is wrong
  /// (a garbage time far ahead) and warms up again from the next sample [-].
  static constexpr int kMaxTimeRejections = 64;

  [[nodiscard]] ObserverStatus lastStatus() const noexcept { return status_; }
  [[nodiscard]] std::uint64_t rejectedSamples() const noexcept { return rejected_; }
  [[nodiscard]] const DisturbanceObserverParams& params() const noexcept { return params_; }

 private:
  /// update() on accepted inputs; its estimate may be non-finite when they are huge.
  DisturbanceEstimate step(const DisturbanceObserverInput& in) noexcept;

  DisturbanceObserverParams params_;
  double mass_kg_;
  Eigen::Vector3d inertia_kgm2_;
  model::Mixer mixer_;
  // One filter type, one cut-off (the paper's "(·)_f"): ω, τ_B, specific force, thrust.
  model::LowPass2<3> w_filter_;
  model::LowPass2<3> tau_filter_;
  model::LowPass2<3> accel_filter_;
  model::LowPass2<1> thrust_filter_;
  // Filtered values and attitude of the previous sample.
  Eigen::Vector3d w_prev_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d tau_prev_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d f_prev_ = Eigen::Vector3d::Zero();
  double thrust_prev_ = 0.0;
  Eigen::Quaterniond q_prev_ = Eigen::Quaterniond::Identity();
  double t_prev_ = 0.0;
  bool have_prev_ = false;
  DisturbanceEstimate last_;
  ObserverStatus status_ = ObserverStatus::kWarmingUp;
  std::uint64_t rejected_ = 0;
  int time_rejections_ = 0;
};

}  // namespace geaware::estimation
