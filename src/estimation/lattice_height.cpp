#include "geaware/estimation/lattice_height.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include "geaware/model/field_check.hpp"
#include "geaware/model/mixer.hpp"
#include "geaware/model/vehicle_model.hpp"

namespace geaware::estimation {
namespace {

using Vec3 = Eigen::Vector3d;
constexpr int kN = model::RangerFrame::kMaxZones;
constexpr int kUnassigned = -1;
constexpr int kDiscarded = -2;  // inlier of a surface, but not in a large enough zone patch

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

/// Scratch of one frame, on the stack (≈ 10 kB).
struct Work {
  std::array<Vec3, kN> X;             // points, vehicle-centred world-oriented frame [m]
  std::array<int, kN> zone;           // zone index of each point
  std::array<int, kN> label;          // surface index, kUnassigned or kDiscarded
  std::array<int, kN> point_of_zone;  // inverse of `zone`, −1 for unusable zones
  std::array<int, kN> pool;           // candidate point indices of the current RANSAC
  std::array<int, kN> queue;          // BFS queue / component members
  std::array<bool, kN> inlier;        // per point, for the current surface
  std::array<bool, kN> seen;          // per point, BFS visited
  int n = 0;
};

struct PlaneFit {
  Vec3 n = Vec3::UnitZ();
  double c = 0.0;
  double rms = 0.0;
  bool ok = false;
};

/// Plane through the flagged points by regularised least squares on the ground's graph
/// z = a + b·x + c·y: minimise Σ(z_i − a − b·x_i − c·y_i)²/σ_r² + (b² + c²)/σ_s², the MAP
/// estimate with range noise σ_r and a level-ground prior of slope σ_s. Close to the ground
/// the lattice's footprint is a few centimetres wide and the tilt is not observable from it;
/// the prior then keeps the plane level instead of letting noise tilt it (and the tilt,
/// extrapolated to the rotor-plane centre, bias the height). Over a wide footprint the data
/// dominate. Not ok when fewer than 3 points or when the points are collinear seen from above
/// (the smaller horizontal spread below 1 % of the larger), which no prior should paper over.
PlaneFit fitPlane(const Work& w, const std::array<bool, kN>& use, double lambda) {
  PlaneFit f;
  int m = 0;
  Vec3 mean = Vec3::Zero();
  for (int i = 0; i < w.n; ++i) {
    if (use[static_cast<std::size_t>(i)]) {
      mean += w.X[static_cast<std::size_t>(i)];
      ++m;
    }
  }
  if (m < 3) return f;
  mean /= m;
  double sxx = 0.0, sxy = 0.0, syy = 0.0, sxz = 0.0, syz = 0.0;
  for (int i = 0; i < w.n; ++i) {
    if (use[static_cast<std::size_t>(i)]) {
      const Vec3 d = w.X[static_cast<std::size_t>(i)] - mean;
      sxx += d.x() * d.x();
      sxy += d.x() * d.y();
      syy += d.y() * d.y();
      sxz += d.x() * d.z();
      syz += d.y() * d.z();
    }
  }
  // Horizontal spread: eigenvalues of [[sxx, sxy], [sxy, syy]].
  const double half_tr = 0.5 * (sxx + syy);
  const double disc = std::sqrt(std::max(0.0, half_tr * half_tr - (sxx * syy - sxy * sxy)));
  const double l_max = half_tr + disc, l_min = half_tr - disc;
  if (!(l_max > 0.0) || !(l_min > 1e-4 * l_max)) return f;
  // Slopes from the 2×2 normal equations with the ridge λ = σ_r²/σ_s² on both.
  const double a11 = sxx + lambda, a22 = syy + lambda, det = a11 * a22 - sxy * sxy;
  const double b = (a22 * sxz - sxy * syz) / det;
  const double c = (a11 * syz - sxy * sxz) / det;
  const double z0 = mean.z() - b * mean.x() - c * mean.y();  // plane height at x = y = 0
  const Vec3 g(-b, -c, 1.0);
  const double gn = g.norm();
  f.n = g / gn;
  f.c = z0 / gn;
  double ss = 0.0;
  for (int i = 0; i < w.n; ++i) {
    if (use[static_cast<std::size_t>(i)]) {
      const double r = f.n.dot(w.X[static_cast<std::size_t>(i)]) - f.c;
      ss += r * r;
    }
  }
  f.rms = std::sqrt(ss / m);
  f.ok = f.n.allFinite() && std::isfinite(f.c);
  return f;
}

}  // namespace

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
  if (!rotor_plane_centre_B.allFinite()) {
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
  LatticeHeight out;
  const LatticeHeightParams& p = params_;

  // 0. Guards on the frame as a whole.
  const double qn = q_WB.norm();
  if (!(q_WB.coeffs().allFinite() && std::abs(qn - 1.0) < 1e-3 && frame.mount_B.allFinite() &&
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
  const int side = frame.side;

  // 1. Points. The zone rays are separable, d ∝ (tan α_i, tan β_j, −1) (RangerFrame), so the
  //    tangents are taken once per row and column from zoneDirection_B itself.
  std::array<double, model::RangerFrame::kMaxSide> tx{}, ty{};
  for (int k = 0; k < side; ++k) {
    const Vec3 di = frame.zoneDirection_B(k, 0);
    const Vec3 dj = frame.zoneDirection_B(0, k);
    tx[static_cast<std::size_t>(k)] = -di.x() / di.z();
    ty[static_cast<std::size_t>(k)] = -dj.y() / dj.z();
  }
  Work w;
  w.point_of_zone.fill(-1);
  const Vec3 origin_B = frame.mount_B - p.rotor_plane_centre_B;
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      const int z = frame.index(i, j);
      if (!frame.valid[static_cast<std::size_t>(z)]) continue;
      const double r = frame.range_m[static_cast<std::size_t>(z)];
      if (!(std::isfinite(r) && r >= p.min_range_m && r <= p.max_range_m)) {
        ++out.discarded_zones;
        continue;
      }
      const Vec3 d =
          Vec3(tx[static_cast<std::size_t>(i)], ty[static_cast<std::size_t>(j)], -1.0).normalized();
      const auto k = static_cast<std::size_t>(w.n);
      w.X[k] = R * (origin_B + r * d);
      w.zone[k] = z;
      w.label[k] = kUnassigned;
      w.point_of_zone[static_cast<std::size_t>(z)] = w.n;
      ++w.n;
    }
  }
  out.usable_zones = w.n;
  if (w.n < p.min_inliers) {
    out.status = LatticeStatus::kTooFewZones;
    return out;
  }

  // 2. Sequential RANSAC with least-squares refinement and the zone-patch support rule.
  const double cos_tilt = std::cos(p.max_ground_tilt_rad);
  const double thr = p.inlier_threshold_m;
  const double lambda =
      (p.range_noise_std_m * p.range_noise_std_m) / (p.ground_slope_prior * p.ground_slope_prior);
  SplitMix64 rng{p.seed};
  bool degenerate = false;
  const auto markInliers = [&](const Vec3& n, double c) {
    int count = 0;
    for (int i = 0; i < w.n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      w.inlier[k] = w.label[k] == kUnassigned && std::abs(n.dot(w.X[k]) - c) <= thr;
      count += w.inlier[k] ? 1 : 0;
    }
    return count;
  };
  for (int s = 0; s < p.max_surfaces; ++s) {
    int m = 0;
    for (int i = 0; i < w.n; ++i) {
      if (w.label[static_cast<std::size_t>(i)] == kUnassigned)
        w.pool[static_cast<std::size_t>(m++)] = i;
    }
    if (m < p.min_inliers) break;

    // 2a. Hypotheses from random triples, scored by MSAC (Torr & Zisserman 2000): the sum of
    //     squared residuals truncated at half the inlier threshold, lower is better. Plain
    //     inlier counting prefers a tilted plane that cuts through both levels of a step (two
    //     wide strips of "inliers"); the truncated cost with the narrower band prefers the
    //     plane the points actually lie on. `best` counts the hypothesis' points in that band.
    int best = 0;
    double best_cost = std::numeric_limits<double>::infinity();
    const double thr2 = 0.25 * thr * thr;
    int proper = 0;  // hypotheses from non-collinear triples
    Vec3 best_n = Vec3::UnitZ();
    double best_c = 0.0;
    for (int it = 0; it < p.ransac_iterations; ++it) {
      const int a = w.pool[static_cast<std::size_t>(rng.below(m))];
      const int b = w.pool[static_cast<std::size_t>(rng.below(m))];
      const int c = w.pool[static_cast<std::size_t>(rng.below(m))];
      if (a == b || b == c || a == c) continue;
      const Vec3& A = w.X[static_cast<std::size_t>(a)];
      const Vec3 u = w.X[static_cast<std::size_t>(b)] - A;
      const Vec3 v = w.X[static_cast<std::size_t>(c)] - A;
      Vec3 n = u.cross(v);
      const double nn = n.norm();
      if (!(nn > 1e-3 * u.norm() * v.norm())) continue;  // nearly collinear triple
      n /= nn;
      ++proper;
      if (n.z() < 0.0) n = -n;
      if (n.z() < cos_tilt) continue;  // too steep to be ground
      const double off = n.dot(A);
      int count = 0;
      double cost = 0.0;
      for (int q = 0; q < m; ++q) {
        const double r =
            n.dot(w.X[static_cast<std::size_t>(w.pool[static_cast<std::size_t>(q)])]) - off;
        const double r2 = r * r;
        count += r2 <= thr2 ? 1 : 0;
        cost += std::min(r2, thr2);
      }
      if (cost < best_cost) {
        best_cost = cost;
        best = count;
        best_n = n;
        best_c = off;
      }
    }
    if (best < p.min_inliers) {
      degenerate = degenerate || (proper == 0 && out.surfaces == 0);
      break;
    }

    // 2b. Least squares on the inliers, twice (the refit can gain or lose border points).
    PlaneFit fit;
    Vec3 n = best_n;
    double c = best_c;
    for (int pass = 0; pass < 2; ++pass) {
      markInliers(n, c);
      fit = fitPlane(w, w.inlier, lambda);
      if (!fit.ok) break;
      n = fit.n;
      c = fit.c;
    }
    if (!fit.ok || n.z() < cos_tilt) {
      degenerate = degenerate || !fit.ok;
      break;
    }
    markInliers(n, c);

    // 2c. Support: inliers in 8-connected zone patches of at least min_component_zones.
    int support = 0;
    for (int i = 0; i < w.n; ++i) w.seen[static_cast<std::size_t>(i)] = false;
    for (int i = 0; i < w.n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (!w.inlier[k] || w.seen[k]) continue;
      int head = 0, tail = 0;
      w.queue[static_cast<std::size_t>(tail++)] = i;
      w.seen[k] = true;
      while (head < tail) {
        const int cur = w.queue[static_cast<std::size_t>(head++)];
        const int zi = w.zone[static_cast<std::size_t>(cur)] / side;
        const int zj = w.zone[static_cast<std::size_t>(cur)] % side;
        for (int di = -1; di <= 1; ++di) {
          for (int dj = -1; dj <= 1; ++dj) {
            const int ni = zi + di, nj = zj + dj;
            if ((di == 0 && dj == 0) || ni < 0 || nj < 0 || ni >= side || nj >= side) continue;
            const int nb =
                w.point_of_zone[static_cast<std::size_t>(ni) * static_cast<std::size_t>(side) +
                                static_cast<std::size_t>(nj)];
            if (nb < 0 || !w.inlier[static_cast<std::size_t>(nb)] ||
                w.seen[static_cast<std::size_t>(nb)])
              continue;
            w.seen[static_cast<std::size_t>(nb)] = true;
            w.queue[static_cast<std::size_t>(tail++)] = nb;
          }
        }
      }
      const bool keep = tail >= p.min_component_zones;
      for (int q = 0; q < tail; ++q) {
        w.label[static_cast<std::size_t>(w.queue[static_cast<std::size_t>(q)])] =
            keep ? s : kDiscarded;
      }
      support += keep ? tail : 0;
    }
    if (support < p.min_inliers) {
      // Not a surface: its scattered "inliers" stay discarded so no later hypothesis reuses them.
      for (int i = 0; i < w.n; ++i) {
        if (w.label[static_cast<std::size_t>(i)] == s)
          w.label[static_cast<std::size_t>(i)] = kDiscarded;
      }
      continue;
    }

    // 2d. Final least squares on the support only.
    for (int i = 0; i < w.n; ++i)
      w.inlier[static_cast<std::size_t>(i)] = w.label[static_cast<std::size_t>(i)] == s;
    const PlaneFit final_fit = fitPlane(w, w.inlier, lambda);
    if (!final_fit.ok) {
      degenerate = true;
      for (int i = 0; i < w.n; ++i) {
        if (w.label[static_cast<std::size_t>(i)] == s)
          w.label[static_cast<std::size_t>(i)] = kDiscarded;
      }
      continue;
    }
    GroundPlane& g = out.planes[static_cast<std::size_t>(out.surfaces)];
    g.normal_W = final_fit.n;
    g.offset_m = final_fit.c;
    g.support = support;
    g.rms_residual_m = final_fit.rms;
    // Labels are surface slots from here on (slot == out.surfaces).
    if (s != out.surfaces) {
      for (int i = 0; i < w.n; ++i) {
        if (w.label[static_cast<std::size_t>(i)] == s)
          w.label[static_cast<std::size_t>(i)] = out.surfaces;
      }
    }
    ++out.surfaces;
  }
  if (out.surfaces == 0) {
    out.status = degenerate ? LatticeStatus::kDegenerate : LatticeStatus::kNoSurface;
    return out;
  }

  // 3. The surface under a point (x, y): the owner of the supporting zone nearest its vertical.
  const auto surfaceUnder = [&](const Vec3& P, double& dist) {
    int owner = -1;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (int i = 0; i < w.n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (w.label[k] < 0) continue;
      const double d2 = (w.X[k].head<2>() - P.head<2>()).squaredNorm();
      if (d2 < best_d2) {
        best_d2 = d2;
        owner = w.label[k];
      }
    }
    dist = std::sqrt(best_d2);
    return owner;
  };
  double dist = 0.0;
  const int g = surfaceUnder(Vec3::Zero(), dist);
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
  if (p.diagonal_rotor_distance_m > 0.0) {
    for (std::size_t r = 0; r < 4; ++r) {
      const Vec3 P = R * rotors_B_[r];
      const int o = surfaceUnder(P, out.rotor_support_distance_m[r]);
      const GroundPlane& pl = out.planes[static_cast<std::size_t>(o)];
      out.rotor_height_m[r] = (pl.normal_W.dot(P) - pl.offset_m) / pl.normal_W.z();
    }
  }
  out.status = LatticeStatus::kOk;
  out.valid = true;
  return out;
}

}  // namespace geaware::estimation
