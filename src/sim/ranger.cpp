// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/sim/ranger.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "geaware/model/field_check.hpp"
#include "geaware/model/vehicle_model.hpp"
#include "geaware/sim/terrains.hpp"

namespace geaware::sim {

using model::formatValue;

std::vector<model::FieldError> RangerParams::validate() const {
  std::vector<model::FieldError> out;
  model::FieldChecker c(out);
  using enum model::LowerBound;
  c.range("rate_Hz", rate_Hz, 0.0, 1e4, kExclusive, "Hz");
  c.integerRange("side", side, 1, model::RangerFrame::kMaxSide);
  // Below π the outermost zones (at ±fov/2·(1 − 1/N)) stay short of the horizon.
  c.range("fov_rad", fov_rad, 0.0, std::numbers::pi * 0.9, kExclusive, "rad");
  c.finite("mount_B", mount_B, "m");
  c.nonNegative("min_range_m", min_range_m, "m");
  c.range("max_range_m", max_range_m, 0.0, 1e3, kExclusive, "m");
  if (std::isfinite(min_range_m) && std::isfinite(max_range_m) && min_range_m >= max_range_m) {
    c.fail("min_range_m", formatValue(min_range_m),
           "less than max_range_m = " + formatValue(max_range_m));
  }
  c.range("max_incidence_rad", max_incidence_rad, 0.0, std::numbers::pi / 2.0, kInclusive, "rad");
  c.nonNegative("noise_floor_m", noise_floor_m, "m");
  c.nonNegative("noise_fraction", noise_fraction);
  c.range("outlier_probability", outlier_probability, 0.0, 1.0, kInclusive);
  return out;
}

LatticeRanger::LatticeRanger(const RangerParams& params, std::uint64_t scenario_seed)
    : params_(model::validated(params)),
      noise_(scenario_seed, salt::kRanger),
      clock_(params_.rate_Hz),
      min_cos_incidence_(std::cos(params_.max_incidence_rad)) {
  blank_.side = params_.side;
  blank_.fov_rad = params_.fov_rad;
  blank_.mount_B = params_.mount_B;
  blank_.range_m.fill(0.0);
  blank_.valid.fill(false);
  for (int i = 0; i < params_.side; ++i) {
    for (int j = 0; j < params_.side; ++j) {
      dir_B_[static_cast<std::size_t>(blank_.index(i, j))] = blank_.zoneDirection_B(i, j);
    }
  }
  zones_to_outlier_ = noise_.geometric(params_.outlier_probability);
}

std::optional<model::RangerFrame> LatticeRanger::sample(const PlantState& s, const Terrain* terrain) noexcept {
  if (!isFinite(s)) {
    ++rejected_;
    return std::nullopt;
  }
  if (!clock_.due(s.t_s)) return std::nullopt;
  // Filled in place: a frame is 2.3 kB, and a copy per frame is a measurable part of its cost.
  std::optional<model::RangerFrame> frame(std::in_place, blank_);
  measureInto(*frame, s, terrain);
  return frame;
}

model::RangerFrame LatticeRanger::measure(const PlantState& s, const Terrain* terrain) noexcept {
  model::RangerFrame f = blank_;
  measureInto(f, s, terrain);
  return f;
}

void LatticeRanger::measureInto(model::RangerFrame& f, const PlantState& s,
                                const Terrain* terrain) noexcept {
  f.t_s = s.t_s;
  const Eigen::Matrix3d R_WB = s.q_WB.normalized().toRotationMatrix();
  const Eigen::Vector3d origin_W = s.p_W + R_WB * params_.mount_B;
  const double r_min = params_.min_range_m;
  const double r_max = params_.max_range_m;
  const int zones = params_.side * params_.side;

  // A plane (flat ground, tilted board) in closed form, in the body frame: with the plane's
  // normal n_B and offset c seen from the ranger, zone d hits at r = c/(n_B·d) and meets the
  // surface at cos(incidence) = −n_B·d. Same results as the terrains' own ray casts, without two
  // virtual calls per zone. Other terrains answer each ray themselves (rangeHit).
  const std::optional<LocalPlane> plane =
      terrain != nullptr ? terrain->planeSeenFrom(R_WB, origin_W) : std::nullopt;

  for (int k = 0; k < zones; ++k) {
    const auto idx = static_cast<std::size_t>(k);
    // 1. Outlier zone: a spurious return anywhere in the working range.
    if (--zones_to_outlier_ <= 0) {
      zones_to_outlier_ = noise_.geometric(params_.outlier_probability);
      f.range_m[idx] = r_min + (r_max - r_min) * noise_.uniform();
      f.valid[idx] = true;
      continue;
    }
    // 2. The true range along the zone's centre ray, and whether it meets the surface beyond
    //    the incidence limit (cos(incidence) below cos(max_incidence_rad)).
    double r = 0.0;
    bool grazing = false;
    if (plane) {
      const double dn = plane->normal.dot(dir_B_[idx]);
      if (!(dn < 0.0)) continue;  // looking away from the plane
      r = plane->offset_m / dn;
      grazing = -dn < min_cos_incidence_;
    } else {
      if (terrain == nullptr) continue;
      const std::optional<RangeHit> hit =
          terrain->rangeHit(origin_W, R_WB * dir_B_[idx], r_max, min_cos_incidence_);
      if (!hit) continue;
      r = hit->distance_m;
      grazing = hit->grazing;
    }
    // 3. Out of the working range, or grazing: no return.
    if (!(r >= r_min && r <= r_max) || grazing) continue;
    // 4. Range noise growing with range.
    const double measured = r + (params_.noise_floor_m + params_.noise_fraction * r) * noise_.normal();
    f.range_m[idx] = measured > 0.0 ? measured : 0.0;
    f.valid[idx] = true;
  }
}

}  // namespace geaware::sim
