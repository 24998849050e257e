// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/estimation/lattice_height.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include "geaware/estimation/lattice_steps.hpp"
#include "geaware/model/field_check.hpp"
#include "geaware/model/finite.hpp"
#include "geaware/model/mixer.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::estimation {
const char* toString(LatticeStatus s) noexcept {
  switch (s) {
    case LatticeStatus::kOk:
      return "ok";
    case LatticeStatus::kNonFiniteInput:
      return "non-finite input";
    case LatticeStatus::kBadFrame:
      return "bad frame";
    case LatticeStatus::kTooFewZones:
      return "too few zones";
    case LatticeStatus::kNoSurface:
      return "no surface";
    case LatticeStatus::kDegenerate:
      return "degenerate";
    case LatticeStatus::kSurfaceAbove:
      return "surface above";
  }
  return "?";
}

LatticeHeightParams LatticeHeightParams::forVehicle(const model::VehicleParams& vehicle) {
  LatticeHeightParams p;
  p.diagonal_rotor_distance_m = vehicle.diagonal_rotor_distance_m;
  return p;
}

std::vector<model::FieldError> LatticeHeightParams::validate() const {
  std::vector<model::FieldError> e;
  model::FieldChecker c(e);
  if (!model::allFinite(rotor_plane_centre_B)) {
    c.fail("lattice.rotor_plane_centre_B", "non-finite", "a finite vector [m]");
  }
  c.nonNegative("lattice.diagonal_rotor_distance_m", diagonal_rotor_distance_m);
  c.nonNegative("lattice.min_range_m", min_range_m);
  if (!(std::isfinite(max_range_m) && max_range_m > min_range_m)) {
    c.fail("lattice.max_range_m", model::formatValue(max_range_m), "a finite number > min_range_m");
  }
  c.positive("lattice.inlier_threshold_m", inlier_threshold_m);
  c.integerRange("lattice.ransac_iterations", ransac_iterations, 1, 10000);
  c.integerRange("lattice.max_surfaces", max_surfaces, 1, LatticeHeightEstimator::kMaxSurfaces);
  c.integerAtLeast("lattice.min_inliers", min_inliers, 3);
  c.integerAtLeast("lattice.min_component_zones", min_component_zones, 1);
  c.positive("lattice.range_noise_std_m", range_noise_std_m);
  c.positive("lattice.ground_slope_prior", ground_slope_prior);
  if (!(std::isfinite(max_ground_tilt_rad) && max_ground_tilt_rad > 0.0 &&
        max_ground_tilt_rad < 0.5 * std::numbers::pi)) {
    c.fail("lattice.max_ground_tilt_rad", model::formatValue(max_ground_tilt_rad),
           "a number in (0, π/2)");
  }
  return e;
}

LatticeHeightEstimator::LatticeHeightEstimator(LatticeHeightParams params)
    : params_(std::move(params)) {
  if (auto errors = params_.validate(); !errors.empty())
    throw model::InvalidParameters(std::move(errors));
  const auto r = model::Mixer::rotorPositions_B(params_.diagonal_rotor_distance_m);
  for (std::size_t i = 0; i < 4; ++i) rotors_B_[i] = r[i];  // relative to c_B by definition
}

LatticeHeight LatticeHeightEstimator::estimate(const model::RangerFrame& frame,
                                               const Eigen::Quaterniond& q_WB) const noexcept {
  using namespace lattice;
  LatticeHeight out;
  const LatticeHeightParams& p = params_;

  // 0. Guards on the frame as a whole.
  const double qn = q_WB.norm();
  if (!(model::allFinite(q_WB.coeffs()) && std::abs(qn - 1.0) < 1e-3 && model::allFinite(frame.mount_B) &&
        std::isfinite(frame.fov_rad))) {
    out.status = LatticeStatus::kNonFiniteInput;
    return out;
  }
  if (frame.side < 1 || frame.side > model::RangerFrame::kMaxSide || !(frame.fov_rad > 0.0) ||
      !(frame.fov_rad < std::numbers::pi)) {
    out.status = LatticeStatus::kBadFrame;
    return out;
  }
  const Eigen::Matrix3d R = (q_WB.normalized()).toRotationMatrix();

  // 1. Points.
  Points w;
  collectPoints(frame, R, p.rotor_plane_centre_B, p.min_range_m, p.max_range_m, w,
                out.discarded_zones);
  out.usable_zones = w.n;
  if (w.n < p.min_inliers) {
    out.status = LatticeStatus::kTooFewZones;
    return out;
  }

  // 2. Sequential RANSAC with least-squares refinement and the zone-patch support rule.
  SplitMix64 rng{p.seed};
  bool degenerate = false;
  for (int s = 0; s < p.max_surfaces; ++s) {
    const SurfaceResult r = extractSurface(w, s, out.surfaces, frame.side, p, rng);
    degenerate = degenerate || r.degenerate;
    if (r.outcome == SurfaceResult::kStop) break;
    if (r.outcome == SurfaceResult::kRejected) continue;
    out.planes[static_cast<std::size_t>(out.surfaces)] = r.plane;
    ++out.surfaces;
  }
  if (out.surfaces == 0) {
    out.status = degenerate ? LatticeStatus::kDegenerate : LatticeStatus::kNoSurface;
    return out;
  }

  // 3. The ground: the surface under the rotor-plane centre; with per-rotor heights, the
  //    surfaces under the rotors in the same pass.
  const bool rotors = p.diagonal_rotor_distance_m > 0.0;
  std::array<Eigen::Vector3d, kUnderPoints> P;
  P[0] = Eigen::Vector3d::Zero();
  std::array<int, kUnderPoints> owner{};
  std::array<double, kUnderPoints> dist{};
  if (rotors) {
    for (std::size_t r = 0; r < 4; ++r) P[r + 1] = R * rotors_B_[r];
    surfacesUnder(w, P, owner, dist);
  } else {
    owner[0] = surfaceUnder(w, P[0], dist[0]);
  }
  const int g = owner[0];
  const GroundPlane& ground = out.planes[static_cast<std::size_t>(g)];

  // 4. Height along −z_W: the point (0, 0, −h) lies on n·X = c, so h = −c / n_z.
  out.normal_W = ground.normal_W;
  out.inliers = ground.support;
  out.rms_residual_m = ground.rms_residual_m;
  out.height_m = -ground.offset_m / ground.normal_W.z();
  if (!(out.height_m > 0.0)) {
    out.status = LatticeStatus::kSurfaceAbove;
    return out;
  }
  if (rotors) {
    for (std::size_t r = 0; r < 4; ++r) {
      const int o = owner[r + 1];
      out.rotor_support_distance_m[r] = dist[r + 1];
      const GroundPlane& pl = out.planes[static_cast<std::size_t>(o)];
      out.rotor_height_m[r] = (pl.normal_W.dot(P[r + 1]) - pl.offset_m) / pl.normal_W.z();
      out.rotor_height_offset_m[r] =
          o == g ? 0.0
                 : out.rotor_height_m[r] -
                       (ground.normal_W.dot(P[r + 1]) - ground.offset_m) / ground.normal_W.z();
    }
  }
  out.status = LatticeStatus::kOk;
  out.valid = true;
  return out;
}

}  // namespace geaware::estimation
