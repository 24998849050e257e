// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The steps of LatticeHeightEstimator::estimate (lattice_height.hpp), each a function of its
// inputs so that each can be tested alone:
//   1. collectPoints: valid zones → 3-D points in the vehicle-centred, world-oriented frame;
//   2. extractSurface, per surface: bestHypothesis (RANSAC with MSAC scoring), fitPlane
//      (regularised least squares), keepZonePatches (8-connected support rule, union-find),
//      fitPlane again;
//   3. surfaceUnder: the surface owning the supporting zone nearest to a vertical.
// Fixed-size storage, no allocation.

#include <array>
#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geaware/estimation/lattice_height.hpp"
#include "geaware/model/sensor_data.hpp"

namespace geaware::estimation::lattice {

inline constexpr int kN = model::RangerFrame::kMaxZones;
inline constexpr int kUnassigned = -1;
inline constexpr int kDiscarded = -2;  // inlier of a surface, but not in a large enough zone patch

/// splitmix64 (Steele et al. 2014): tiny, deterministic, good enough to draw RANSAC triples.
struct SplitMix64 {
  std::uint64_t s;
  std::uint64_t next() noexcept {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  int below(int n) noexcept { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
};

/// Scratch of one frame (≈ 10 kB, on the caller's stack).
struct Points {
  std::array<Eigen::Vector3d, kN> X;  // points, vehicle-centred world-oriented frame [m]
  std::array<int, kN> zone;           // zone index of each point
  std::array<int, kN> label;          // surface index, kUnassigned or kDiscarded
  std::array<int, kN> point_of_zone;  // inverse of `zone`, −1 for unusable zones
  std::array<int, kN> pool;           // candidate point indices of the current RANSAC
  std::array<int, kN> parent;         // union-find parents of the zone patches
  std::array<int, kN> component_size; // zones per patch, at each patch's root
  std::array<bool, kN> inlier;        // per point, for the current surface
  std::array<int, kN> sel;            // the selected points in increasing order (see n_sel)
  int n = 0;
  int n_sel = 0;                      // markInliers: the inliers; keepZonePatches: the support
};

struct PlaneFit {
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  double c = 0.0;
  double rms = 0.0;
  bool ok = false;
};

/// Step 1: the valid, finite, in-range zones of `frame` as points X = R·(origin_B + r·d) with
/// origin_B = mount_B − c_B; counts the discarded zones (flagged valid but unusable).
void collectPoints(const model::RangerFrame& frame, const Eigen::Matrix3d& R,
                   const Eigen::Vector3d& rotor_plane_centre_B, double min_range_m,
                   double max_range_m, Points& w, int& discarded_zones) noexcept;

/// Plane through the flagged points by regularised least squares on the ground's graph
/// z = a + b·x + c·y: minimise Σ(z_i − a − b·x_i − c·y_i)²/σ_r² + (b² + c²)/σ_s², the MAP
/// estimate with range noise σ_r and a level-ground prior of slope σ_s. Close to the ground
/// the lattice's footprint is a few centimetres wide and the tilt is not observable from it;
/// the prior then keeps the plane level instead of letting noise tilt it (and the tilt,
/// extrapolated to the rotor-plane centre, bias the height). Over a wide footprint the data
/// dominate. Not ok when fewer than 3 points or when the points are collinear seen from above
/// (the smaller horizontal spread below 1 % of the larger), which no prior should paper over.
PlaneFit fitPlane(const Points& w, const std::array<bool, kN>& use, double lambda) noexcept;

/// The same fit on the points w.X[idx[0..m)], idx increasing (the same sums in the same order as
/// the flagged form, without a branch per point).
PlaneFit fitPlane(const Points& w, const int* idx, int m, double lambda) noexcept;

/// Flags the unassigned points within `threshold_m` of n·X = c and lists them in
/// w.sel[0..w.n_sel); returns how many.
int markInliers(Points& w, const Eigen::Vector3d& n, double c, double threshold_m) noexcept;

/// Best plane hypothesis of one RANSAC round over the `m` pooled points.
struct Hypothesis {
  int count = 0;  ///< points within half the inlier threshold of the best plane
  int proper = 0;  ///< hypotheses from non-collinear triples
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  double c = 0.0;
};

/// Step 2a: hypotheses from random triples of w.pool[0..m), planes steeper than the tilt limit
/// skipped, scored by MSAC (Torr & Zisserman 2000): the sum of squared residuals truncated at
/// half the inlier threshold, lower is better. Plain inlier counting prefers a tilted plane that
/// cuts through both levels of a step; the truncated cost with the narrower band prefers the
/// plane the points actually lie on.
Hypothesis bestHypothesis(const Points& w, int m, SplitMix64& rng, int iterations,
                          double cos_tilt, double threshold_m) noexcept;

/// Step 2c: labels the inliers in 8-connected zone patches of at least `min_component_zones`
/// with `label`, the others kDiscarded, and lists the kept ones in w.sel[0..w.n_sel); returns
/// the number of zones kept.
int keepZonePatches(Points& w, int side, int label, int min_component_zones) noexcept;

/// Relabels every point labelled `from` as `to`.
void relabel(Points& w, int from, int to) noexcept;

/// Step 2, one surface: hypothesis, refinement, support rule, final fit. Labels its support
/// `slot` on success.
struct SurfaceResult {
  enum Outcome { kFound, kRejected, kStop } outcome = kStop;
  bool degenerate = false;  ///< a fit found collinear points
  GroundPlane plane;
};
SurfaceResult extractSurface(Points& w, int s, int slot, int side, const LatticeHeightParams& p,
                             SplitMix64& rng) noexcept;

/// Step 3: the surface under the horizontal point P: the label of the supporting point nearest
/// to P's vertical, and that horizontal distance in `dist`; −1 when no point is labelled.
int surfaceUnder(const Points& w, const Eigen::Vector3d& P, double& dist) noexcept;

/// surfaceUnder for the rotor-plane centre and the four rotor centres at once (one pass over
/// the points; for each the same owner and distance as surfaceUnder gives).
inline constexpr int kUnderPoints = 5;
void surfacesUnder(const Points& w, const std::array<Eigen::Vector3d, kUnderPoints>& P,
                   std::array<int, kUnderPoints>& owner, std::array<double, kUnderPoints>& dist) noexcept;

}  // namespace geaware::estimation::lattice
