// SPDX-License-Identifier: BSD-3-Clause
// The terrains: the generic ray cast of Terrain and the concrete shapes of terrains.hpp.
#include "geaware/sim/terrain.hpp"
#include "geaware/sim/terrains.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

namespace geaware::sim {

// ---------------------------------------------------------------------------------------------
// Terrain: the generic ray cast.
// ---------------------------------------------------------------------------------------------

namespace {

/// A root of the gap f in the bracket [lo, hi] (f(lo) > 0 ≥ f(hi)) to 1e-9 m: false position
/// with the Illinois modification (superlinear on the smooth, often quadratic, gap along a ray;
/// never leaves the bracket). Returns the end of the final bracket that is on or under the surface.
template <typename F>
double refineRoot(F&& f, double lo, double f_lo, double hi, double f_hi) {
  int kept = 0;  // which end stayed last time: −1 lo, +1 hi
  for (int k = 0; k < 200 && hi - lo > 1e-9; ++k) {
    double m = (f_lo * hi - f_hi * lo) / (f_lo - f_hi);
    if (!(m > lo && m < hi)) m = 0.5 * (lo + hi);
    const double f_m = f(m);
    if (f_m > 0.0) {
      lo = m;
      f_lo = f_m;
      if (kept == 1) f_hi *= 0.5;
      kept = 1;
    } else {
      hi = m;
      f_hi = f_m;
      if (f_m == 0.0) break;
      if (kept == -1) f_lo *= 0.5;
      kept = -1;
    }
  }
  return hi;
}

}  // namespace

std::optional<double> Terrain::rayCast(const Eigen::Vector3d& origin_W,
                                       const Eigen::Vector3d& dir_W,
                                       double max_range_m) const noexcept {
  if (!origin_W.allFinite() || !dir_W.allFinite() || !(max_range_m > 0.0) ||
      !std::isfinite(max_range_m)) {
    return std::nullopt;
  }
  const double len = dir_W.norm();
  if (!(len > 0.0)) return std::nullopt;
  const Eigen::Vector3d d = dir_W / len;
  // f(t) = height of the ray point above the surface; the first root is the hit.
  const auto f = [&](double t) {
    const Eigen::Vector3d p = origin_W + t * d;
    return p.z() - heightAt(p.x(), p.y());
  };
  double f_prev = f(0.0);
  if (f_prev <= 0.0) return 0.0;  // the origin is on or under the surface
  // 1. March at a fixed step (features narrower than the step may be missed: 1/1024 of the
  //    range, at most 5 mm), then 2. refine the step that crosses the surface.
  const double step = std::min(max_range_m / 1024.0, 5e-3);
  double t_prev = 0.0;
  for (;;) {
    const double t = std::min(t_prev + step, max_range_m);
    const double f_t = f(t);
    if (f_t <= 0.0) return refineRoot(f, t_prev, f_prev, t, f_t);  // 2. refine the bracket
    if (t >= max_range_m) return std::nullopt;
    t_prev = t;
    f_prev = f_t;
  }
}

std::optional<RangeHit> Terrain::rangeHit(const Eigen::Vector3d& origin_W,
                                          const Eigen::Vector3d& unit_dir_W, double max_range_m,
                                          double min_cos_incidence) const noexcept {
  const std::optional<double> hit = rayCast(origin_W, unit_dir_W, max_range_m);
  if (!hit) return std::nullopt;
  const Eigen::Vector3d p_hit = origin_W + *hit * unit_dir_W;
  return RangeHit{*hit, -unit_dir_W.dot(normalAt(p_hit.x(), p_hit.y())) < min_cos_incidence};
}

// ---------------------------------------------------------------------------------------------
// FlatGround
// ---------------------------------------------------------------------------------------------

namespace {

/// First t ≥ 0 at which origin + t·d reaches the plane z = level from above, within max_range.
std::optional<double> hitLevel(double origin_z, double dir_z, double level, double max_range_m) {
  const double above = origin_z - level;
  if (above <= 0.0) return 0.0;
  if (!(dir_z < 0.0)) return std::nullopt;
  const double t = above / -dir_z;
  if (t <= max_range_m) return t;
  return std::nullopt;
}

bool validRay(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range_m) {
  return o.allFinite() && d.allFinite() && d.squaredNorm() > 0.0 && max_range_m > 0.0 &&
         std::isfinite(max_range_m);
}

}  // namespace

std::optional<double> FlatGround::rayCast(const Eigen::Vector3d& origin_W,
                                          const Eigen::Vector3d& dir_W,
                                          double max_range_m) const noexcept {
  if (!validRay(origin_W, dir_W, max_range_m)) return std::nullopt;
  const Eigen::Vector3d d = dir_W.normalized();
  return hitLevel(origin_W.z(), d.z(), z0_m_, max_range_m);
}

// ---------------------------------------------------------------------------------------------
// TiltedPlane
// ---------------------------------------------------------------------------------------------

TiltedPlane::TiltedPlane(const Eigen::Vector3d& point_W, const Eigen::Vector3d& normal_W)
    : p_W_(point_W) {
  const double len = normal_W.norm();
  if (!point_W.allFinite() || !normal_W.allFinite() || !(len > 0.0) ||
      !(normal_W.z() / len > 0.05)) {
    throw std::invalid_argument(
        "TiltedPlane: the point must be finite and the normal finite with an upward z component "
        "(tilt < 87°)");
  }
  n_W_ = normal_W / len;
}

TiltedPlane TiltedPlane::fromTilt(const Eigen::Vector3d& point_W, double roll_rad,
                                  double pitch_rad) {
  const Eigen::Vector3d n =
      Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()) *
      (Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX()) * Eigen::Vector3d::UnitZ());
  return TiltedPlane(point_W, n);
}

double TiltedPlane::heightAt(double x_m, double y_m) const noexcept {
  return p_W_.z() - (n_W_.x() * (x_m - p_W_.x()) + n_W_.y() * (y_m - p_W_.y())) / n_W_.z();
}

std::optional<double> TiltedPlane::rayCast(const Eigen::Vector3d& origin_W,
                                           const Eigen::Vector3d& dir_W,
                                           double max_range_m) const noexcept {
  if (!validRay(origin_W, dir_W, max_range_m)) return std::nullopt;
  const Eigen::Vector3d d = dir_W.normalized();
  // n·(o + t·d − p) = 0; n·(o − p) ≤ 0 means the origin is on or under the plane (n_z > 0).
  const double above = n_W_.dot(origin_W - p_W_);
  if (above <= 0.0) return 0.0;
  const double rate = n_W_.dot(d);
  if (!(rate < 0.0)) return std::nullopt;
  const double t = above / -rate;
  if (t <= max_range_m) return t;
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------------
// StepTerrain
// ---------------------------------------------------------------------------------------------

StepTerrain::StepTerrain(const Eigen::Vector2d& edge_point_W, const Eigen::Vector2d& towards_high,
                         double z_low_m, double z_high_m)
    : edge_point_W_(edge_point_W), z_low_m_(z_low_m), z_high_m_(z_high_m) {
  if (!edge_point_W.allFinite() || !towards_high.allFinite() || !(towards_high.norm() > 0.0) ||
      !std::isfinite(z_low_m) || !std::isfinite(z_high_m)) {
    throw std::invalid_argument(
        "StepTerrain: finite edge point and heights and a non-zero direction are required");
  }
  u_ = towards_high.normalized();
}

double StepTerrain::signedDistance(double x_m, double y_m) const noexcept {
  return (Eigen::Vector2d(x_m, y_m) - edge_point_W_).dot(u_);
}

double StepTerrain::heightAt(double x_m, double y_m) const noexcept {
  return signedDistance(x_m, y_m) >= 0.0 ? z_high_m_ : z_low_m_;
}

std::optional<double> StepTerrain::rayCast(const Eigen::Vector3d& origin_W,
                                           const Eigen::Vector3d& dir_W,
                                           double max_range_m) const noexcept {
  if (!validRay(origin_W, dir_W, max_range_m)) return std::nullopt;
  const Eigen::Vector3d d = dir_W.normalized();
  // The ray's ground track crosses the edge line at most once, at t_cross; before it the ray is
  // over the origin's level, after it over the other level. Crossing onto a higher level below
  // its top means the ray hits the vertical face at t_cross.
  const double s0 = signedDistance(origin_W.x(), origin_W.y());
  const double rate = d.head<2>().dot(u_);
  const bool high0 = s0 >= 0.0;
  const double level0 = high0 ? z_high_m_ : z_low_m_;
  const double level1 = high0 ? z_low_m_ : z_high_m_;
  const bool crosses = high0 ? rate < 0.0 : rate > 0.0;
  const double t_cross = crosses ? -s0 / rate : std::numeric_limits<double>::infinity();
  const double t_first_end = std::min(t_cross, max_range_m);
  if (auto t = hitLevel(origin_W.z(), d.z(), level0, t_first_end)) return t;
  if (!(t_cross <= max_range_m)) return std::nullopt;
  const double z_cross = origin_W.z() + t_cross * d.z();
  if (z_cross <= level1) return t_cross;  // the face of the step (or exactly its edge)
  if (!(d.z() < 0.0)) return std::nullopt;
  const double t = (origin_W.z() - level1) / -d.z();
  if (t <= max_range_m) return t;
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------------
// HeightMap
// ---------------------------------------------------------------------------------------------

HeightMap::HeightMap(double origin_x_m, double origin_y_m, double cell_m,
                     const std::vector<std::vector<double>>& heights)
    : origin_x_m_(origin_x_m), origin_y_m_(origin_y_m), cell_m_(cell_m) {
  if (!std::isfinite(origin_x_m) || !std::isfinite(origin_y_m) || !std::isfinite(cell_m) ||
      !(cell_m > 0.0)) {
    throw std::invalid_argument("HeightMap: origin must be finite and cell size positive");
  }
  ny_ = heights.size();
  nx_ = ny_ > 0 ? heights.front().size() : 0;
  if (ny_ < 2 || nx_ < 2) throw std::invalid_argument("HeightMap: at least 2×2 nodes are required");
  z_.reserve(nx_ * ny_);
  for (std::size_t j = 0; j < ny_; ++j) {
    if (heights[j].size() != nx_) {
      throw std::invalid_argument("HeightMap: row " + std::to_string(j) + " has " +
                                  std::to_string(heights[j].size()) + " values, row 0 has " +
                                  std::to_string(nx_));
    }
    for (std::size_t i = 0; i < nx_; ++i) {
      if (!std::isfinite(heights[j][i])) {
        throw std::invalid_argument("HeightMap: height (" + std::to_string(i) + ", " +
                                    std::to_string(j) + ") is not finite");
      }
      z_.push_back(heights[j][i]);
    }
  }
  max_z_m_ = *std::max_element(z_.begin(), z_.end());
  inv_cell_ = 1.0 / cell_m_;
}

std::optional<double> HeightMap::rayCast(const Eigen::Vector3d& origin_W,
                                         const Eigen::Vector3d& dir_W,
                                         double max_range_m) const noexcept {
  if (!validRay(origin_W, dir_W, max_range_m)) return std::nullopt;
  const auto hit = walk<false>(origin_W, dir_W * (1.0 / dir_W.norm()), max_range_m);
  if (!hit) return std::nullopt;
  return hit->distance_m;
}

std::optional<HeightMapHit> HeightMap::rayHitUnit(const Eigen::Vector3d& origin_W,
                                                  const Eigen::Vector3d& unit_dir_W,
                                                  double max_range_m) const noexcept {
  return walk<true>(origin_W, unit_dir_W, max_range_m);
}

template <bool kGradient>
std::optional<HeightMapHit> HeightMap::walk(const Eigen::Vector3d& origin_W,
                                            const Eigen::Vector3d& d,
                                            double max_range_m) const noexcept {
  // Exact: walk the cells the ray's ground track crosses (Amanatides & Woo 1987, "A fast voxel
  // traversal algorithm for ray tracing") and intersect the ray with each cell's bilinear patch.
  // Along the ray the patch is a quadratic in t, so each cell is one closed-form root; the
  // first root is the hit (no step size, nothing narrow can be jumped over).
  // Above the highest node nothing can be hit: start where the ray comes down to it.
  double t = 0.0;
  if (origin_W.z() > max_z_m_) {
    if (!(d.z() < 0.0)) return std::nullopt;
    t = (origin_W.z() - max_z_m_) / -d.z();
    if (t > max_range_m) return std::nullopt;
  } else if (origin_W.z() - heightAt(origin_W.x(), origin_W.y()) <= 0.0) {
    // The origin is on or under the surface.
    HeightMapHit hit;
    if constexpr (kGradient) hit.gradient = gradientAt(origin_W.x(), origin_W.y());
    return hit;
  }
  // Grid coordinates u = (x − x0)/cell, v = (y − y0)/cell along the ray: u(t) = u0 + du·t.
  // Cells are indexed −1 … n−1 per axis: −1 and n−1 are the half-planes outside the grid,
  // where the height is held at the border (the patch is constant along that axis there).
  const double u0 = (origin_W.x() - origin_x_m_) * inv_cell_;
  const double v0 = (origin_W.y() - origin_y_m_) * inv_cell_;
  const double du = d.x() * inv_cell_;
  const double dv = d.y() * inv_cell_;
  const double inv_du = du != 0.0 ? 1.0 / du : 0.0;
  const double inv_dv = dv != 0.0 ? 1.0 / dv : 0.0;
  const auto last_x = static_cast<std::ptrdiff_t>(nx_) - 1;
  const auto last_y = static_cast<std::ptrdiff_t>(ny_) - 1;
  const auto cellOf = [](double w, std::ptrdiff_t last) -> std::ptrdiff_t {
    if (!(w >= 0.0)) return -1;
    return w >= static_cast<double>(last) ? last : static_cast<std::ptrdiff_t>(w);
  };
  std::ptrdiff_t I = cellOf(u0 + du * t, last_x);
  std::ptrdiff_t J = cellOf(v0 + dv * t, last_y);
  static constexpr double kNever = std::numeric_limits<double>::infinity();
  // The ray parameter at which the track leaves cell I along one axis (∞: never).
  const auto exitOf = [](std::ptrdiff_t c, std::ptrdiff_t last, double w0, double dw,
                         double inv_dw) {
    if (dw > 0.0) return c < last ? (static_cast<double>(c + 1) - w0) * inv_dw : kNever;
    if (dw < 0.0) return c >= 0 ? (static_cast<double>(c) - w0) * inv_dw : kNever;
    return kNever;
  };
  double t_exit_u = exitOf(I, last_x, u0, du, inv_du);
  double t_exit_v = exitOf(J, last_y, v0, dv, inv_dv);
  for (;;) {
    const double t_exit = std::min({t_exit_u, t_exit_v, max_range_m});
    // 1. The patch of cell (I, J) as H = a + b·fx + c·fy + e·fx·fy, fx and fy linear in the
    //    local parameter τ = t − t_entry (rate 0 outside the grid, where they are held).
    const auto i = static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(I, 0, last_x - 1));
    const auto j = static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(J, 0, last_y - 1));
    const bool inner_x = I >= 0 && I < last_x;
    const bool inner_y = J >= 0 && J < last_y;
    const double fx = inner_x ? u0 + du * t - static_cast<double>(I) : (I < 0 ? 0.0 : 1.0);
    const double fy = inner_y ? v0 + dv * t - static_cast<double>(J) : (J < 0 ? 0.0 : 1.0);
    const double qx = inner_x ? du : 0.0;
    const double qy = inner_y ? dv : 0.0;
    const double z00 = node(i, j);
    const double b = node(i + 1, j) - z00;
    const double c = node(i, j + 1) - z00;
    const double e = node(i + 1, j + 1) - node(i, j + 1) - b;
    // The hit at τ in this cell, with ∇H there (zero across a held border, as gradientAt()).
    const auto hitAt = [&](double tau) {
      HeightMapHit hit;
      hit.distance_m = t + tau;
      if constexpr (kGradient) {
        hit.gradient.x() = inner_x ? (b + e * (fy + qy * tau)) * inv_cell_ : 0.0;
        hit.gradient.y() = inner_y ? (c + e * (fx + qx * tau)) * inv_cell_ : 0.0;
      }
      return hit;
    };
    // 2. The gap g(τ) = z(τ) − H(τ) = A·τ² + B·τ + C.
    const double C = origin_W.z() + d.z() * t - (z00 + b * fx + c * fy + e * fx * fy);
    if (C <= 0.0) return hitAt(0.0);  // reached at the entry (a root at the previous cell's end)
    const double B = d.z() - (b * qx + c * qy + e * (fx * qy + qx * fy));
    const double A = -e * qx * qy;
    // 3. The first root in [0, τ_exit]: g(0) = C > 0, so it is the smallest positive root.
    //    Most cells have none, which shows without a division: g stays positive on the cell
    //    when g(τ_exit) > 0 and g has no minimum ≤ 0 inside (concave, or rising from τ = 0,
    //    or its vertex −B/2A beyond τ_exit, or B² < 4AC).
    const double tau_exit = t_exit - t;
    const double disc = B * B - 4.0 * A * C;
    const double g_exit = (A * tau_exit + B) * tau_exit + C;
    const bool crosses =
        g_exit <= 0.0 || (A > 0.0 && B < 0.0 && -B < 2.0 * A * tau_exit && disc >= 0.0);
    if (crosses) {
      double tau = kNever;
      if (A == 0.0) {
        if (B < 0.0) tau = C / -B;
      } else if (disc >= 0.0) {
        // The roots without cancellation: q = −(B + sign(B)·√disc)/2, roots q/A and C/q. With
        // C > 0 the first non-negative one is C/q when B < 0 (the smaller of two positive
        // roots for A > 0, the only positive one for A < 0) and q/A otherwise (then A < 0).
        const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
        const double root = B < 0.0 ? C / q : q / A;
        if (root >= 0.0) tau = root;
      }
      if (tau <= tau_exit) return hitAt(tau);
      // Round-off put the root just past the cell's end (or the discriminant just below 0).
      if (g_exit <= 0.0) return hitAt(tau_exit);
    }
    // 4. On to the next cell, or out of range. A ray climbing above the highest node never
    //    comes back down.
    if (t_exit >= max_range_m) return std::nullopt;
    t = t_exit;
    if (d.z() >= 0.0 && origin_W.z() + d.z() * t > max_z_m_) return std::nullopt;
    if (t_exit_u <= t_exit_v) {
      I += du > 0.0 ? 1 : -1;
      t_exit_u = exitOf(I, last_x, u0, du, inv_du);
    } else {
      J += dv > 0.0 ? 1 : -1;
      t_exit_v = exitOf(J, last_y, v0, dv, inv_dv);
    }
  }
}

HeightMap::HeightMap(const model::HeightGrid& grid)
    : HeightMap(grid.origin_x_m, grid.origin_y_m, grid.cell_m, grid.heights) {}

std::optional<RangeHit> HeightMap::rangeHit(const Eigen::Vector3d& origin_W,
                                            const Eigen::Vector3d& unit_dir_W, double max_range_m,
                                            double min_cos_incidence) const noexcept {
  const std::optional<HeightMapHit> hit = rayHitUnit(origin_W, unit_dir_W, max_range_m);
  if (!hit) return std::nullopt;
  const Eigen::Vector2d& g = hit->gradient;
  const Eigen::Vector3d& d = unit_dir_W;
  const double s_inc = d.x() * g.x() + d.y() * g.y() - d.z();
  const bool grazing = !(s_inc >= 0.0 && s_inc * s_inc >= min_cos_incidence * min_cos_incidence *
                                                              (1.0 + g.squaredNorm()));
  return RangeHit{hit->distance_m, grazing};
}

void HeightMap::locate(double x_m, double y_m, std::size_t& i, std::size_t& j, double& fx,
                       double& fy) const noexcept {
  // Clamp to the grid (held at the border outside); a NaN coordinate lands on node 0.
  const double max_u = static_cast<double>(nx_ - 1);
  const double max_v = static_cast<double>(ny_ - 1);
  double u = (x_m - origin_x_m_) * inv_cell_;
  double v = (y_m - origin_y_m_) * inv_cell_;
  u = u > 0.0 ? std::min(u, max_u) : 0.0;
  v = v > 0.0 ? std::min(v, max_v) : 0.0;
  i = std::min(static_cast<std::size_t>(u), nx_ - 2);
  j = std::min(static_cast<std::size_t>(v), ny_ - 2);
  fx = u - static_cast<double>(i);
  fy = v - static_cast<double>(j);
}

double HeightMap::heightAt(double x_m, double y_m) const noexcept {
  std::size_t i = 0;
  std::size_t j = 0;
  double fx = 0.0;
  double fy = 0.0;
  locate(x_m, y_m, i, j, fx, fy);
  const double z0 = node(i, j) + fx * (node(i + 1, j) - node(i, j));
  const double z1 = node(i, j + 1) + fx * (node(i + 1, j + 1) - node(i, j + 1));
  return z0 + fy * (z1 - z0);
}

Eigen::Vector2d HeightMap::gradientAt(double x_m, double y_m) const noexcept {
  std::size_t i = 0;
  std::size_t j = 0;
  double fx = 0.0;
  double fy = 0.0;
  locate(x_m, y_m, i, j, fx, fy);
  // Gradient of the bilinear patch; zero across the border, where the height is held.
  const double u = (x_m - origin_x_m_) * inv_cell_;
  const double v = (y_m - origin_y_m_) * inv_cell_;
  const bool inside_x = u >= 0.0 && u <= static_cast<double>(nx_ - 1);
  const bool inside_y = v >= 0.0 && v <= static_cast<double>(ny_ - 1);
  const double dzdx = inside_x ? ((node(i + 1, j) - node(i, j)) * (1.0 - fy) +
                                  (node(i + 1, j + 1) - node(i, j + 1)) * fy) *
                                     inv_cell_
                               : 0.0;
  const double dzdy = inside_y ? ((node(i, j + 1) - node(i, j)) * (1.0 - fx) +
                                  (node(i + 1, j + 1) - node(i + 1, j)) * fx) *
                                     inv_cell_
                               : 0.0;
  return {dzdx, dzdy};
}

Eigen::Vector3d HeightMap::normalAt(double x_m, double y_m) const noexcept {
  // (−∂H/∂x, −∂H/∂y, 1)/|…|: one square root and one division.
  const Eigen::Vector2d g = gradientAt(x_m, y_m);
  return Eigen::Vector3d(-g.x(), -g.y(), 1.0) * (1.0 / std::sqrt(g.squaredNorm() + 1.0));
}

}  // namespace geaware::sim
