// SPDX-License-Identifier: BSD-3-Clause
// Boxes around the vehicle, their ceiling and wall effects, strikes and single-beam returns:
// see obstacles.hpp and docs/world.md §10.
#include "geaware/sim/obstacles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

#include <Eigen/Geometry>

#include "geaware/model/field_check.hpp"
#include "geaware/model/proximity_effect.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::sim {

Box boxFromCorners(const Eigen::Vector3d& min_W, const Eigen::Vector3d& max_W, double yaw_rad,
                   std::string name) {
  if (!min_W.allFinite() || !max_W.allFinite() || !std::isfinite(yaw_rad) ||
      !(max_W.array() > min_W.array()).all()) {
    throw std::invalid_argument("box '" + name + "': needs finite corners with max > min on every axis");
  }
  Box b;
  b.name = std::move(name);
  b.centre_W = 0.5 * (min_W + max_W);
  b.half_extent_m = 0.5 * (max_W - min_W);
  b.R_WO = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return b;
}

Obstacles::Obstacles(std::vector<Box> boxes) : boxes_(std::move(boxes)) {
  for (const Box& b : boxes_) {
    const bool extent_ok = b.half_extent_m.allFinite() && (b.half_extent_m.array() > 0.0).all();
    const bool rotation_ok = b.R_WO.allFinite() &&
                             (b.R_WO.transpose() * b.R_WO - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-9 &&
                             b.R_WO.determinant() > 0.0;
    if (!extent_ok || !b.centre_W.allFinite() || !rotation_ok) {
      throw std::invalid_argument("obstacle '" + b.name +
                                  "': needs a finite centre, positive finite half extents and a rotation");
    }
    R_OW_.push_back(b.R_WO.transpose());
  }
}

BoxProximity Obstacles::proximity(std::size_t k, const Eigen::Vector3d& p_W) const noexcept {
  const Box& b = boxes_[k];
  const Eigen::Vector3d local = R_OW_[k] * (p_W - b.centre_W);
  const Eigen::Vector3d nearest = local.cwiseMax(-b.half_extent_m).cwiseMin(b.half_extent_m);
  const Eigen::Vector3d gap = local - nearest;
  BoxProximity p;
  p.distance_m = gap.norm();
  p.inside = p.distance_m == 0.0;
  if (!p.inside) p.normal_W = b.R_WO * (gap / p.distance_m);
  return p;
}

std::optional<std::size_t> Obstacles::containing(const Eigen::Vector3d& p_W) const noexcept {
  for (std::size_t k = 0; k < boxes_.size(); ++k) {
    const Eigen::Vector3d local = R_OW_[k] * (p_W - boxes_[k].centre_W);
    if ((local.cwiseAbs().array() <= boxes_[k].half_extent_m.array()).all()) return k;
  }
  return std::nullopt;
}

double Obstacles::clearance(const Eigen::Vector3d& p_W) const noexcept {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < boxes_.size(); ++k) d = std::min(d, proximity(k, p_W).distance_m);
  return d;
}

std::optional<Obstacles::Hit> Obstacles::rayCast(const Eigen::Vector3d& origin_W, const Eigen::Vector3d& dir_W,
                                                 double max_range_m) const noexcept {
  std::optional<Hit> best;
  if (!origin_W.allFinite() || !dir_W.allFinite() || !(max_range_m >= 0.0)) return best;
  for (std::size_t k = 0; k < boxes_.size(); ++k) {
    const Box& b = boxes_[k];
    const Eigen::Vector3d o = R_OW_[k] * (origin_W - b.centre_W);
    const Eigen::Vector3d d = R_OW_[k] * dir_W;
    // Slab method: the ray is inside the box for t in [t_in, t_out]; the entering face's axis
    // gives the normal.
    double t_in = -std::numeric_limits<double>::infinity();
    double t_out = std::numeric_limits<double>::infinity();
    int axis = -1;
    bool miss = false;
    for (int i = 0; i < 3 && !miss; ++i) {
      const double h = b.half_extent_m[i];
      if (std::abs(d[i]) < 1e-15) {
        miss = std::abs(o[i]) > h;
        continue;
      }
      double t0 = (-h - o[i]) / d[i];
      double t1 = (h - o[i]) / d[i];
      if (t0 > t1) std::swap(t0, t1);
      if (t0 > t_in) {
        t_in = t0;
        axis = i;
      }
      t_out = std::min(t_out, t1);
      miss = t_in > t_out;
    }
    if (miss || t_out < 0.0) continue;
    Hit hit;
    if (t_in <= 0.0 || axis < 0) {
      hit.distance_m = 0.0;  // the origin is inside
    } else {
      hit.distance_m = t_in;
      hit.cos_incidence = std::abs(d[axis]);  // |d·n| with n the entering face's axis
    }
    if (hit.distance_m <= max_range_m && (!best || hit.distance_m < best->distance_m)) best = hit;
  }
  return best;
}

ProximityContribution::ProximityContribution(const TruthParams& truth,
                                             std::shared_ptr<const Obstacles> obstacles)
    : obstacles_(std::move(obstacles)), geometry_(truth.rotorGeometry()) {
  if (!obstacles_) throw std::invalid_argument("ProximityContribution: no obstacles");
}

Wrench ProximityContribution::wrench(const ContributionContext& ctx) noexcept {
  Wrench w;
  const Obstacles& obs = *obstacles_;
  const Eigen::Matrix3d& R = ctx.R_WB;
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3d& r_B = geometry_.position_B[i];
    const Eigen::Vector3d a_W = R * geometry_.thrust_axis_B[i];
    const Eigen::Vector3d c_W = ctx.body.p_W + R * r_B;
    Eigen::Vector3d u = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < obs.boxes().size(); ++k) {
      const BoxProximity p = obs.proximity(k, c_W);
      if (!p.inside) u += model::imageInflow(p.distance_m, geometry_.radius_m, p.normal_W, a_W);
    }
    if (u.isZero(0.0)) continue;
    const double n = ctx.n_rpm[i];
    const double t_free = geometry_.k_T_N_per_rpm2[i] * n * n;
    const model::ProximityResponse resp = model::proximityResponse(u, a_W);
    const Eigen::Vector3d f_W = t_free * ((resp.thrust_ratio - 1.0) * a_W + resp.side_force_per_N);
    const Eigen::Vector3d f_B = R.transpose() * f_W;
    w.force_B += f_B;
    w.torque_B += r_B.cross(f_B);
  }
  return w;
}

std::optional<Crash> obstacleStrike(const Obstacles& obstacles, const TruthParams& truth,
                                    const Eigen::Vector3d& p_W, const Eigen::Matrix3d& R_WB, double t_s,
                                    const std::vector<Eigen::Vector2d>& rim_unit) noexcept {
  const auto hit = [&](const Eigen::Vector3d& pt, StrikePart part, int index) -> std::optional<Crash> {
    if (!obstacles.containing(pt)) return std::nullopt;
    Crash c{t_s, pt, part, index, 0.0};
    c.obstacle = true;
    return c;
  };
  const Eigen::Vector3d ex = truth.propeller_radius_m * R_WB.col(0);
  const Eigen::Vector3d ey = truth.propeller_radius_m * R_WB.col(1);
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3d centre = p_W + R_WB * truth.rotor_position_B[i];
    for (const Eigen::Vector2d& u : rim_unit) {
      if (auto c = hit(centre + u.x() * ex + u.y() * ey, StrikePart::kRotorDisc, static_cast<int>(i))) return c;
    }
  }
  for (std::size_t k = 0; k < truth.landing_feet_B.size(); ++k) {
    if (auto c = hit(p_W + R_WB * truth.landing_feet_B[k], StrikePart::kLandingFoot, static_cast<int>(k)))
      return c;
  }
  return hit(p_W, StrikePart::kBody, 0);
}

std::vector<model::FieldError> BeamRangerParams::validate() const {
  std::vector<model::FieldError> out;
  model::FieldChecker c(out);
  using enum model::LowerBound;
  c.finite("direction_B", direction_B);
  if (direction_B.allFinite() && std::abs(direction_B.norm() - 1.0) > 1e-6) {
    c.fail("direction_B", model::formatValue(direction_B.norm()), "a unit vector (norm 1)");
  }
  c.finite("mount_B", mount_B, "m");
  c.range("rate_Hz", rate_Hz, 0.0, 1e4, kExclusive, "Hz");
  c.nonNegative("min_range_m", min_range_m, "m");
  c.range("max_range_m", max_range_m, 0.0, 1e3, kExclusive, "m");
  if (std::isfinite(min_range_m) && std::isfinite(max_range_m) && min_range_m >= max_range_m) {
    c.fail("min_range_m", model::formatValue(min_range_m),
           "less than max_range_m = " + model::formatValue(max_range_m));
  }
  c.range("max_incidence_rad", max_incidence_rad, 0.0, std::numbers::pi / 2.0, kInclusive, "rad");
  c.nonNegative("noise_floor_m", noise_floor_m, "m");
  c.nonNegative("noise_fraction", noise_fraction);
  c.range("outlier_probability", outlier_probability, 0.0, 1.0, kInclusive);
  return out;
}

std::vector<BeamRangerParams> defaultBeamRangers() {
  std::vector<BeamRangerParams> v;
  const Eigen::Vector3d dirs[] = {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-1, 0, 0),
                                  Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, -1, 0)};
  for (const Eigen::Vector3d& d : dirs) {
    BeamRangerParams p;
    p.direction_B = d;
    v.push_back(p);
  }
  return v;
}

BeamRanger::BeamRanger(const BeamRangerParams& params, std::uint64_t scenario_seed, std::uint64_t index)
    : params_(model::validated(params)),
      noise_(scenario_seed, salt::kBeamRanger + index),
      clock_(params_.rate_Hz) {}

std::optional<model::BeamReading> BeamRanger::sample(const PlantState& state, const Obstacles* obstacles,
                                                     const Terrain* terrain) noexcept {
  if (!clock_.due(state.t_s)) return std::nullopt;
  model::BeamReading r;
  r.t_s = state.t_s;
  r.direction_B = params_.direction_B;
  r.mount_B = params_.mount_B;
  if (!state.p_W.allFinite() || !state.q_WB.coeffs().allFinite()) return r;
  const Eigen::Matrix3d R = state.q_WB.toRotationMatrix();
  const Eigen::Vector3d o = state.p_W + R * params_.mount_B;
  const Eigen::Vector3d d = R * params_.direction_B;
  const double min_cos = std::cos(params_.max_incidence_rad);
  double range = std::numeric_limits<double>::infinity();
  bool grazing = false;
  if (obstacles != nullptr) {
    if (const auto h = obstacles->rayCast(o, d, params_.max_range_m)) {
      range = h->distance_m;
      grazing = h->cos_incidence < min_cos;
    }
  }
  if (terrain != nullptr) {
    if (const auto h = terrain->rangeHit(o, d, params_.max_range_m, min_cos); h && h->distance_m < range) {
      range = h->distance_m;
      grazing = h->grazing;
    }
  }
  // Three draws per reading (the outlier test, the noise, the outlier's range), whatever the
  // geometry, so the stream does not depend on it (a non-finite state returned above draws none).
  const bool outlier = noise_.uniformHalfOpen() < params_.outlier_probability;
  const double z = noise_.normal();
  const double u = noise_.uniformHalfOpen();
  if (outlier) {
    r.range_m = params_.min_range_m + (params_.max_range_m - params_.min_range_m) * u;
    r.valid = true;
    return r;
  }
  if (!std::isfinite(range) || grazing || range < params_.min_range_m) return r;
  r.range_m = std::max(0.0, range + (params_.noise_floor_m + params_.noise_fraction * range) * z);
  r.valid = true;
  return r;
}

}  // namespace geaware::sim
