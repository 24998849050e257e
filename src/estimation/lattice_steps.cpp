// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/estimation/lattice_steps.hpp"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>

namespace geaware::estimation::lattice {

using Vec3 = Eigen::Vector3d;

namespace {

/// The unit rays of a frame's zones (body frame), a function of its side and field of view only.
struct RayTable {
  int side = 0;
  double fov_rad = 0.0;
  alignas(32) std::array<double, model::RangerFrame::kMaxZones> dx{}, dy{}, dz{};
};

/// The unit rays of `frame`'s zones. A ranger's geometry does not change from frame to frame, so
/// they are computed once per thread and geometry, not once per frame (≈ 10 % of a fit).
const RayTable& unitRays(const model::RangerFrame& frame) noexcept {
  thread_local RayTable t;
  const int side = frame.side;
  if (t.side == side && t.fov_rad == frame.fov_rad) return t;
  // The zone rays are separable, d ∝ (tan α_i, tan β_j, −1) (RangerFrame), so the tangents
  // are taken once per row and column from zoneDirection_B itself.
  std::array<double, model::RangerFrame::kMaxSide> tx{}, ty{};
  for (int k = 0; k < side; ++k) {
    const Vec3 di = frame.zoneDirection_B(k, 0);
    const Vec3 dj = frame.zoneDirection_B(0, k);
    tx[static_cast<std::size_t>(k)] = -di.x() / di.z();
    ty[static_cast<std::size_t>(k)] = -dj.y() / dj.z();
  }
  // In a loop without branches (it vectorises; the same arithmetic as Eigen's normalized():
  // x/√((x² + y²) + z²) per component).
  for (int i = 0; i < side; ++i) {
    const double a = tx[static_cast<std::size_t>(i)];
    for (int j = 0; j < side; ++j) {
      const double b = ty[static_cast<std::size_t>(j)];
      const double len = std::sqrt((a * a + b * b) + 1.0);
      const auto k = static_cast<std::size_t>(i * side + j);
      t.dx[k] = a / len;
      t.dy[k] = b / len;
      t.dz[k] = -1.0 / len;
    }
  }
  t.side = side;
  t.fov_rad = frame.fov_rad;
  return t;
}

}  // namespace

void collectPoints(const model::RangerFrame& frame, const Eigen::Matrix3d& R,
                   const Eigen::Vector3d& rotor_plane_centre_B, double min_range_m,
                   double max_range_m, Points& w, int& discarded_zones) noexcept {
  const int side = frame.side;
  const RayTable& rays = unitRays(frame);
  const auto& dx = rays.dx;
  const auto& dy = rays.dy;
  const auto& dz = rays.dz;
  const int zones = side * side;
  // Every zone's point is computed and written to the next free slot; the slot is kept only
  // when the zone is usable. No branch on the zone's validity, which is as unpredictable as
  // the ranger's dropouts (an unusable zone's value, even non-finite, is overwritten or lies
  // beyond w.n, where nothing reads).
  w.point_of_zone.fill(-1);  // zones beyond side² too
  int n = 0;
  int discarded = 0;
  const Vec3 origin_B = frame.mount_B - rotor_plane_centre_B;
  for (int k = 0; k < zones; ++k) {
    const auto zk = static_cast<std::size_t>(k);
    const bool valid = frame.valid[zk];
    const double r = frame.range_m[zk];
    const bool usable = valid && std::isfinite(r) && r >= min_range_m && r <= max_range_m;
    discarded += valid && !usable ? 1 : 0;
    const auto slot = static_cast<std::size_t>(n);
    w.X[slot] = R * (origin_B + r * Vec3(dx[zk], dy[zk], dz[zk]));
    w.zone[slot] = k;
    w.label[slot] = kUnassigned;
    w.point_of_zone[zk] = usable ? n : -1;
    n += usable ? 1 : 0;
  }
  w.n = n;
  discarded_zones += discarded;
}

PlaneFit fitPlane(const Points& w, const int* idx, int m, double lambda) noexcept {
  PlaneFit f;
  if (m < 3) return f;
  Vec3 mean = Vec3::Zero();
  for (int q = 0; q < m; ++q) mean += w.X[static_cast<std::size_t>(idx[q])];
  mean /= m;
  double sxx = 0.0, sxy = 0.0, syy = 0.0, sxz = 0.0, syz = 0.0;
  for (int q = 0; q < m; ++q) {
    const Vec3 d = w.X[static_cast<std::size_t>(idx[q])] - mean;
    sxx += d.x() * d.x();
    sxy += d.x() * d.y();
    syy += d.y() * d.y();
    sxz += d.x() * d.z();
    syz += d.y() * d.z();
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
  for (int q = 0; q < m; ++q) {
    const double r = f.n.dot(w.X[static_cast<std::size_t>(idx[q])]) - f.c;
    ss += r * r;
  }
  f.rms = std::sqrt(ss / m);
  f.ok = f.n.allFinite() && std::isfinite(f.c);
  return f;
}

PlaneFit fitPlane(const Points& w, const std::array<bool, kN>& use, double lambda) noexcept {
  std::array<int, kN> idx;
  int m = 0;
  for (int i = 0; i < w.n; ++i) {
    idx[static_cast<std::size_t>(m)] = i;
    m += use[static_cast<std::size_t>(i)] ? 1 : 0;
  }
  return fitPlane(w, idx.data(), m, lambda);
}

int markInliers(Points& w, const Eigen::Vector3d& n, double c, double threshold_m) noexcept {
  int count = 0;
  for (int i = 0; i < w.n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const bool in = w.label[k] == kUnassigned && std::abs(n.dot(w.X[k]) - c) <= threshold_m;
    w.inlier[k] = in;
    w.sel[static_cast<std::size_t>(count)] = i;
    count += in ? 1 : 0;
  }
  w.n_sel = count;
  return count;
}

// Two builds of this function, chosen once at load time by the processor (GNU ifunc): the
// scoring's four partial sums are one AVX2 register where the processor has it, two SSE2
// registers otherwise. The same IEEE operations in the same order either way (AVX2 without FMA:
// nothing is contracted), so the same hypothesis wins, bit for bit.
#if defined(__GNUC__) && defined(__x86_64__) && defined(__gnu_linux__) && \
    !defined(__SANITIZE_ADDRESS__) && !defined(GEAWARE_NO_TARGET_CLONES)
[[gnu::target_clones("avx2", "default")]]
#endif
Hypothesis bestHypothesis(const Points& w, int m, SplitMix64& rng, int iterations,
                          double cos_tilt, double threshold_m) noexcept {
  Hypothesis h;
  double best_cost = std::numeric_limits<double>::infinity();
  const double thr2 = 0.25 * threshold_m * threshold_m;
  // The pool as contiguous coordinates (structure of arrays), so that scoring a hypothesis
  // streams through memory instead of gathering through w.pool.
  constexpr int kLanes = 4;      // independent partial sums: the adds do not wait on each other
  constexpr int kBlock = 32;     // points scored between two early-exit checks
  alignas(32) std::array<double, kN + kLanes> px, py, pz;  // [0, m) is filled and read
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
  // joins its inlier neighbours already scanned, west, north-west, north and north-east, in a
  // union-find forest whose parents always point to earlier points), then the component sizes.
  // Same patches as a flood fill, without a queue or a second visit.
  auto& parent = w.parent;
  auto& size = w.component_size;
  for (int i = 0; i < w.n; ++i) {
    parent[static_cast<std::size_t>(i)] = i;
    size[static_cast<std::size_t>(i)] = 0;
  }
  // The inlier point of each zone, or −1, on a grid with a border of −1 above, left and right,
  // so that the four scanned neighbours are plain loads.
  constexpr int kMaxW = model::RangerFrame::kMaxSide + 2;
  std::array<int, (model::RangerFrame::kMaxSide + 1) * kMaxW> cell;
  const int W = side + 2;
  std::fill_n(cell.begin(), static_cast<std::size_t>(W), -1);
  for (int zi = 0; zi < side; ++zi) {
    int* row = cell.data() + static_cast<std::ptrdiff_t>(zi + 1) * W;
    row[0] = -1;
    row[side + 1] = -1;
    for (int zj = 0; zj < side; ++zj) {
      const int p = w.point_of_zone[static_cast<std::size_t>(zi * side + zj)];
      const int safe = p < 0 ? 0 : p;
      row[zj + 1] = p >= 0 && w.inlier[static_cast<std::size_t>(safe)] ? p : -1;
    }
  }
  // The scan decides from the neighbours' geometry which unions can be new (Wu, Otoo & Suzuki
  // 2009): a north inlier is adjacent to all three others, so joining it is enough; else a
  // north-east one may bridge two patches (with the west or north-west, adjacent to each
  // other); else the north-west or the west alone.
  const auto unite = [&parent](int a, int b) {
    const int ra = findRoot(parent, a), rb = findRoot(parent, b);
    const int lo = std::min(ra, rb);
    parent[static_cast<std::size_t>(std::max(ra, rb))] = lo;
    return lo;
  };
  for (int zi = 0; zi < side; ++zi) {
    const int* row = cell.data() + static_cast<std::ptrdiff_t>(zi + 1) * W;
    const int* above = row - W;
    for (int zj = 1; zj <= side; ++zj) {
      const int i = row[zj];
      if (i < 0) continue;
      const int n = above[zj], ne = above[zj + 1], nw = above[zj - 1], west = row[zj - 1];
      int root = i;
      if (n >= 0) {
        root = parent[static_cast<std::size_t>(n)];
      } else if (ne >= 0) {
        const int other = nw >= 0 ? nw : west;
        root = other >= 0 ? unite(ne, other) : parent[static_cast<std::size_t>(ne)];
      } else if (nw >= 0) {
        root = parent[static_cast<std::size_t>(nw)];
      } else if (west >= 0) {
        root = parent[static_cast<std::size_t>(west)];
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
    w.sel[static_cast<std::size_t>(support)] = i;
    support += keep ? 1 : 0;
  }
  w.n_sel = support;
  return support;
}

void relabel(Points& w, int from, int to) noexcept {
  for (int i = 0; i < w.n; ++i) {
    auto& l = w.label[static_cast<std::size_t>(i)];
    l = l == from ? to : l;
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
    w.pool[static_cast<std::size_t>(m)] = i;
    m += w.label[static_cast<std::size_t>(i)] == kUnassigned ? 1 : 0;
  }
  if (m < p.min_inliers) return out;  // kStop

  // 2a. The best hypothesis.
  const Hypothesis h = bestHypothesis(w, m, rng, p.ransac_iterations, cos_tilt, thr);
  if (h.count < p.min_inliers) {
    out.degenerate = h.proper == 0 && slot == 0;
    return out;  // kStop
  }

  // 2b. Least squares on the inliers, twice (the refit can gain or lose border points). A fit
  // is a function of its point list alone: where a list equals the one fitted last, that fit is
  // reused instead of recomputed (the usual case on clean ground: all three lists agree).
  PlaneFit fit;
  std::array<int, kN> fitted;  // the list `fit` was computed on: fitted[0..n_fitted)
  int n_fitted = -1;
  const auto sameAsFitted = [&w, &fitted, &n_fitted] {
    return w.n_sel == n_fitted &&
           std::equal(w.sel.begin(), w.sel.begin() + w.n_sel, fitted.begin());
  };
  const auto fitSelection = [&] {
    if (sameAsFitted()) return;
    fit = fitPlane(w, w.sel.data(), w.n_sel, lambda);
    std::copy(w.sel.begin(), w.sel.begin() + w.n_sel, fitted.begin());
    n_fitted = w.n_sel;
  };
  Vec3 n = h.n;
  double c = h.c;
  for (int pass = 0; pass < 2; ++pass) {
    markInliers(w, n, c, thr);
    fitSelection();
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

  // 2d. Final least squares on the support only (listed in w.sel by keepZonePatches).
  fitSelection();
  const PlaneFit final_fit = fit;
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
    const double d2 = w.label[k] < 0 ? std::numeric_limits<double>::infinity()
                                     : (w.X[k].head<2>() - P.head<2>()).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      owner = w.label[k];
    }
  }
  dist = std::sqrt(best_d2);
  return owner;
}

void surfacesUnder(const Points& w, const std::array<Eigen::Vector3d, kUnderPoints>& P,
                   std::array<int, kUnderPoints>& owner, std::array<double, kUnderPoints>& dist) noexcept {
  // The same comparisons as surfaceUnder for each target, in one pass over the points (the
  // distances computed exactly as (X.head<2>() − P.head<2>()).squaredNorm() is).
  constexpr double kInf = std::numeric_limits<double>::infinity();
  constexpr std::size_t kT = kUnderPoints;
  std::array<double, kT> px{}, py{}, best{};
  std::array<std::int64_t, kT> who{};
  for (std::size_t t = 0; t < kT; ++t) {
    px[t] = P[t].x();
    py[t] = P[t].y();
    best[t] = kInf;
    who[t] = -1;
  }
  for (int i = 0; i < w.n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const std::int64_t label = w.label[k];
    const double xi = w.X[k].x(), yi = w.X[k].y();
    for (std::size_t t = 0; t < kT; ++t) {
      const double ex = xi - px[t], ey = yi - py[t];
      const double d2 = label < 0 ? kInf : ex * ex + ey * ey;
      const bool better = d2 < best[t];
      best[t] = better ? d2 : best[t];
      who[t] = better ? label : who[t];
    }
  }
  for (std::size_t t = 0; t < kT; ++t) {
    owner[t] = static_cast<int>(who[t]);
    dist[t] = std::sqrt(best[t]);
  }
}

}  // namespace geaware::estimation::lattice
