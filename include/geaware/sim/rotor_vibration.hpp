// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Rotor-harmonic vibration at the IMU: what an accelerometer on a multirotor mostly measures
// besides the vehicle's motion. A propeller's residual imbalance is a force rotating with the
// rotor, at its rotation frequency (1×); each blade passing an arm pulses the thrust at the blade
// passage frequency (N_b×), the spike ArduPilot's vibration guide says its FFT plots usually
// show. Both scale with the square of the rotor speed (centripetal force of the imbalance m·e·Ω²,
// thrust ∝ Ω²). Model, per rotor i with phase φ_i = ∫ 2π·n_i/60 dt (rotor speed in rpm):
//
//   accel_x += a·(n_i/n_ref)²·cos(φ_i + α_i)     accel_y += a·(n_i/n_ref)²·sin(φ_i + α_i)   (1×, in the rotor plane)
//   accel_z += a·(n_i/n_ref)²·cos(N_b·φ_i + β_i)                                             (blade passage)
//   gyro_x,y += g·(n_i/n_ref)²·cos(N_b·φ_i + γ_i,x/y)  gyro_z += g·(n_i/n_ref)²·cos(φ_i + γ_i,z)
//
// with per-rotor phase offsets drawn once from the scenario seed (salt::kImuRotorVibration).
// a = σ_a·√(2/N) so that, with N rotors at n_ref and unrelated phases, each axis has standard
// deviation σ_a (the parameter: the RAW vibration, before any filter, as ArduPilot's VIBE
// reports it); likewise g. Everything deterministic given the seed and the rotor speeds. No
// allocation.

#include <algorithm>
#include <array>
#include <cstdint>
#include <tuple>

#include <Eigen/Core>

#include "geaware/sim/plant_state.hpp"
#include "geaware/sim/sampling.hpp"

namespace geaware::sim {

namespace salt {
inline constexpr std::uint64_t kImuRotorVibration = 0x726876'0000000cULL;
}  // namespace salt

struct RotorVibrationParams {
  double accel_std_m_per_s2 = 0.0;  ///< raw accelerometer vibration at reference_rpm, 1σ per axis; 0: off [m/s²]
  double gyro_std_rad_per_s = 0.0;  ///< raw gyro vibration at reference_rpm, 1σ per axis; 0: off [rad/s]
  double reference_rpm = 10000.0;   ///< rotor speed at which the σ above hold [rpm]
  int blade_count = 2;              ///< blades per propeller (the blade-passage harmonic) [-]

  [[nodiscard]] bool enabled() const noexcept { return accel_std_m_per_s2 > 0.0 || gyro_std_rad_per_s > 0.0; }
};

class RotorVibration {
 public:
  static constexpr int kRotors = static_cast<int>(std::tuple_size_v<decltype(PlantState::n_rpm)>);

  /// Parameters validated by ImuParams. Phase offsets from (scenario_seed, salt::kImuRotorVibration).
  RotorVibration(const RotorVibrationParams& params, std::uint64_t scenario_seed) noexcept;

  /// Advance every rotor's phase to t_s at the rotor speeds of `s` (the first call only sets
  /// the time) and return the vibration to add to the specific force [m/s²] and the rate [rad/s].
  void advance(const PlantState& s) noexcept;
  [[nodiscard]] const Eigen::Vector3d& accel_B() const noexcept { return accel_B_; }
  [[nodiscard]] const Eigen::Vector3d& gyro_B() const noexcept { return gyro_B_; }

 private:
  RotorVibrationParams params_;
  double accel_amplitude_ = 0.0;  // a, per rotor at reference_rpm [m/s²]
  double gyro_amplitude_ = 0.0;   // g [rad/s]
  std::array<double, kRotors> phase_rad_{};
  std::array<std::array<double, 5>, kRotors> offset_rad_{};  // α, β, γx, γy, γz
  double last_t_s_ = 0.0;
  bool started_ = false;
  Eigen::Vector3d accel_B_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_B_ = Eigen::Vector3d::Zero();
};

}  // namespace geaware::sim
