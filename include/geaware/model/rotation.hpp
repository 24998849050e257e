// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Rotations as unit quaternions: the Log and Exp maps between a rotation and its rotation
// vector (angle·axis), and the angle between two attitudes. The one place for these maps; the
// estimator (error-state injection), the controller (attitude error, paper eq. 32) and the
// flight metrics use them.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace geaware::model {

/// Rotation vector θ = angle·axis of a unit quaternion (Log map), taking the shorter of q and
/// −q so that |θ| ≤ π [rad].
[[nodiscard]] Eigen::Vector3d logMap(const Eigen::Quaterniond& q) noexcept;

/// Unit quaternion of a rotation vector θ [rad] (Exp map).
[[nodiscard]] Eigen::Quaterniond expMap(const Eigen::Vector3d& theta) noexcept;

/// Angle of the rotation from attitude `a` to attitude `b`, the short way round [rad], in [0, π].
[[nodiscard]] double angleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) noexcept;

}  // namespace geaware::model
