// SPDX-License-Identifier: BSD-3-Clause
// The lattice estimator's steps alone: the regularised plane fit, inlier marking, the zone-patch
// support rule, the RANSAC hypothesis and the surface under a point.
#include "geaware/estimation/lattice_steps.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "geaware_test/eigen_matchers.hpp"

namespace {

using namespace geaware::estimation::lattice;
using Eigen::Vector3d;

/// A side×side grid of points on z = z0 + sx·x + sy·y, zone index i·side + j.
Points grid(int side, double z0, double sx, double sy, double spacing = 0.05) {
  Points w;
  w.point_of_zone.fill(-1);
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      const double x = spacing * (i - 0.5 * (side - 1)), y = spacing * (j - 0.5 * (side - 1));
      const auto k = static_cast<std::size_t>(w.n);
      w.X[k] = Vector3d(x, y, z0 + sx * x + sy * y);
      w.zone[k] = i * side + j;
      w.label[k] = kUnassigned;
      w.point_of_zone[static_cast<std::size_t>(i * side + j)] = w.n;
      ++w.n;
    }
  }
  return w;
}

TEST(LatticeSteps, FitPlaneRecoversATiltedPlaneWithoutPriorAndRejectsCollinearPoints) {
  const Points w = grid(8, -0.5, 0.1, -0.2);
  std::array<bool, kN> all{};
  for (int i = 0; i < w.n; ++i) all[static_cast<std::size_t>(i)] = true;
  const PlaneFit f = fitPlane(w, all, 0.0);
  ASSERT_TRUE(f.ok);
  const Vector3d n = Vector3d(-0.1, 0.2, 1.0).normalized();
  EXPECT_MATRIX_NEAR(f.n, n, 1e-12);
  EXPECT_NEAR(f.c, -0.5 * n.z(), 1e-12);
  EXPECT_NEAR(f.rms, 0.0, 1e-12);
  // A strong level prior pulls the slope towards zero.
  EXPECT_GT(fitPlane(w, all, 1e6).n.z(), f.n.z());
  // One row of zones only: collinear seen from above.
  std::array<bool, kN> row{};
  for (int j = 0; j < 8; ++j) row[static_cast<std::size_t>(j)] = true;
  EXPECT_FALSE(fitPlane(w, row, 0.0).ok);
}

TEST(LatticeSteps, ZonePatchesKeepContiguousSupportOnly) {
  Points w = grid(6, -0.4, 0.0, 0.0);
  // Inliers: a 3×3 patch in one corner and two isolated zones.
  for (int i = 0; i < w.n; ++i) w.inlier[static_cast<std::size_t>(i)] = false;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) w.inlier[static_cast<std::size_t>(i * 6 + j)] = true;
  w.inlier[5 * 6 + 5] = true;
  w.inlier[0 * 6 + 5] = true;
  EXPECT_EQ(keepZonePatches(w, 6, 0, 4), 9);
  EXPECT_EQ(w.label[0], 0);
  EXPECT_EQ(w.label[2 * 6 + 2], 0);
  EXPECT_EQ(w.label[5 * 6 + 5], kDiscarded);
  EXPECT_EQ(w.label[0 * 6 + 5], kDiscarded);
  EXPECT_EQ(w.label[3 * 6 + 3], kUnassigned);  // not an inlier: untouched
  relabel(w, 0, 2);
  EXPECT_EQ(w.label[1 * 6 + 1], 2);
}

TEST(LatticeSteps, MarkInliersAndTheHypothesisFindTheDominantPlane) {
  Points w = grid(8, -0.3, 0.0, 0.0);
  // Lift one corner 3×3 well off the floor (a box): not inliers of the floor.
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) w.X[static_cast<std::size_t>(i * 8 + j)].z() += 0.2;
  EXPECT_EQ(markInliers(w, Vector3d::UnitZ(), -0.3, 0.01), 64 - 9);
  for (int i = 0; i < w.n; ++i) w.pool[static_cast<std::size_t>(i)] = i;
  SplitMix64 rng{42};
  const Hypothesis h = bestHypothesis(w, w.n, rng, 40, std::cos(0.6), 0.03);
  EXPECT_EQ(h.count, 64 - 9);
  EXPECT_MATRIX_NEAR(h.n, Vector3d::UnitZ(), 1e-12);
  EXPECT_NEAR(h.c, -0.3, 1e-12);
  EXPECT_GT(h.proper, 0);
}

TEST(LatticeSteps, SurfaceUnderIsTheOwnerOfTheNearestSupportingZone) {
  Points w = grid(4, -0.3, 0.0, 0.0, 1.0);  // x, y in {−1.5, −0.5, 0.5, 1.5}
  for (int i = 0; i < w.n; ++i) w.label[static_cast<std::size_t>(i)] = w.X[static_cast<std::size_t>(i)].x() < 0 ? 0 : 1;
  w.label[0] = kDiscarded;  // discarded points own nothing
  double d = 0.0;
  EXPECT_EQ(surfaceUnder(w, Vector3d(-0.6, 0.4, 0.0), d), 0);
  EXPECT_NEAR(d, std::hypot(0.1, 0.1), 1e-12);
  EXPECT_EQ(surfaceUnder(w, Vector3d(1.4, -1.4, 0.0), d), 1);
  Points empty;
  EXPECT_EQ(surfaceUnder(empty, Vector3d::Zero(), d), -1);
}

/// Oracle: the 8-connected patches of the inlier zones by breadth-first flood fill, and the
/// label each inlier gets under the support rule.
std::vector<int> floodFillLabels(const Points& w, int side, int label, int min_zones) {
  std::vector<int> out(static_cast<std::size_t>(w.n), kUnassigned);
  std::vector<int> patch(static_cast<std::size_t>(side * side), -1);
  auto inlierAt = [&](int zi, int zj) {
    if (zi < 0 || zj < 0 || zi >= side || zj >= side) return -1;
    const int p = w.point_of_zone[static_cast<std::size_t>(zi * side + zj)];
    return p >= 0 && w.inlier[static_cast<std::size_t>(p)] ? p : -1;
  };
  for (int z = 0; z < side * side; ++z) {
    if (inlierAt(z / side, z % side) < 0 || patch[static_cast<std::size_t>(z)] >= 0) continue;
    std::vector<int> members{z};
    patch[static_cast<std::size_t>(z)] = z;
    for (std::size_t q = 0; q < members.size(); ++q) {
      const int zi = members[q] / side, zj = members[q] % side;
      for (int di = -1; di <= 1; ++di) {
        for (int dj = -1; dj <= 1; ++dj) {
          const int ni = zi + di, nj = zj + dj;
          if (inlierAt(ni, nj) < 0 || patch[static_cast<std::size_t>(ni * side + nj)] >= 0) continue;
          patch[static_cast<std::size_t>(ni * side + nj)] = z;
          members.push_back(ni * side + nj);
        }
      }
    }
    const bool keep = static_cast<int>(members.size()) >= min_zones;
    for (const int m : members) {
      out[static_cast<std::size_t>(w.point_of_zone[static_cast<std::size_t>(m)])] =
          keep ? label : kDiscarded;
    }
  }
  return out;
}

TEST(LatticeSteps, ZonePatchesAgreeWithAFloodFillOnRandomMasks) {
  // Random inlier masks of every density on grids of several sides, some zones unusable: the
  // raster scan's union-find (with its shortcuts for the north and north-east neighbours) must
  // label exactly the patches a flood fill finds, and list the support in increasing order.
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 2000; ++trial) {
    const int side = 1 + trial % 16;
    const double density = (trial % 10) / 9.0;
    std::bernoulli_distribution in(density), usable(0.9);
    Points w;
    w.point_of_zone.fill(-1);
    w.n = 0;
    for (int z = 0; z < side * side; ++z) {
      if (!usable(rng)) continue;
      const auto k = static_cast<std::size_t>(w.n);
      w.X[k] = Vector3d::Zero();
      w.zone[k] = z;
      w.label[k] = kUnassigned;
      w.inlier[k] = in(rng);
      w.point_of_zone[static_cast<std::size_t>(z)] = w.n++;
    }
    const int min_zones = 1 + trial % 7;
    const std::vector<int> expected = floodFillLabels(w, side, 3, min_zones);
    const int support = keepZonePatches(w, side, 3, min_zones);
    int kept = 0;
    for (int i = 0; i < w.n; ++i) {
      ASSERT_EQ(w.label[static_cast<std::size_t>(i)], expected[static_cast<std::size_t>(i)])
          << "trial " << trial << ", side " << side << ", point " << i;
      if (expected[static_cast<std::size_t>(i)] == 3) {
        ASSERT_EQ(w.sel[static_cast<std::size_t>(kept)], i);
        ++kept;
      }
    }
    ASSERT_EQ(support, kept);
    ASSERT_EQ(w.n_sel, kept);
  }
}

TEST(LatticeSteps, FitPlaneOnAListEqualsTheFlaggedFitBitForBit) {
  Points w = grid(12, -0.4, 0.05, -0.02);
  std::mt19937_64 rng(9);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (int i = 0; i < w.n; ++i) w.X[static_cast<std::size_t>(i)].z() += noise(rng);
  std::bernoulli_distribution pick(0.7);
  std::array<bool, kN> use{};
  std::array<int, kN> list{};
  int m = 0;
  for (int i = 0; i < w.n; ++i) {
    use[static_cast<std::size_t>(i)] = pick(rng);
    if (use[static_cast<std::size_t>(i)]) list[static_cast<std::size_t>(m++)] = i;
  }
  const PlaneFit a = fitPlane(w, use, 1e-3);
  const PlaneFit b = fitPlane(w, list.data(), m, 1e-3);
  ASSERT_TRUE(a.ok);
  EXPECT_EQ(a.n, b.n);
  EXPECT_EQ(a.c, b.c);
  EXPECT_EQ(a.rms, b.rms);
  // markInliers lists exactly the flagged points, in order.
  const int count = markInliers(w, a.n, a.c, 0.015);
  ASSERT_EQ(count, w.n_sel);
  int q = 0;
  for (int i = 0; i < w.n; ++i) {
    if (w.inlier[static_cast<std::size_t>(i)]) {
      EXPECT_EQ(w.sel[static_cast<std::size_t>(q++)], i);
    }
  }
  EXPECT_EQ(q, count);
}

}  // namespace

// The one-pass search for the centre and the rotors gives, for each target, exactly what
// surfaceUnder gives: over random labellings (unlabelled, discarded and three surfaces) and
// targets inside, at the edge of and outside the points.
TEST(LatticeSteps, SurfacesUnderEqualsSurfaceUnderForEachTarget) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> label(-2, 2);
  std::uniform_real_distribution<double> coord(-0.6, 0.6);
  for (int trial = 0; trial < 200; ++trial) {
    Points w = grid(16, -0.3, 0.0, 0.0, 0.04);
    for (int i = 0; i < w.n; ++i) w.label[static_cast<std::size_t>(i)] = label(rng);
    if (trial % 50 == 0) {  // none labelled: no owner, infinite distance
      for (int i = 0; i < w.n; ++i) w.label[static_cast<std::size_t>(i)] = kUnassigned;
    }
    std::array<Vector3d, kUnderPoints> P;
    for (auto& p : P) p = Vector3d(coord(rng), coord(rng), coord(rng));
    if (trial % 7 == 0) P[2] = w.X[17];  // on a point: distance 0
    std::array<int, kUnderPoints> owner{};
    std::array<double, kUnderPoints> dist{};
    surfacesUnder(w, P, owner, dist);
    for (std::size_t t = 0; t < kUnderPoints; ++t) {
      double d = 0.0;
      EXPECT_EQ(owner[t], surfaceUnder(w, P[t], d)) << "trial " << trial << " target " << t;
      EXPECT_EQ(dist[t], d) << "trial " << trial << " target " << t;
    }
  }
}

// The zones' unit rays are kept per thread and ranger geometry: frames of two geometries in
// turn each get their own rays (the points of the zones straight below and at a corner).
TEST(LatticeSteps, CollectPointsFollowsTheFramesGeometryFromFrameToFrame) {
  const Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  for (int round = 0; round < 3; ++round) {
    for (const auto& [side, fov_deg] : {std::pair{16, 45.0}, std::pair{8, 60.0}, std::pair{16, 30.0}}) {
      geaware::model::RangerFrame f;
      f.side = side;
      f.fov_rad = fov_deg * M_PI / 180.0;
      f.mount_B = Vector3d(0.01, -0.02, -0.03);
      for (int k = 0; k < side * side; ++k) {
        f.valid[static_cast<std::size_t>(k)] = true;
        f.range_m[static_cast<std::size_t>(k)] = 0.5 + 0.001 * k;
      }
      Points w;
      int discarded = 0;
      collectPoints(f, R, Vector3d::Zero(), 0.01, 4.0, w, discarded);
      ASSERT_EQ(w.n, side * side);
      for (const auto& [i, j] : {std::pair{0, 0}, std::pair{side / 2, side / 2 - 1}, std::pair{side - 1, 0}}) {
        const int k = f.index(i, j);
        const Vector3d expected = f.mount_B + f.range_m[static_cast<std::size_t>(k)] * f.zoneDirection_B(i, j);
        EXPECT_NEAR((w.X[static_cast<std::size_t>(k)] - expected).norm(), 0.0, 1e-12)
            << "side " << side << ", fov " << fov_deg << "°, zone (" << i << ", " << j << ")";
      }
    }
  }
}
