// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The concrete terrains: flat ground, a tilted plane, a step or table edge, and a
// height map (a grid of heights). Each overrides rayCast with an exact method: a closed form for
// the planes and the step; for the height map, a walk over the cells under the ray with the
// closed-form intersection of each cell's bilinear patch.

#include <algorithm>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geaware/model/height_grid.hpp"
#include "geaware/sim/terrain.hpp"

namespace geaware::sim {

/// Horizontal ground z = z0.
class FlatGround final : public Terrain {
 public:
  explicit FlatGround(double z0_m = 0.0) noexcept : z0_m_(z0_m) {}
  [[nodiscard]] double heightAt(double, double) const noexcept override { return z0_m_; }
  [[nodiscard]] Eigen::Vector3d normalAt(double, double) const noexcept override {
    return Eigen::Vector3d::UnitZ();
  }
  [[nodiscard]] std::optional<double> rayCast(const Eigen::Vector3d& origin_W,
                                              const Eigen::Vector3d& dir_W,
                                              double max_range_m) const noexcept override;
  [[nodiscard]] double level() const noexcept { return z0_m_; }  ///< z0 [m]
  [[nodiscard]] std::optional<double> flatLevel() const noexcept override { return z0_m_; }
  [[nodiscard]] std::optional<double> heightBound() const noexcept override { return z0_m_; }
  /// normal = R_WBᵀ·z_W, offset = z0 − origin_z.
  [[nodiscard]] std::optional<LocalPlane> planeSeenFrom(
      const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& origin_W) const noexcept override {
    return LocalPlane{R_WB.row(2).transpose(), z0_m_ - origin_W.z()};
  }

 private:
  double z0_m_;
};

/// The plane through `point_W` with upward unit normal `normal_W` (n_z > 0 required: a height
/// field cannot hold a vertical or overhanging plane).
class TiltedPlane final : public Terrain {
 public:
  /// Throws std::invalid_argument for a non-finite point or a normal with n_z ≤ 0.05 (> 87°).
  TiltedPlane(const Eigen::Vector3d& point_W, const Eigen::Vector3d& normal_W);

  /// The horizontal plane through `point_W` rotated by `roll_rad` about x_W, then `pitch_rad`
  /// about y_W: n = R_y(pitch)·R_x(roll)·z_W. A positive pitch lowers the +x side (the board of
  /// the paper's platform tilted about the vehicle's y axis).
  [[nodiscard]] static TiltedPlane fromTilt(const Eigen::Vector3d& point_W, double roll_rad,
                                            double pitch_rad);

  [[nodiscard]] double heightAt(double x_m, double y_m) const noexcept override;
  [[nodiscard]] Eigen::Vector3d normalAt(double, double) const noexcept override { return n_W_; }
  [[nodiscard]] std::optional<double> rayCast(const Eigen::Vector3d& origin_W,
                                              const Eigen::Vector3d& dir_W,
                                              double max_range_m) const noexcept override;
  /// normal = R_WBᵀ·n_W, offset = n_W·((0, 0, H(0, 0)) − origin_W).
  [[nodiscard]] std::optional<LocalPlane> planeSeenFrom(
      const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& origin_W) const noexcept override {
    return LocalPlane{R_WB.transpose() * n_W_,
                      n_W_.dot(Eigen::Vector3d(0.0, 0.0, heightAt(0.0, 0.0)) - origin_W)};
  }

 private:
  Eigen::Vector3d p_W_;
  Eigen::Vector3d n_W_;
};

/// A step or table edge: two horizontal levels split by a straight line in the xy-plane.
/// Points with (xy − edge_point)·towards_high ≥ 0 are at z_high, the rest at z_low. The vertical
/// face is part of the surface for ray casts; its normal is not defined by a height field, so
/// normalAt() returns z_W everywhere (each side is horizontal).
class StepTerrain final : public Terrain {
 public:
  /// Throws std::invalid_argument for non-finite values or a zero `towards_high`.
  StepTerrain(const Eigen::Vector2d& edge_point_W, const Eigen::Vector2d& towards_high,
              double z_low_m, double z_high_m);

  [[nodiscard]] double heightAt(double x_m, double y_m) const noexcept override;
  [[nodiscard]] Eigen::Vector3d normalAt(double, double) const noexcept override {
    return Eigen::Vector3d::UnitZ();
  }
  [[nodiscard]] std::optional<double> rayCast(const Eigen::Vector3d& origin_W,
                                              const Eigen::Vector3d& dir_W,
                                              double max_range_m) const noexcept override;

  /// Signed horizontal distance of (x, y) from the edge, positive on the high side [m].
  [[nodiscard]] double signedDistance(double x_m, double y_m) const noexcept;
  [[nodiscard]] double maxHeight() const noexcept {
    return std::max(z_low_m_, z_high_m_);
  }  ///< [m]
  [[nodiscard]] std::optional<double> heightBound() const noexcept override { return maxHeight(); }

 private:
  Eigen::Vector2d edge_point_W_;
  Eigen::Vector2d u_;  // unit, towards the high side
  double z_low_m_;
  double z_high_m_;
};

/// A ray's first hit on a height map: how far along the ray, and the surface gradient there.
struct HeightMapHit {
  double distance_m = 0.0;                             ///< along the unit direction [m]
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();  ///< (∂H/∂x, ∂H/∂y) at the hit [-]
};

/// A regular grid of heights, bilinear between the nodes, held at the border value outside.
/// Node (i, j) sits at (origin_x + i·cell, origin_y + j·cell). The file format is io/'s
/// (io/height_map_file.hpp reads it into a model::HeightGrid).
class HeightMap final : public Terrain {
 public:
  /// `heights[j][i]`; throws std::invalid_argument unless ≥ 2×2, rectangular, all finite, cell > 0.
  HeightMap(double origin_x_m, double origin_y_m, double cell_m,
            const std::vector<std::vector<double>>& heights);

  /// The same from a grid (as read by io::readHeightMapFile).
  explicit HeightMap(const model::HeightGrid& grid);

  [[nodiscard]] double heightAt(double x_m, double y_m) const noexcept override;
  [[nodiscard]] Eigen::Vector3d normalAt(double x_m, double y_m) const noexcept override;
  /// (∂H/∂x, ∂H/∂y) at (x, y) [-]; zero across the border, where the height is held.
  /// normalAt() is (−∂H/∂x, −∂H/∂y, 1) normalised; this skips the square root (the ranger's
  /// incidence test needs none).
  [[nodiscard]] Eigen::Vector2d gradientAt(double x_m, double y_m) const noexcept;
  [[nodiscard]] std::optional<double> rayCast(const Eigen::Vector3d& origin_W,
                                              const Eigen::Vector3d& dir_W,
                                              double max_range_m) const noexcept override;
  /// rayCast() for a finite origin, a direction of unit length and a finite range > 0 (not
  /// checked), with the gradient at the hit: the lattice ranger's call (no normalisation, no
  /// second look-up of the cell for the incidence angle).
  [[nodiscard]] std::optional<HeightMapHit> rayHitUnit(const Eigen::Vector3d& origin_W,
                                                       const Eigen::Vector3d& unit_dir_W,
                                                       double max_range_m) const noexcept;

  [[nodiscard]] std::size_t columns() const noexcept { return nx_; }  ///< nodes along x
  [[nodiscard]] std::size_t rows() const noexcept { return ny_; }     ///< nodes along y
  [[nodiscard]] double cellSize() const noexcept { return cell_m_; }
  [[nodiscard]] double maxHeight() const noexcept { return max_z_m_; }  ///< highest node [m]
  [[nodiscard]] std::optional<double> heightBound() const noexcept override { return max_z_m_; }
  /// rayHitUnit() with the incidence test on the gradient at the hit: cos(incidence) =
  /// s/√(1 + |∇H|²) with s = −d·(−∇H, 1), tested as s ≥ 0 and s² ≥ cos²(limit)·(1 + |∇H|²)
  /// (the limit is ≤ 90°): no square root, no division.
  [[nodiscard]] std::optional<RangeHit> rangeHit(const Eigen::Vector3d& origin_W,
                                                 const Eigen::Vector3d& unit_dir_W,
                                                 double max_range_m,
                                                 double min_cos_incidence) const noexcept override;

 private:
  /// The cell walk of rayCast() and rayHitUnit() (the gradient only when kGradient).
  template <bool kGradient>
  [[nodiscard]] std::optional<HeightMapHit> walk(const Eigen::Vector3d& origin_W,
                                                 const Eigen::Vector3d& unit_dir_W,
                                                 double max_range_m) const noexcept;
  /// Cell index and fractions of (x, y), clamped to the grid.
  void locate(double x_m, double y_m, std::size_t& i, std::size_t& j, double& fx,
              double& fy) const noexcept;
  [[nodiscard]] double node(std::size_t i, std::size_t j) const noexcept { return z_[j * nx_ + i]; }

  double origin_x_m_;
  double origin_y_m_;
  double cell_m_;
  std::size_t nx_ = 0;
  std::size_t ny_ = 0;
  std::vector<double> z_;     // row-major, j * nx + i
  double inv_cell_ = 0.0;     // 1/cell [1/m]
  double max_z_m_ = 0.0;      // highest node [m]
};

}  // namespace geaware::sim
