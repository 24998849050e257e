// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The surfaces under (and, later, around) the vehicle. Terrain is a height field z = H(x, y) in
// the world frame (z up): flat ground, a tilted plane, a step or table edge, or a height map
// loaded from a file. Everything the simulator needs from it is here: the height and normal
// under a point (per-rotor ground effect, ground strikes) and ray casts (the lattice ranger).
// A terrain also answers the questions that let its users take shortcuts (is it flat, how high
// can it reach, is it a plane, where and how steeply does a ray meet it), so no user needs to
// know the concrete shapes.

#include <optional>

#include <Eigen/Core>

namespace geaware::sim {

/// A plane seen from a point in a rotated frame: points x of the plane, relative to the point
/// and expressed in the frame, satisfy normal·x = offset_m.
struct LocalPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< upward unit normal, in the frame
  double offset_m = 0.0;                              ///< [m]
};

/// A ray's first hit for a range sensor: the distance, and whether the ray meets the surface
/// more obliquely than the sensor's incidence limit allows.
struct RangeHit {
  double distance_m = 0.0;  ///< along the unit direction [m]
  bool grazing = false;     ///< cos(incidence) below the limit: no return
};

class Terrain {
 public:
  virtual ~Terrain() = default;

  /// Surface height H(x, y) [m] under a world point.
  [[nodiscard]] virtual double heightAt(double x_m, double y_m) const noexcept = 0;

  /// Unit upward surface normal at (x, y), world frame.
  [[nodiscard]] virtual Eigen::Vector3d normalAt(double x_m, double y_m) const noexcept = 0;

  /// Distance along the unit direction `dir_W` from `origin_W` to the first surface hit within
  /// `max_range_m`, or nothing. The default marches and bisects on heightAt(); simple shapes
  /// override it with a closed form.
  [[nodiscard]] virtual std::optional<double> rayCast(const Eigen::Vector3d& origin_W,
                                                      const Eigen::Vector3d& dir_W,
                                                      double max_range_m) const noexcept;

  /// The height of a terrain that is horizontal and flat everywhere, or nothing.
  [[nodiscard]] virtual std::optional<double> flatLevel() const noexcept { return std::nullopt; }

  /// The highest point of the terrain [m], or nothing when it is unbounded.
  [[nodiscard]] virtual std::optional<double> heightBound() const noexcept { return std::nullopt; }

  /// For a terrain that is one plane: that plane seen from `origin_W` in the frame whose
  /// rotation to the world is R_WB (so a sensor can intersect its rays in closed form).
  /// Nothing for any other terrain.
  [[nodiscard]] virtual std::optional<LocalPlane> planeSeenFrom(
      const Eigen::Matrix3d& /*R_WB*/, const Eigen::Vector3d& /*origin_W*/) const noexcept {
    return std::nullopt;
  }

  /// First hit of the ray from `origin_W` along the unit direction `unit_dir_W` within
  /// `max_range_m`, and whether it grazes: cos(incidence) = −d·n below `min_cos_incidence`.
  /// The default is rayCast() and normalAt() at the hit.
  [[nodiscard]] virtual std::optional<RangeHit> rangeHit(const Eigen::Vector3d& origin_W,
                                                         const Eigen::Vector3d& unit_dir_W,
                                                         double max_range_m,
                                                         double min_cos_incidence) const noexcept;
};

}  // namespace geaware::sim
