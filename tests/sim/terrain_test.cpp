// SPDX-License-Identifier: BSD-3-Clause
// Terrains: heights, normals and ray casts against closed forms; the generic march-and-bisect
// against the closed forms; height-map files and their errors.
#include "geaware/sim/terrains.hpp"

#include <cmath>
#include <cstdint>
#include <fstream>
#include <numbers>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "geaware_test/eigen_matchers.hpp"

namespace geaware::sim {
namespace {

// The generic ray cast bisects to 1e-9 m; the closed forms are exact to round-off.
constexpr double kMarchTol = 1e-7;

/// Seeded random rays from above the terrain, mostly pointing down (a lattice ranger's rays).
template <typename F>
void forRandomRays(std::uint64_t seed, int count, F&& f) {
  std::mt19937_64 rng(seed);
  const auto u = [&rng](double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
  };
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d o(u(-2.0, 2.0), u(-2.0, 2.0), u(0.6, 3.0));
    const Eigen::Vector3d d =
        Eigen::Vector3d(u(-1.0, 1.0), u(-1.0, 1.0), u(-1.0, 0.2)).normalized();
    f(o, d);
  }
}

/// Calls the base class's march-and-bisect on any terrain.
std::optional<double> marched(const Terrain& t, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                              double range) {
  return t.Terrain::rayCast(o, d, range);
}

TEST(FlatGround, HeightNormalAndRays) {
  const FlatGround g(0.25);
  EXPECT_DOUBLE_EQ(g.heightAt(3.0, -7.0), 0.25);
  EXPECT_MATRIX_NEAR(g.normalAt(1.0, 1.0), Eigen::Vector3d::UnitZ(), 0.0);
  EXPECT_NEAR(*g.rayCast({0, 0, 2.25}, {0, 0, -1}, 4.0), 2.0, 1e-15);
  // A ray 60° off the vertical travels h / cos 60° = 2h.
  const Eigen::Vector3d slanted(std::sin(std::numbers::pi / 3.0), 0.0,
                                -std::cos(std::numbers::pi / 3.0));
  EXPECT_NEAR(*g.rayCast({0, 0, 1.25}, slanted, 4.0), 2.0, 1e-12);
  EXPECT_FALSE(g.rayCast({0, 0, 2.25}, {0, 0, 1}, 4.0));            // upward
  EXPECT_FALSE(g.rayCast({0, 0, 5.25}, {0, 0, -1}, 4.0));           // out of range
  EXPECT_DOUBLE_EQ(*g.rayCast({0, 0, 0.0}, {0, 0, -1}, 4.0), 0.0);  // origin under the surface
  EXPECT_FALSE(g.rayCast({0, 0, 1.0}, {0, 0, 0}, 4.0));             // no direction
  forRandomRays(1, 200, [&](const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
    const auto exact = g.rayCast(o, d, 4.0);
    const auto march = marched(g, o, d, 4.0);
    ASSERT_EQ(exact.has_value(), march.has_value());
    if (exact) {
      ASSERT_NEAR(*exact, *march, kMarchTol);
    }
  });
}

TEST(TiltedPlane, HeightNormalAndRays) {
  // Pitched by δ about y through (1, 0, 0.5): H(x, y) = 0.5 − tan δ·(x − 1), n = (sin δ, 0, cos δ).
  const double delta = 15.0 * std::numbers::pi / 180.0;
  const TiltedPlane plane = TiltedPlane::fromTilt({1.0, 0.0, 0.5}, 0.0, delta);
  EXPECT_NEAR(plane.heightAt(2.0, 3.0), 0.5 - std::tan(delta), 1e-15);
  EXPECT_MATRIX_NEAR(plane.normalAt(0, 0), Eigen::Vector3d(std::sin(delta), 0.0, std::cos(delta)),
                     1e-15);
  // Straight down from (x, y, z): z − H(x, y).
  EXPECT_NEAR(*plane.rayCast({0.0, 0.0, 2.0}, {0, 0, -1}, 4.0), 2.0 - plane.heightAt(0.0, 0.0),
              1e-14);
  // Along the normal towards the plane: the perpendicular distance.
  const Eigen::Vector3d n = plane.normalAt(0, 0);
  EXPECT_NEAR(*plane.rayCast(Eigen::Vector3d(1.0, 0.0, 0.5) + 0.7 * n, -n, 4.0), 0.7, 1e-14);
  // A positive roll about x: n = R_x(φ)·z = (0, −sin φ, cos φ), so the +y side rises by tan φ.
  const TiltedPlane rolled = TiltedPlane::fromTilt({0, 0, 0}, delta, 0.0);
  EXPECT_NEAR(rolled.heightAt(0.0, 1.0), std::tan(delta), 1e-15);
  EXPECT_THROW(TiltedPlane({0, 0, 0}, {1, 0, 0}),
               std::invalid_argument);  // vertical: not a height field
  forRandomRays(2, 200, [&](const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
    const auto exact = plane.rayCast(o, d, 4.0);
    const auto march = marched(plane, o, d, 4.0);
    ASSERT_EQ(exact.has_value(), march.has_value());
    if (exact) {
      ASSERT_NEAR(*exact, *march, kMarchTol);
    }
  });
}

TEST(StepTerrain, TwoLevelsAndTheFace) {
  // A table edge along y at x = 0.5: the table (z = 0.8) for x ≥ 0.5, the floor (z = 0) beyond.
  const StepTerrain step({0.5, 0.0}, {1.0, 0.0}, 0.0, 0.8);
  EXPECT_DOUBLE_EQ(step.heightAt(0.49, 7.0), 0.0);
  EXPECT_DOUBLE_EQ(step.heightAt(0.5, -3.0), 0.8);
  EXPECT_DOUBLE_EQ(step.signedDistance(1.5, 2.0), 1.0);
  // Straight down on each side.
  EXPECT_NEAR(*step.rayCast({0.0, 0.0, 1.0}, {0, 0, -1}, 4.0), 1.0, 1e-15);
  EXPECT_NEAR(*step.rayCast({1.0, 0.0, 1.0}, {0, 0, -1}, 4.0), 0.2, 1e-15);
  // Horizontally into the face from the floor side, 0.3 m above the floor: the face is 0.5 m away.
  EXPECT_NEAR(*step.rayCast({0.0, 0.0, 0.3}, {1, 0, 0}, 4.0), 0.5, 1e-15);
  // Over the face (higher than the table): nothing in range horizontally.
  EXPECT_FALSE(step.rayCast({0.0, 0.0, 0.9}, {1, 0, 0}, 4.0));
  // From above the table, steeply down towards the edge: it lands on the table top at x = 0.8,
  // before the edge.
  const Eigen::Vector3d diag = Eigen::Vector3d(-1.0, 0.0, -1.0).normalized();
  EXPECT_NEAR(*step.rayCast({1.0, 0.0, 1.0}, diag, 4.0), 0.2 * std::sqrt(2.0), 1e-14);
  // Shallower: it crosses the edge at z = 0.85, above the table, and lands on the floor at
  // x = −1.2 after a drop of 0.9 m, i.e. √5·0.9 m along the ray.
  const Eigen::Vector3d shallow = Eigen::Vector3d(-2.0, 0.0, -1.0).normalized();
  EXPECT_NEAR(*step.rayCast({0.6, 0.0, 0.9}, shallow, 4.0), std::sqrt(5.0) * 0.9, 1e-13);
  EXPECT_THROW(StepTerrain({0, 0}, {0, 0}, 0.0, 1.0), std::invalid_argument);
  // The generic march finds the same hits (including the face) on random rays, for an edge at
  // an angle.
  const StepTerrain oblique({0.2, -0.1}, {1.0, 2.0}, -0.1, 0.4);
  forRandomRays(3, 300, [&](const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
    const auto exact = oblique.rayCast(o, d, 4.0);
    const auto march = marched(oblique, o, d, 4.0);
    ASSERT_EQ(exact.has_value(), march.has_value()) << o.transpose() << " / " << d.transpose();
    if (exact) {
      ASSERT_NEAR(*exact, *march, kMarchTol) << o.transpose() << " / " << d.transpose();
    }
  });
}

/// A height map sampling z = a + b·x + c·y + e·x·y on nodes `cell` apart from (x0, y0):
/// bilinear interpolation reproduces it exactly.
HeightMap bilinearMap(double a, double b, double c, double e, double x0 = -1.0, double y0 = -0.5,
                      double cell = 0.25, int nx = 11, int ny = 9) {
  std::vector<std::vector<double>> rows;
  for (int j = 0; j < ny; ++j) {
    std::vector<double> row;
    for (int i = 0; i < nx; ++i) {
      const double x = x0 + cell * i;
      const double y = y0 + cell * j;
      row.push_back(a + b * x + c * y + e * x * y);
    }
    rows.push_back(row);
  }
  return HeightMap(x0, y0, cell, rows);
}

TEST(HeightMap, BilinearHeightsAndNormals) {
  const HeightMap m = bilinearMap(0.1, 0.2, -0.3, 0.15);
  EXPECT_EQ(m.columns(), 11u);
  EXPECT_EQ(m.rows(), 9u);
  const auto H = [](double x, double y) { return 0.1 + 0.2 * x - 0.3 * y + 0.15 * x * y; };
  for (double x : {-1.0, -0.61, 0.0, 0.33, 1.49}) {
    for (double y : {-0.5, -0.2, 0.7, 1.5}) {
      ASSERT_NEAR(m.heightAt(x, y), H(x, y), 1e-14) << x << ", " << y;
      const Eigen::Vector3d n =
          Eigen::Vector3d(-(0.2 + 0.15 * y), -(-0.3 + 0.15 * x), 1.0).normalized();
      ASSERT_MATRIX_NEAR(m.normalAt(x, y), n, 1e-13);
    }
  }
  // Outside the grid the border value is held and the surface is flat across the border.
  EXPECT_NEAR(m.heightAt(5.0, 0.0), H(1.5, 0.0), 1e-14);
  EXPECT_NEAR(m.heightAt(-3.0, -9.0), H(-1.0, -0.5), 1e-14);
  EXPECT_NEAR(m.normalAt(5.0, 0.0).x(), 0.0, 1e-15);
}

TEST(HeightMap, GradientIsTheSlopeUnderTheNormal) {
  // gradientAt() = (∂H/∂x, ∂H/∂y); normalAt() is (−∂H/∂x, −∂H/∂y, 1) normalised; both are zero
  // across the border, where the height is held.
  const HeightMap m = bilinearMap(0.1, 0.2, -0.3, 0.15);
  const Eigen::Vector2d g = m.gradientAt(0.33, 0.7);
  EXPECT_MATRIX_NEAR(g, Eigen::Vector2d(0.2 + 0.15 * 0.7, -0.3 + 0.15 * 0.33), 1e-13);
  EXPECT_MATRIX_NEAR(m.normalAt(0.33, 0.7), Eigen::Vector3d(-g.x(), -g.y(), 1.0).normalized(),
                     1e-15);
  EXPECT_EQ(m.gradientAt(5.0, 0.0).x(), 0.0);
  EXPECT_EQ(m.gradientAt(0.0, -3.0).y(), 0.0);
}

TEST(HeightMap, GenericRayCastMatchesAPlane) {
  // A planar map over [−5, 5]² and the same TiltedPlane: the height map's march-and-bisect
  // agrees with the closed form (rays of ≤ 3 m from |x|, |y| ≤ 2 stay over the map).
  const HeightMap m = bilinearMap(0.1, 0.05, -0.08, 0.0, -5.0, -5.0, 0.25, 41, 41);
  const TiltedPlane plane({0.0, 0.0, 0.1}, Eigen::Vector3d(-0.05, 0.08, 1.0));
  int hits = 0;
  forRandomRays(4, 200, [&](const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
    const auto exact = plane.rayCast(o, d, 3.0);
    const auto march = m.rayCast(o, d, 3.0);
    ASSERT_EQ(exact.has_value(), march.has_value());
    if (exact) {
      ++hits;
      ASSERT_NEAR(*exact, *march, kMarchTol);
    }
  });
  EXPECT_GT(hits, 50);
}

TEST(HeightMap, SlopeBoundedRayCastMatchesTheGenericMarch) {
  // A bumpy map (±5 cm waves on 10 cm cells): the override and the base class's march find the
  // same first hits; rays that climb away miss in both.
  std::vector<std::vector<double>> rows(61, std::vector<double>(61));
  for (std::size_t j = 0; j < 61; ++j) {
    for (std::size_t i = 0; i < 61; ++i) {
      rows[j][i] = 0.05 * std::sin(1.3 * static_cast<double>(i) * 0.1) *
                       std::cos(0.9 * static_cast<double>(j) * 0.1) +
                   0.02 * std::sin(7.0 * static_cast<double>(i + j) * 0.1);
    }
  }
  const HeightMap m(-3.0, -3.0, 0.1, rows);
  int hits = 0;
  forRandomRays(5, 300, [&](const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
    const auto fast = m.rayCast(o, d, 4.0);
    const auto march = marched(m, o, d, 4.0);
    ASSERT_EQ(fast.has_value(), march.has_value()) << o.transpose() << " / " << d.transpose();
    if (fast) {
      ++hits;
      ASSERT_NEAR(*fast, *march, kMarchTol) << o.transpose() << " / " << d.transpose();
    }
  });
  EXPECT_GT(hits, 100);
}

/// The bumpy map of the tests below: ±5 cm waves plus a ±2 cm ripple on 10 cm cells.
HeightMap bumpyMap() {
  std::vector<std::vector<double>> rows(61, std::vector<double>(61));
  for (std::size_t j = 0; j < 61; ++j) {
    for (std::size_t i = 0; i < 61; ++i) {
      rows[j][i] = 0.05 * std::sin(1.3 * static_cast<double>(i) * 0.1) *
                       std::cos(0.9 * static_cast<double>(j) * 0.1) +
                   0.02 * std::sin(7.0 * static_cast<double>(i + j) * 0.1);
    }
  }
  return HeightMap(-3.0, -3.0, 0.1, rows);
}

/// The ray's first hit is exact when the hit point lies on the surface and the ray is above
/// the surface everywhere before it (sampled every 0.5 mm: a check, not a proof).
void expectFirstHit(const HeightMap& m, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                    double t) {
  const auto gap = [&](double s) {
    const Eigen::Vector3d p = o + s * d;
    return p.z() - m.heightAt(p.x(), p.y());
  };
  EXPECT_NEAR(gap(t), 0.0, 1e-12) << o.transpose() << " / " << d.transpose();
  for (double s = 0.0; s < t - 1e-6; s += 5e-4)
    ASSERT_GT(gap(s), 0.0) << "s = " << s << " of " << t << ": " << o.transpose();
}

TEST(HeightMap, CellWalkRayCastIsExactOnEveryKindOfRay) {
  // The height map's own ray cast walks the cells under the ray and solves each bilinear patch
  // exactly (a quadratic along the ray): the hit is on the surface to round-off, nothing is
  // hit before it, and it agrees with the generic march (which bisects to 1e-9 m).
  const HeightMap m = bumpyMap();
  const auto check = [&](const Eigen::Vector3d& o, const Eigen::Vector3d& dir,
                         double range) -> bool {
    const Eigen::Vector3d d = dir.normalized();
    const auto fast = m.rayCast(o, dir, range);
    const auto march = marched(m, o, d, range);
    EXPECT_EQ(fast.has_value(), march.has_value()) << o.transpose() << " / " << d.transpose();
    if (!fast || !march) return false;
    EXPECT_NEAR(*fast, *march, kMarchTol) << o.transpose() << " / " << d.transpose();
    expectFirstHit(m, o, d, *fast);
    return true;
  };
  // Vertical, axis-parallel, diagonal and grazing rays; from above, from the side below the
  // highest node (hitting the flank of a bump), from outside the grid inwards (the border is
  // held there), along a grid line, and one climbing away.
  EXPECT_TRUE(check({0.31, -0.42, 0.5}, {0, 0, -1}, 4.0));
  EXPECT_TRUE(check({0.0, 0.0, 0.5}, {1, 0, -0.3}, 4.0));
  EXPECT_TRUE(check({0.0, 0.0, 0.5}, {0, -1, -0.3}, 4.0));
  EXPECT_TRUE(check({-1.0, -1.0, 0.3}, {1, 1, -0.2}, 4.0));
  EXPECT_TRUE(check({-2.0, 0.3, 0.06}, {1, 0.05, -0.01}, 4.0));
  EXPECT_TRUE(check({-5.0, 0.2, 0.4}, {1, 0.1, -0.2}, 4.0));
  EXPECT_TRUE(check({0.5, 5.0, 0.4}, {0.0, -1, -0.15}, 4.0));
  EXPECT_TRUE(check({-0.5, 0.7, 0.5}, {1, 0, -0.4}, 4.0));   // x and y on grid lines
  EXPECT_TRUE(check({4.0, 4.0, 0.3}, {-1, -1, -0.1}, 4.0));  // from the held corner
  EXPECT_FALSE(check({0.0, 0.0, 0.5}, {0.3, 0.2, 1.0}, 4.0));
  EXPECT_FALSE(check({0.0, 0.0, 0.5}, {0, 0, -1}, 0.3));  // out of range
  // Grazing rays just above the crests, in every direction.
  int hits = 0;
  for (int k = 0; k < 72; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 72.0;
    hits += check({0.1, -0.2, 0.09}, {std::cos(a), std::sin(a), -0.02}, 4.0) ? 1 : 0;
  }
  EXPECT_GT(hits, 20);  // 35 of 72 reach the surface within 4 m
  // Under the surface: a hit at 0.
  EXPECT_DOUBLE_EQ(*m.rayCast({0.0, 0.0, m.heightAt(0.0, 0.0) - 1e-3}, {0, 0, -1}, 4.0), 0.0);
}

TEST(HeightMap, CellWalkRayCastMatchesTheMarchFromAnywhere) {
  // Random rays from inside and outside the grid (it spans ±3 m), heights from just above the
  // crests to 3 m, many nearly horizontal.
  const HeightMap m = bumpyMap();
  std::mt19937_64 rng(17);
  const auto u = [&rng](double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
  };
  int hits = 0;
  for (int k = 0; k < 400; ++k) {
    const Eigen::Vector3d o(u(-4.0, 4.0), u(-4.0, 4.0), u(0.08, 3.0));
    const Eigen::Vector3d d = Eigen::Vector3d(u(-1, 1), u(-1, 1), u(-1.0, 0.05)).normalized();
    const auto fast = m.rayCast(o, d, 4.0);
    const auto march = marched(m, o, d, 4.0);
    ASSERT_EQ(fast.has_value(), march.has_value()) << o.transpose() << " / " << d.transpose();
    if (!fast) continue;
    ++hits;
    ASSERT_NEAR(*fast, *march, kMarchTol) << o.transpose() << " / " << d.transpose();
    expectFirstHit(m, o, d, *fast);
    // The ranger's entry point: the same hit, and the gradient of the patch under it.
    const auto hit = m.rayHitUnit(o, d, 4.0);
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->distance_m, *fast, 1e-12);
    const Eigen::Vector3d p = o + hit->distance_m * d;
    EXPECT_MATRIX_NEAR(hit->gradient, m.gradientAt(p.x(), p.y()), 1e-9);
  }
  EXPECT_GT(hits, 150);
}

TEST(HeightMap, BuiltFromAGrid) {
  const model::HeightGrid grid{-1.0, 2.0, 0.5, {{0.0, 0.1, 0.2}, {0.5, 0.6, 0.7}, {1.0, 1.0, 1.0}}};
  const HeightMap m(grid);
  EXPECT_EQ(m.columns(), 3u);
  EXPECT_EQ(m.rows(), 3u);
  EXPECT_DOUBLE_EQ(m.cellSize(), 0.5);
  EXPECT_DOUBLE_EQ(m.maxHeight(), 1.0);
  EXPECT_NEAR(m.heightAt(-1.0, 2.0), 0.0, 1e-15);
  EXPECT_NEAR(m.heightAt(-0.5, 2.5), 0.6, 1e-15);
  EXPECT_NEAR(m.heightAt(-0.75, 2.25), (0.0 + 0.1 + 0.5 + 0.6) / 4.0, 1e-15);
}

TEST(HeightMap, RejectsBadGridsInMemory) {
  EXPECT_THROW(HeightMap(0, 0, 1.0, {{0.0, 1.0}}), std::invalid_argument);
  EXPECT_THROW(HeightMap(0, 0, 1.0, {{0.0, 1.0}, {0.0}}), std::invalid_argument);
  EXPECT_THROW(HeightMap(0, 0, 0.0, {{0.0, 1.0}, {0.0, 1.0}}), std::invalid_argument);
  EXPECT_THROW(HeightMap(0, 0, 1.0, {{0.0, NAN}, {0.0, 1.0}}), std::invalid_argument);
}

}  // namespace
}  // namespace geaware::sim
