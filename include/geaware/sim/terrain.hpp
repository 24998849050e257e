#pragma once
// The surfaces under (and, later, around) the vehicle. Terrain is a height field z = H(x, y) in
// the world frame (z up): flat ground, a tilted plane, a step or table edge, or a height map
// loaded from a file. Everything the simulator needs from it is here: the height and normal
// under a point (per-rotor ground effect, ground strikes) and ray casts (the lattice ranger).

#include <optional>

#include <Eigen/Core>

namespace geaware::sim {

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
};

}  // namespace geaware::sim
