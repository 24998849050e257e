// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Height of the rotor-plane centre above the ground, and the ground normal, from one frame of
// the N×N lattice time-of-flight ranger and the attitude estimate (SPEC §4).
//
// 1. Every valid zone becomes a 3-D point X = R_WB·(mount_B + r·d_B − c_B) in a frame with
//    the world's orientation and its origin at the rotor-plane centre c_B.
// 2. Surfaces are found by sequential RANSAC (a fixed, seeded budget per surface, MSAC
//    scoring; planes steeper than max_ground_tilt_rad are not ground), each refined by least
//    squares on its inliers with a weak level-ground prior on the slope. A lattice ranger sees a
//    real surface as a contiguous patch of zones, so only inliers in 8-connected zone components of
//    at least min_component_zones count as the surface's support: stray outlier zones that happen
//    to lie on a plane do not make one.
// 3. The ground is the surface *under the vehicle*: the one owning the supporting zone whose
//    point lies nearest to the vertical through the rotor-plane centre. Over a table edge this
//    picks the table or the floor by where the centre is, not which surface fills more zones.
// 4. Height h = vertical distance (along −z_W) from c_B to that plane; per-rotor heights use
//    the same rule at each rotor centre (partial ground effect over steps).
// Fixed-size storage (RangerFrame::kMaxZones); no allocation, no exceptions in estimate().
// Derivation and choices: docs/estimation.md.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "geaware/model/sensor_data.hpp"
#include "geaware/model/vehicle_params.hpp"

namespace geaware::estimation {

/// Surfaces extracted from one frame, at most (e.g. floor, table top, a box).
inline constexpr int kMaxGroundPlanes = 3;

struct LatticeHeightParams {
  /// Rotor-plane centre in the body frame [m]. The rotor centres are the mixer's layout
  /// (model::Mixer::rotorPositions_B) shifted by this point.
  Eigen::Vector3d rotor_plane_centre_B = Eigen::Vector3d::Zero();
  /// b, distance between diagonal rotor axes [m]; 0 skips the per-rotor heights.
  double diagonal_rotor_distance_m = 0.0;
  double min_range_m = 0.01;  ///< shorter returns are discarded [m]
  double max_range_m = 4.0;   ///< longer returns are discarded [m]
  double inlier_threshold_m =
      0.03;  ///< point-to-plane distance of an inlier (≈ 3σ of range noise) [m]
  double range_noise_std_m = 0.01;  ///< σ_r, range noise of one zone, 1σ [m]
  /// σ_s, prior 1σ of the ground's slope (tan of its tilt) [-]: keeps the fitted plane level
  /// when the footprint is too small to resolve a tilt; a large value disables the prior.
  double ground_slope_prior = 0.3;
  int ransac_iterations = 40;          ///< hypotheses per surface (fixed budget) [-]
  int max_surfaces = 3;                ///< surfaces extracted per frame [-]
  int min_inliers = 8;                 ///< support a surface needs to count [-]
  int min_component_zones = 4;         ///< smallest contiguous zone patch kept as support [-]
  double max_ground_tilt_rad = 0.6;    ///< steeper planes are not ground (walls, clutter) [rad]
  std::uint64_t seed = 0x5eed5eedULL;  ///< RANSAC sampling seed (reseeded every frame) [-]

  /// Params for a vehicle: b from its geometry, rotor-plane centre at the body origin.
  [[nodiscard]] static LatticeHeightParams forVehicle(const model::VehicleParams& vehicle);

  /// Every offending field with its value and expectation; empty when usable.
  [[nodiscard]] std::vector<model::FieldError> validate() const;
};

enum class LatticeStatus : std::uint8_t {
  kOk,
  kNonFiniteInput,  ///< attitude or mount not finite / not a rotation
  kBadFrame,        ///< side outside [1, kMaxSide] or field of view outside (0, π)
  kTooFewZones,     ///< fewer usable zones than min_inliers
  kNoSurface,       ///< no plane reached min_inliers supporting zones
  kDegenerate,      ///< inliers collinear: no unique plane
  kSurfaceAbove,    ///< the chosen plane is not below the rotor-plane centre
};

[[nodiscard]] const char* toString(LatticeStatus s) noexcept;

/// A plane n·X = c in the vehicle-centred, world-oriented frame of step 1 (n unit, n_z > 0).
struct GroundPlane {
  Eigen::Vector3d normal_W = Eigen::Vector3d::UnitZ();
  double offset_m = 0.0;  ///< c [m]; −c is the perpendicular distance from c_B
  int support = 0;        ///< supporting zones [-]
  double rms_residual_m = 0.0;
};

struct LatticeHeight {
  bool valid = false;
  LatticeStatus status = LatticeStatus::kNoSurface;
  double height_m = 0.0;                                ///< along −z_W from c_B [m]
  Eigen::Vector3d normal_W = Eigen::Vector3d::UnitZ();  ///< ground normal, pointing up
  int inliers = 0;                                      ///< supporting zones of the ground
  int usable_zones = 0;                                 ///< valid, finite, in range
  int discarded_zones = 0;      ///< flagged valid but non-finite or out of range
  double rms_residual_m = 0.0;  ///< of the ground's inliers [m]
  int surfaces = 0;             ///< planes found in the frame
  std::array<GroundPlane, kMaxGroundPlanes> planes{};  ///< the first `surfaces` of them
  /// Per rotor (mixer order): vertical distance from the rotor centre to the surface beneath
  /// it [m], and the horizontal distance from the rotor's vertical to the nearest zone that
  /// supports that surface [m] (large: the surface is extrapolated, the rotor is outside the
  /// ranger's footprint). Zero when per-rotor heights are off or the result is invalid.
  std::array<double, 4> rotor_height_m{};
  std::array<double, 4> rotor_support_distance_m{};
  /// Per rotor: rotor_height_m less the rotor's vertical distance to the ground plane (the
  /// surface under the rotor-plane centre) extended beneath it [m]. Exactly 0 where the same
  /// surface lies under the rotor; +0.1 m for a rotor beyond the edge of a 10 cm table the
  /// vehicle is over (partial ground effect).
  std::array<double, 4> rotor_height_offset_m{};
};

class LatticeHeightEstimator {
 public:
  static constexpr int kMaxSurfaces = kMaxGroundPlanes;

  /// Validates params (throws model::InvalidParameters).
  explicit LatticeHeightEstimator(LatticeHeightParams params);

  /// One frame; q_WB is the attitude estimate at the frame's time. No allocation.
  [[nodiscard]] LatticeHeight estimate(const model::RangerFrame& frame,
                                       const Eigen::Quaterniond& q_WB) const noexcept;

  [[nodiscard]] const LatticeHeightParams& params() const noexcept { return params_; }

 private:
  LatticeHeightParams params_;
  std::array<Eigen::Vector3d, 4> rotors_B_;  ///< rotor centres relative to c_B [m]
};

}  // namespace geaware::estimation
