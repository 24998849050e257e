// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Sensor samples: the only things that cross the wall from the simulator (or a real vehicle)
// to the estimator and controller. Plain value types, fixed size, no allocation.

#include <array>
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace geaware::model {

/// One IMU sample (the paper's flights: 200 Hz).
struct ImuSample {
  double t_s = 0.0;                                    ///< sample time [s]
  Eigen::Vector3d gyro_B = Eigen::Vector3d::Zero();    ///< body rates [rad/s], with bias and noise
  Eigen::Vector3d accel_B = Eigen::Vector3d::Zero();   ///< specific force Rᵀ(a + g·z_W) [m/s²]
};

/// One motion-capture pose. `t_s` is the time the pose was captured; it is delivered later
/// (latency), so an estimator must fuse it against its past state.
struct MocapSample {
  double t_s = 0.0;                                          ///< capture time [s]
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();             ///< position of the body origin [m]
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();  ///< attitude
};

/// Rotor speeds reported by the ESCs (bidirectional DShot in the paper, 200 Hz).
struct RotorTelemetry {
  double t_s = 0.0;                                          ///< sample time [s]
  Eigen::Vector4d n_rpm = Eigen::Vector4d::Zero();           ///< rotor speeds, mixer order [rpm]
};

/// One frame of an N×N lattice time-of-flight ranger looking down along −z_B (the paper: 16×16
/// zones at 100 Hz). Zone (i, j), i along body x and j along body y, looks along
/// zoneDirection_B(i, j); a zone without a return (out of range, no target) is not valid.
struct RangerFrame {
  static constexpr int kMaxSide = 16;
  static constexpr int kMaxZones = kMaxSide * kMaxSide;

  double t_s = 0.0;                                   ///< sample time [s]
  int side = 0;                                       ///< N, zones per side (≤ kMaxSide)
  double fov_rad = 0.0;                               ///< full field of view per axis [rad]
  Eigen::Vector3d mount_B = Eigen::Vector3d::Zero();  ///< sensor origin in the body frame [m]
  std::array<double, kMaxZones> range_m{};            ///< distance along each zone's ray [m]
  std::array<bool, kMaxZones> valid{};                ///< zone has a return

  [[nodiscard]] int index(int i, int j) const noexcept { return i * side + j; }

  /// Unit ray of zone (i, j) in the body frame: zone centres spread evenly over the field of
  /// view, tilted by ((i + ½)/N − ½)·fov about −y (towards +x) and likewise towards +y.
  [[nodiscard]] Eigen::Vector3d zoneDirection_B(int i, int j) const noexcept {
    const double ax = ((i + 0.5) / side - 0.5) * fov_rad;
    const double ay = ((j + 0.5) / side - 0.5) * fov_rad;
    return Eigen::Vector3d(std::tan(ax), std::tan(ay), -1.0).normalized();
  }
};

/// One reading of a single-zone ranger looking along a fixed body direction (up at a ceiling,
/// sideways at a wall; sim::BeamRanger). Without a return (out of range, grazing) not valid.
struct BeamReading {
  double t_s = 0.0;                                        ///< sample time [s]
  Eigen::Vector3d direction_B = Eigen::Vector3d::UnitZ();  ///< unit beam direction, body [-]
  Eigen::Vector3d mount_B = Eigen::Vector3d::Zero();       ///< beam origin rel. the geometric centre, body [m]
  double range_m = 0.0;                                    ///< along the beam [m]
  bool valid = false;                                      ///< has a return
};

}  // namespace geaware::model
