// The terrains: the generic ray cast of Terrain and the concrete shapes of terrains.hpp.
#include "geaware/sim/terrain.hpp"
#include "geaware/sim/terrains.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
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

namespace {

std::string locationPrefix(const std::string& file, int line, int column) {
  std::string s = file;
  if (line > 0) s += ":" + std::to_string(line);
  if (line > 0 && column > 0) s += ":" + std::to_string(column);
  return s;
}

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

/// Parses the whole of `s` as a double; nothing on failure.
std::optional<double> parseNumber(std::string_view s) {
  if (s.empty()) return std::nullopt;
  if (s.front() == '+') s.remove_prefix(1);
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

}  // namespace

TerrainFileError::TerrainFileError(std::string file, int line, int column,
                                   const std::string& message)
    : std::runtime_error(locationPrefix(file, line, column) + ": " + message),
      file_(std::move(file)),
      line_(line),
      column_(column) {}

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
  // The gradient of a bilinear patch is a convex combination of its edges' slopes, so the
  // steepest edges bound the slope everywhere (and outside, where the height is held, it is 0).
  for (std::size_t j = 0; j < ny_; ++j) {
    for (std::size_t i = 0; i < nx_; ++i) {
      if (i + 1 < nx_)
        max_slope_x_ = std::max(max_slope_x_, std::abs(node(i + 1, j) - node(i, j)) / cell_m_);
      if (j + 1 < ny_)
        max_slope_y_ = std::max(max_slope_y_, std::abs(node(i, j + 1) - node(i, j)) / cell_m_);
    }
  }
}

std::optional<double> HeightMap::rayCast(const Eigen::Vector3d& origin_W,
                                         const Eigen::Vector3d& dir_W,
                                         double max_range_m) const noexcept {
  if (!validRay(origin_W, dir_W, max_range_m)) return std::nullopt;
  const Eigen::Vector3d d = dir_W.normalized();
  const auto gap = [&](double t) {
    const Eigen::Vector3d p = origin_W + t * d;
    return p.z() - heightAt(p.x(), p.y());
  };
  // Along the ray the gap f(t) = z(t) − H(x(t), y(t)) falls at most at the rate
  // −d_z + Lx·|d_x| + Ly·|d_y| (L the slope bounds): a step of f/rate cannot cross the surface.
  const double rate = -d.z() + max_slope_x_ * std::abs(d.x()) + max_slope_y_ * std::abs(d.y());
  double t = 0.0;
  double f = gap(0.0);
  if (f <= 0.0) return 0.0;
  if (!(rate > 0.0)) return std::nullopt;  // the ray climbs faster than any slope of the map
  // Near the surface the safe steps shrink geometrically; below kMinStep the march takes
  // fixed steps and refines the one that crosses, to 1e-9 m like the generic march.
  constexpr double kMinStep = 1e-4;  // [m]
  for (int k = 0; k < 100000; ++k) {
    const double t_next = t + std::max(f / rate, kMinStep);
    if (t_next > max_range_m) {
      // The last stretch: a hit there is within one safe step, check the end of the range.
      const double f_end = gap(max_range_m);
      if (f_end > 0.0) return std::nullopt;
      return refineRoot(gap, t, f, max_range_m, f_end);
    }
    const double f_next = gap(t_next);
    if (f_next <= 0.0)
      return refineRoot(gap, t, f, t_next, f_next);  // only a minimum step can overshoot
    t = t_next;
    f = f_next;
  }
  return Terrain::rayCast(origin_W, dir_W, max_range_m);  // pathological: fall back to the march
}

HeightMap HeightMap::fromFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw TerrainFileError(path, 0, 0, "cannot open the height-map file");
  std::optional<double> origin_x;
  std::optional<double> origin_y;
  std::optional<double> cell;
  int first_data_line = 0;
  std::vector<std::vector<double>> rows;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    const std::string_view s = trim(text);
    if (s.empty()) continue;
    if (s.front() == '#') {
      // "# key: value" for one of the known keys, anything else is a comment.
      const std::string_view body = trim(s.substr(1));
      const auto colon = body.find(':');
      if (colon == std::string_view::npos) continue;
      const std::string_view key = trim(body.substr(0, colon));
      std::optional<double>* slot = key == "origin_x_m"   ? &origin_x
                                    : key == "origin_y_m" ? &origin_y
                                    : key == "cell_m"     ? &cell
                                                          : nullptr;
      if (slot == nullptr) continue;
      if (first_data_line > 0) {
        throw TerrainFileError(path, line, 0,
                               "header key '" + std::string(key) +
                                   "' after the first data row (line " +
                                   std::to_string(first_data_line) + ")");
      }
      if (slot->has_value())
        throw TerrainFileError(path, line, 0, "header key '" + std::string(key) + "' given twice");
      const std::string_view value = trim(body.substr(colon + 1));
      const auto v = parseNumber(value);
      if (!v || !std::isfinite(*v)) {
        throw TerrainFileError(path, line, 0,
                               "header key '" + std::string(key) + "': '" + std::string(value) +
                                   "' is not a finite number");
      }
      if (slot == &cell && !(*v > 0.0)) {
        throw TerrainFileError(
            path, line, 0, "header key 'cell_m': " + std::string(value) + " must be positive (m)");
      }
      *slot = *v;
      continue;
    }
    if (first_data_line == 0) first_data_line = line;
    std::vector<double> row;
    std::size_t start = 0;
    int column = 0;
    for (;;) {
      ++column;
      const std::size_t comma = s.find(',', start);
      const std::string_view field =
          trim(s.substr(start, comma == std::string_view::npos ? s.npos : comma - start));
      const auto v = parseNumber(field);
      if (!v)
        throw TerrainFileError(path, line, column, "'" + std::string(field) + "' is not a number");
      if (!std::isfinite(*v))
        throw TerrainFileError(path, line, column,
                               "height '" + std::string(field) + "' is not finite");
      row.push_back(*v);
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (!rows.empty() && row.size() != rows.front().size()) {
      throw TerrainFileError(path, line, 0,
                             "row has " + std::to_string(row.size()) +
                                 " values, the first row (line " + std::to_string(first_data_line) +
                                 ") has " + std::to_string(rows.front().size()) +
                                 ": the grid must be rectangular");
    }
    rows.push_back(std::move(row));
  }
  const char* missing = !origin_x   ? "origin_x_m"
                        : !origin_y ? "origin_y_m"
                        : !cell     ? "cell_m"
                                    : nullptr;
  if (missing != nullptr) {
    throw TerrainFileError(path, 0, 0,
                           std::string("missing header key '") + missing + "' (a line '# " +
                               missing + ": VALUE' before the data)");
  }
  if (rows.size() < 2 || rows.front().size() < 2) {
    throw TerrainFileError(
        path, 0, 0,
        "the grid has " + std::to_string(rows.size()) + " rows of " +
            std::to_string(rows.empty() ? 0 : rows.front().size()) +
            " values; at least 2 rows of 2 are needed for bilinear interpolation");
  }
  return HeightMap(*origin_x, *origin_y, *cell, rows);
}

void HeightMap::locate(double x_m, double y_m, std::size_t& i, std::size_t& j, double& fx,
                       double& fy) const noexcept {
  // Clamp to the grid (held at the border outside); a NaN coordinate lands on node 0.
  const double max_u = static_cast<double>(nx_ - 1);
  const double max_v = static_cast<double>(ny_ - 1);
  double u = (x_m - origin_x_m_) / cell_m_;
  double v = (y_m - origin_y_m_) / cell_m_;
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

Eigen::Vector3d HeightMap::normalAt(double x_m, double y_m) const noexcept {
  std::size_t i = 0;
  std::size_t j = 0;
  double fx = 0.0;
  double fy = 0.0;
  locate(x_m, y_m, i, j, fx, fy);
  // Gradient of the bilinear patch; zero across the border, where the height is held.
  const double u = (x_m - origin_x_m_) / cell_m_;
  const double v = (y_m - origin_y_m_) / cell_m_;
  const bool inside_x = u >= 0.0 && u <= static_cast<double>(nx_ - 1);
  const bool inside_y = v >= 0.0 && v <= static_cast<double>(ny_ - 1);
  const double dzdx = inside_x ? ((node(i + 1, j) - node(i, j)) * (1.0 - fy) +
                                  (node(i + 1, j + 1) - node(i, j + 1)) * fy) /
                                     cell_m_
                               : 0.0;
  const double dzdy = inside_y ? ((node(i, j + 1) - node(i, j)) * (1.0 - fx) +
                                  (node(i + 1, j + 1) - node(i + 1, j)) * fx) /
                                     cell_m_
                               : 0.0;
  return Eigen::Vector3d(-dzdx, -dzdy, 1.0).normalized();
}

}  // namespace geaware::sim
