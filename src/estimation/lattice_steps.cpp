// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/estimation/lattice_steps.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace geaware::estimation::lattice {

using Vec3 = Eigen::Vector3d;

void collectPoints(const model::RangerFrame& frame, const Eigen::Matrix3d& R,
                   const Eigen::Vector3d& rotor_plane_centre_B, double min_range_m,
                   double max_range_m, Points& w, int& discarded_zones) noexcept {
  const int side = frame.side;
  // The zone rays are separable, d ∝ (tan α_i, tan β_j, −1) (RangerFrame), so the tangents
  // are taken once per row and column from zoneDirection_B itself.
  std::array<double, model::RangerFrame::kMaxSide> tx{}, ty{};
  for (int k = 0; k < side; ++k) {
    const Vec3 di = frame.zoneDirection_B(k, 0);
    const Vec3 dj = frame.zoneDirection_B(0, k);
    tx[static_cast<std::size_t>(k)] = -di.x() / di.z();
    ty[static_cast<std::size_t>(k)] = -dj.y() / dj.z();
  }
  w.n = 0;
  w.point_of_zone.fill(-1);
  const Vec3 origin_B = frame.mount_B - rotor_plane_centre_B;
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      const int z = frame.index(i, j);
      if (!frame.valid[static_cast<std::size_t>(z)]) continue;
      const double r = frame.range_m[static_cast<std::size_t>(z)];
      if (!(std::isfinite(r) && r >= min_range_m && r <= max_range_m)) {
        ++discarded_zones;
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
}

PlaneFit fitPlane(const Points& w, const std::array<bool, kN>& use, double lambda) noexcept {
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

int markInliers(Points& w, const Eigen::Vector3d& n, double c, double threshold_m) noexcept {
  int count = 0;
  for (int i = 0; i < w.n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    w.inlier[k] = w.label[k] == kUnassigned && std::abs(n.dot(w.X[k]) - c) <= threshold_m;
    count += w.inlier[k] ? 1 : 0;
  }
  return count;
}

Hypothesis bestHypothesis(const Points& w, int m, SplitMix64& rng, int iterations,
                          double cos_tilt, double threshold_m) noexcept {
  Hypothesis h;
  double best_cost = std::numeric_limits<double>::infinity();
  const double thr2 = 0.25 * threshold_m * threshold_m;
  // The pool as contiguous coordinates (structure of arrays), so that scoring a hypothesis
  // streams through memory instead of gathering through w.pool.
  constexpr int kLanes = 4;      // independent partial sums: the adds do not wait on each other
  constexpr int kBlock = 32;     // points scored between two early-exit checks
  alignas(32) std::array<double, kN + kLanes> px{}, py{}, pz{};
  for (int q = 0; q < m; ++q) {
    const Vec3& X = w.X[static_cast<std::size_t>(w.pool[static_cast<std::size_t>(q)])];
    px[static_cast<std::size_t>(q)] = X.x();
    py[static_cast<std::size_t>(q)] = X.y();
    pz[static_cast<std::size_t>(q)] = X.z();
  }
  for (int it = 0; it < iterations; ++it) {
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
    ++h.proper;
    if (n.z() < 0.0) n = -n;
    if (n.z() < cos_tilt) continue;  // too steep to be ground
    const double off = n.dot(A);
    const double nx = n.x(), ny = n.y(), nz = n.z();
    // MSAC cost: Σ min(r², thr²) in kLanes partial sums. The terms are non-negative, so a
    // partial sum that already reaches the best cost cannot win: the hypothesis is dropped
    // there (the same choice as the full sum, at a fraction of the work for most hypotheses).
    std::array<double, kLanes> part{};
    double cost = 0.0;
    bool dropped = false;
    int q = 0;
    while (q < m) {
      const int end = std::min(m, q + kBlock);
      for (; q + kLanes <= end; q += kLanes) {
        for (int l = 0; l < kLanes; ++l) {
          const auto k = static_cast<std::size_t>(q + l);
          const double r = nx * px[k] + ny * py[k] + nz * pz[k] - off;
          part[static_cast<std::size_t>(l)] += std::min(r * r, thr2);
        }
      }
      for (; q < end; ++q) {
        const auto k = static_cast<std::size_t>(q);
        const double r = nx * px[k] + ny * py[k] + nz * pz[k] - off;
        part[0] += std::min(r * r, thr2);
      }
      cost = (part[0] + part[1]) + (part[2] + part[3]);
      if (cost >= best_cost) {
        dropped = true;
        break;
      }
    }
    if (dropped) continue;
    best_cost = cost;
    h.n = n;
    h.c = off;
  }
  // The inliers of the winner, counted once.
  if (std::isfinite(best_cost)) {
    for (int q = 0; q < m; ++q) {
      const auto k = static_cast<std::size_t>(q);
      const double r = h.n.x() * px[k] + h.n.y() * py[k] + h.n.z() * pz[k] - h.c;
      h.count += r * r <= thr2 ? 1 : 0;
    }
  }
  return h;
}

namespace {

/// Root of point i in the union-find forest `parent`, halving the path on the way.
int findRoot(std::array<int, kN>& parent, int i) noexcept {
  while (parent[static_cast<std::size_t>(i)] != i) {
    auto& p = parent[static_cast<std::size_t>(i)];
    p = parent[static_cast<std::size_t>(p)];
    i = p;
  }
  return i;
}

}  // namespace

int keepZonePatches(Points& w, int side, int label, int min_component_zones) noexcept {
  // Connected components of the inlier zones in one raster scan (8-connectivity: each inlier
  // joins its inlier neighbours already scanned, west, north-west, north and north-east), then
  // the component sizes. Same patches as a flood fill, without a queue or a second visit.
  auto& parent = w.parent;
  auto& size = w.component_size;
  for (int i = 0; i < w.n; ++i) {
    parent[static_cast<std::size_t>(i)] = i;
    size[static_cast<std::size_t>(i)] = 0;
  }
  // The inlier point at zone (zi, zj), or −1.
  auto inlierAt = [&](int zi, int zj) {
    if (zi < 0 || zj < 0 || zj >= side) return -1;
    const int p = w.point_of_zone[static_cast<std::size_t>(zi) * static_cast<std::size_t>(side) +
                                  static_cast<std::size_t>(zj)];
    return p >= 0 && w.inlier[static_cast<std::size_t>(p)] ? p : -1;
  };
  for (int zi = 0; zi < side; ++zi) {
    for (int zj = 0; zj < side; ++zj) {
      const int i = inlierAt(zi, zj);
      if (i < 0) continue;
      // i joins the patch of its first inlier neighbour; patches it bridges are merged into
      // the one with the smaller root.
      int root = i;
      for (const int nb : {inlierAt(zi, zj - 1), inlierAt(zi - 1, zj - 1), inlierAt(zi - 1, zj),
                           inlierAt(zi - 1, zj + 1)}) {
        if (nb < 0) continue;
        const int r = findRoot(parent, nb);
        if (root == i) {
          root = r;
        } else if (r != root) {
          parent[static_cast<std::size_t>(std::max(r, root))] = std::min(r, root);
          root = std::min(r, root);
        }
      }
      parent[static_cast<std::size_t>(i)] = root;
    }
  }
  // Flatten: every inlier points at its root (the roots no longer change).
  for (int i = 0; i < w.n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!w.inlier[k]) continue;
    parent[k] = findRoot(parent, i);
    ++size[static_cast<std::size_t>(parent[k])];
  }
  int support = 0;
  for (int i = 0; i < w.n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!w.inlier[k]) continue;
    const bool keep = size[static_cast<std::size_t>(parent[k])] >= min_component_zones;
    w.label[k] = keep ? label : kDiscarded;
    support += keep ? 1 : 0;
  }
  return support;
}

void relabel(Points& w, int from, int to) noexcept {
  for (int i = 0; i < w.n; ++i) {
    if (w.label[static_cast<std::size_t>(i)] == from) w.label[static_cast<std::size_t>(i)] = to;
  }
}

SurfaceResult extractSurface(Points& w, int s, int slot, int side, const LatticeHeightParams& p,
                             SplitMix64& rng) noexcept {
  SurfaceResult out;
  const double cos_tilt = std::cos(p.max_ground_tilt_rad);
  const double thr = p.inlier_threshold_m;
  const double lambda =
      (p.range_noise_std_m * p.range_noise_std_m) / (p.ground_slope_prior * p.ground_slope_prior);
  int m = 0;
  for (int i = 0; i < w.n; ++i) {
    if (w.label[static_cast<std::size_t>(i)] == kUnassigned)
      w.pool[static_cast<std::size_t>(m++)] = i;
  }
  if (m < p.min_inliers) return out;  // kStop

  // 2a. The best hypothesis.
  const Hypothesis h = bestHypothesis(w, m, rng, p.ransac_iterations, cos_tilt, thr);
  if (h.count < p.min_inliers) {
    out.degenerate = h.proper == 0 && slot == 0;
    return out;  // kStop
  }

  // 2b. Least squares on the inliers, twice (the refit can gain or lose border points).
  PlaneFit fit;
  Vec3 n = h.n;
  double c = h.c;
  for (int pass = 0; pass < 2; ++pass) {
    markInliers(w, n, c, thr);
    fit = fitPlane(w, w.inlier, lambda);
    if (!fit.ok) break;
    n = fit.n;
    c = fit.c;
  }
  if (!fit.ok || n.z() < cos_tilt) {
    out.degenerate = !fit.ok;
    return out;  // kStop
  }
  markInliers(w, n, c, thr);

  // 2c. Support: inliers in 8-connected zone patches of at least min_component_zones.
  const int support = keepZonePatches(w, side, s, p.min_component_zones);
  out.outcome = SurfaceResult::kRejected;
  if (support < p.min_inliers) {
    // Not a surface: its scattered "inliers" stay discarded so no later hypothesis reuses them.
    relabel(w, s, kDiscarded);
    return out;
  }

  // 2d. Final least squares on the support only.
  for (int i = 0; i < w.n; ++i)
    w.inlier[static_cast<std::size_t>(i)] = w.label[static_cast<std::size_t>(i)] == s;
  const PlaneFit final_fit = fitPlane(w, w.inlier, lambda);
  if (!final_fit.ok) {
    out.degenerate = true;
    relabel(w, s, kDiscarded);
    return out;
  }
  out.plane.normal_W = final_fit.n;
  out.plane.offset_m = final_fit.c;
  out.plane.support = support;
  out.plane.rms_residual_m = final_fit.rms;
  // Labels are surface slots from here on.
  if (s != slot) relabel(w, s, slot);
  out.outcome = SurfaceResult::kFound;
  return out;
}

int surfaceUnder(const Points& w, const Eigen::Vector3d& P, double& dist) noexcept {
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
}

}  // namespace geaware::estimation::lattice
