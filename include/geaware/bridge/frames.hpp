// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The conversions at the bridge's edge (docs/bridge.md, "Frames and units"), as plain functions
// without DDS: geaware's world frame is ENU (x east, y north, z up) and its body frame FLU
// (x forward, y left, z up); PX4's are NED and FRD. Rotor speeds stay in rpm; PX4's
// `actuator_motors` carries normalised thrust that PX4 turns into the ESC command through its
// thrust model THR_MDL_FAC; PX4 time stamps are integer microseconds since boot.

#include <array>
#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace geaware::bridge {

/// A world vector ENU → NED (and back: the map is its own inverse): (y, x, −z).
[[nodiscard]] Eigen::Vector3d enuToNed(const Eigen::Vector3d& v) noexcept;
[[nodiscard]] Eigen::Vector3d nedToEnu(const Eigen::Vector3d& v) noexcept;
/// A body vector FLU → FRD (and back): (x, −y, −z).
[[nodiscard]] Eigen::Vector3d fluToFrd(const Eigen::Vector3d& v) noexcept;
[[nodiscard]] Eigen::Vector3d frdToFlu(const Eigen::Vector3d& v) noexcept;

/// The attitude q_WB (FLU body → ENU world) as PX4's q (FRD body → NED world), and back.
/// The result has a non-negative w (q and −q are the same attitude).
[[nodiscard]] Eigen::Quaterniond enuFluToNedFrd(const Eigen::Quaterniond& q_enu_flu) noexcept;
[[nodiscard]] Eigen::Quaterniond nedFrdToEnuFlu(const Eigen::Quaterniond& q_ned_frd) noexcept;

/// Where each rotor of geaware's mixer order (rotor i = column i of model::Mixer's A: 1 front
/// right, 2 rear left, 3 front left, 4 rear right) sits in PX4's motor numbering, 0-based:
/// `actuator_motors.control[px4_index[i]]` commands rotor i and `esc_status.esc[px4_index[i]]`
/// reports it. The default is the identity: PX4's "Quadrotor x" geometry numbers its motors
/// 1 front right (CCW), 2 rear left (CCW), 3 front left (CW), 4 rear right (CW), as the mixer does
/// (PX4 airframe reference, "Quadrotor x"; ROTORS in src/modules/control_allocator).
struct MotorMap {
  std::array<int, 4> px4_index{0, 1, 2, 3};
  /// Each of 0…11 at most once.
  [[nodiscard]] bool valid() const noexcept;
};

/// PX4's thrust model (THR_MDL_FAC = f): relative thrust c = f·u² + (1 − f)·u for the ESC command u
/// ∈ [0, 1]. `actuator_motors.control` carries c, PX4 sends u. The bridge sends
/// c(u) for the throttle u the controller computed, so that PX4's inversion gives back u.
/// Both clamp to [0, 1]; f ∈ [0, 1]; a NaN input gives NaN (PX4: motor stopped).
[[nodiscard]] double normalisedThrustFromThrottle(double throttle, double thr_mdl_fac) noexcept;
[[nodiscard]] double throttleFromNormalisedThrust(double normalised_thrust,
                                                  double thr_mdl_fac) noexcept;

/// Seconds ↔ PX4's microsecond time stamps (rounded to the nearest microsecond; negative and
/// non-finite times give 0).
[[nodiscard]] std::uint64_t toMicroseconds(double t_s) noexcept;
[[nodiscard]] double toSeconds(std::uint64_t t_us) noexcept;

}  // namespace geaware::bridge
