// SPDX-License-Identifier: BSD-3-Clause
// Lattice-ranger height and ground normal. Frames are ray-cast here against analytic terrain
// (a plane; a table edge with its vertical face), so the expected height is exact.
#include "geaware/estimation/lattice_height.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <random>

#include "geaware/model/mixer.hpp"
#include "geaware_test/eigen_matchers.hpp"

namespace {

using namespace geaware::estimation;
using Eigen::Quaterniond;
using Eigen::Vector3d;
using geaware::model::RangerFrame;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kB = 0.35;  // paper quad's diagonal rotor distance [m]

/// Distance along a ray (origin, unit direction) to the terrain, if it hits within range.
using Terrain = std::function<std::optional<double>(const Vector3d&, const Vector3d&)>;

/// Plane n·x = c (world).
Terrain plane(const Vector3d& n_in, double c) {
  const Vector3d n = n_in.normalized();
  return [n, c](const Vector3d& o, const Vector3d& d) -> std::optional<double> {
    const double nd = n.dot(d);
    if (nd >= 0.0) return std::nullopt;
    const double t = (c - n.dot(o)) / nd;
    if (t <= 0.0) return std::nullopt;
    return t;
  };
}

/// Floor z = 0 and a table top z = H for x > x_edge, with its vertical face at x = x_edge.
Terrain tableEdge(double H, double x_edge) {
  return [H, x_edge](const Vector3d& o, const Vector3d& d) -> std::optional<double> {
    double best = std::numeric_limits<double>::infinity();
    if (d.z() < 0.0) {
      const double t_top = (H - o.z()) / d.z();
      if (t_top > 0.0 && o.x() + t_top * d.x() > x_edge) best = std::min(best, t_top);
      const double t_floor = -o.z() / d.z();
      if (t_floor > 0.0 && o.x() + t_floor * d.x() <= x_edge) best = std::min(best, t_floor);
    }
    if (d.x() != 0.0) {
      const double t_face = (x_edge - o.x()) / d.x();
      const double z = o.z() + t_face * d.z();
      if (t_face > 0.0 && z >= 0.0 && z <= H) best = std::min(best, t_face);
    }
    if (!std::isfinite(best)) return std::nullopt;
    return best;
  };
}

struct Pose {
  Vector3d p_W;  // body origin = rotor-plane centre here [m]
  Quaterniond q_WB;
};

RangerFrame castFrame(const Terrain& terrain, const Pose& pose, double noise_std = 0.0,
                      std::uint64_t seed = 1, double max_range = 4.0) {
  RangerFrame f;
  f.side = 16;
  f.fov_rad = 45.0 * kDeg;
  f.mount_B = {0.04, -0.01, -0.05};
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01;
  const Vector3d o = pose.p_W + pose.q_WB * f.mount_B;
  for (int i = 0; i < f.side; ++i) {
    for (int j = 0; j < f.side; ++j) {
      const auto k = static_cast<std::size_t>(f.index(i, j));
      const auto t = terrain(o, pose.q_WB * f.zoneDirection_B(i, j));
      f.valid[k] = t.has_value() && *t <= max_range;
      f.range_m[k] = f.valid[k] ? *t + noise_std * n01(rng) : 0.0;
    }
  }
  return f;
}

Quaterniond attitude(double roll, double pitch, double yaw) {
  return Eigen::AngleAxisd(yaw, Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Vector3d::UnitY()) *
         Eigen::AngleAxisd(roll, Vector3d::UnitX());
}

LatticeHeightParams params() {
  LatticeHeightParams p;
  p.diagonal_rotor_distance_m = kB;
  return p;
}

TEST(LatticeHeightParams, ValidateNamesOffendingFields) {
  LatticeHeightParams p = params();
  EXPECT_TRUE(p.validate().empty());
  p.inlier_threshold_m = 0.0;
  p.max_surfaces = 9;
  const auto e = p.validate();
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].field, "lattice.inlier_threshold_m");
  EXPECT_EQ(e[1].field, "lattice.max_surfaces");
  EXPECT_THROW(LatticeHeightEstimator{p}, std::invalid_argument);
}

/// Closed form: flat ground, tilted and yawed vehicle, offset sensor, no noise → exact height,
/// normal and per-rotor heights (rotor i at height p_z + (R·r_i)_z).
TEST(LatticeHeight, FlatGroundIsExactWithoutNoise) {
  const LatticeHeightEstimator est(params());
  const Pose pose{{0.3, -0.2, 0.5}, attitude(10 * kDeg, -5 * kDeg, 30 * kDeg)};
  const LatticeHeight h = est.estimate(castFrame(plane(Vector3d::UnitZ(), 0.0), pose), pose.q_WB);
  ASSERT_TRUE(h.valid) << toString(h.status);
  EXPECT_NEAR(h.height_m, 0.5, 1e-9);
  EXPECT_MATRIX_NEAR(h.normal_W, Vector3d::UnitZ(), 1e-9);
  EXPECT_EQ(h.inliers, 256);
  EXPECT_EQ(h.usable_zones, 256);
  EXPECT_EQ(h.surfaces, 1);
  EXPECT_LT(h.rms_residual_m, 1e-9);
  const auto rotors = geaware::model::Mixer::rotorPositions_B(kB);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(h.rotor_height_m[i], 0.5 + (pose.q_WB * rotors[i]).z(), 1e-9);
    EXPECT_EQ(h.rotor_height_offset_m[i], 0.0) << "one surface: no partial ground effect";
  }
}

/// 1 cm range noise (a ToF ranger's order): height within 3 mm; normal within 3° (at 0.22 m
/// the footprint is only ±7 cm wide, so the tilt's 1σ is about 0.6° per axis).
TEST(LatticeHeight, FlatGroundWithNoiseWithinMillimetres) {
  const LatticeHeightEstimator est(params());
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Pose pose{{0.0, 0.0, 0.12 + 0.1 * static_cast<double>(seed)}, attitude(0.1, 0.05, 1.0)};
    const LatticeHeight h =
        est.estimate(castFrame(plane(Vector3d::UnitZ(), 0.0), pose, 0.01, seed), pose.q_WB);
    ASSERT_TRUE(h.valid) << toString(h.status);
    EXPECT_NEAR(h.height_m, pose.p_W.z(), 0.003) << "seed " << seed;
    EXPECT_LT(std::acos(std::min(1.0, h.normal_W.z())), 3.0 * kDeg) << "seed " << seed;
    EXPECT_GT(h.inliers, 240);
  }
}

/// The operating regime of the paper: rotor plane 0.1 m above the ground, the sensor 5 cm
/// above it, so the footprint is only ±2 cm; 5 mm noise, random tilts up to 0.1 rad. The
/// level-ground prior keeps the noisy tilt from biasing the height: within 5 mm.
TEST(LatticeHeight, LowAltitudeWithinMillimetres) {
  const LatticeHeightEstimator est(params());
  for (int t = 0; t < 50; ++t) {
    const Pose pose{{0.0, 0.0, 0.1}, attitude(0.1 * std::sin(t), 0.1 * std::cos(t), 0.0)};
    const LatticeHeight h = est.estimate(
        castFrame(plane(Vector3d::UnitZ(), 0.0), pose, 0.005, static_cast<std::uint64_t>(t)),
        pose.q_WB);
    ASSERT_TRUE(h.valid) << toString(h.status);
    EXPECT_NEAR(h.height_m, 0.1, 0.005) << "trial " << t;
  }
}

/// 20 % of the zones read garbage (uniform in [0.02, 3] m): the fit ignores them.
TEST(LatticeHeight, RobustToTwentyPercentOutliers) {
  const LatticeHeightEstimator est(params());
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> garbage(0.02, 3.0);
  std::bernoulli_distribution pick(0.2);
  for (int trial = 0; trial < 20; ++trial) {
    const Pose pose{{0.0, 0.0, 0.3 + 0.05 * trial}, attitude(-0.1, 0.15, 0.3)};
    RangerFrame f =
        castFrame(plane(Vector3d::UnitZ(), 0.0), pose, 0.005, static_cast<std::uint64_t>(trial));
    int bad = 0;
    for (std::size_t k = 0; k < 256; ++k) {
      if (pick(rng)) {
        f.range_m[k] = garbage(rng);
        ++bad;
      }
    }
    const LatticeHeight h = est.estimate(f, pose.q_WB);
    ASSERT_TRUE(h.valid) << toString(h.status);
    EXPECT_NEAR(h.height_m, pose.p_W.z(), 0.003)
        << "trial " << trial << " with " << bad << " outliers";
    EXPECT_LT(std::acos(std::min(1.0, h.normal_W.z())), 1.0 * kDeg);
    EXPECT_LE(h.inliers, 256 - bad + 8);  // a few garbage zones may land on the plane by chance
  }
}

/// Zones without a return (beyond range), and zones flagged valid with a NaN or an
/// out-of-range reading, are left out.
TEST(LatticeHeight, MissingAndNonFiniteZonesAreLeftOut) {
  const LatticeHeightEstimator est(params());
  // Rolled vehicle high above flat ground: the far zones exceed a 1.75 m range.
  const Pose pose{{0.0, 0.0, 1.6}, attitude(0.2, 0.0, 0.0)};
  RangerFrame f = castFrame(plane(Vector3d::UnitZ(), 0.0), pose, 0.0, 1, 1.75);
  int missing = 0;
  for (std::size_t k = 0; k < 256; ++k) missing += f.valid[k] ? 0 : 1;
  ASSERT_GT(missing, 20);
  f.range_m[0] = std::numeric_limits<double>::quiet_NaN();
  f.valid[0] = true;
  f.range_m[1] = -1.0;
  f.valid[1] = true;
  const LatticeHeight h = est.estimate(f, pose.q_WB);
  ASSERT_TRUE(h.valid) << toString(h.status);
  EXPECT_NEAR(h.height_m, 1.6, 1e-9);
  EXPECT_EQ(h.discarded_zones, 2);
  int flagged = 0;
  for (std::size_t k = 0; k < 256; ++k) flagged += f.valid[k] ? 1 : 0;
  EXPECT_EQ(h.usable_zones, flagged - 2);
}

/// Tilted ground: the normal is recovered in the world frame, and the height is the vertical
/// distance to the plane (not the perpendicular one). Exact without noise when the level-ground
/// prior is switched off; with the default prior, the slope shrinks by λ/(λ + Σx²) ≈ 1e-4.
TEST(LatticeHeight, TiltedPlaneNormalRecovered) {
  const LatticeHeightEstimator est(params());
  LatticeHeightParams no_prior = params();
  no_prior.ground_slope_prior = 1e9;
  const LatticeHeightEstimator unbiased(no_prior);
  const Vector3d n =
      (Eigen::AngleAxisd(15 * kDeg, Vector3d(1.0, 2.0, 0.0).normalized()) * Vector3d::UnitZ());
  const double c = 0.1;  // plane n·x = c
  const Pose pose{{0.4, 0.2, 0.9}, attitude(5 * kDeg, 8 * kDeg, -40 * kDeg)};
  const double h_true = (n.dot(pose.p_W) - c) / n.z();
  const LatticeHeight exact = unbiased.estimate(castFrame(plane(n, c), pose), pose.q_WB);
  ASSERT_TRUE(exact.valid);
  EXPECT_MATRIX_NEAR(exact.normal_W, n, 1e-9);
  EXPECT_NEAR(exact.height_m, h_true, 1e-9);
  const LatticeHeight shrunk = est.estimate(castFrame(plane(n, c), pose), pose.q_WB);
  ASSERT_TRUE(shrunk.valid);
  EXPECT_MATRIX_NEAR(shrunk.normal_W, n, 1e-4);
  EXPECT_NEAR(shrunk.height_m, h_true, 1e-5);
  const LatticeHeight noisy = est.estimate(castFrame(plane(n, c), pose, 0.01, 5), pose.q_WB);
  ASSERT_TRUE(noisy.valid);
  EXPECT_LT(std::acos(std::min(1.0, noisy.normal_W.dot(n))), 1.0 * kDeg);
  EXPECT_NEAR(noisy.height_m, h_true, 0.003);
}

/// Table edge (0.3 m step at x = 0, with its vertical face). The rule: the ground is the
/// surface under the rotor-plane centre, even when the other surface fills more zones.
TEST(LatticeHeight, StepTerrainPicksTheSurfaceUnderTheVehicle) {
  const LatticeHeightEstimator est(params());
  const Terrain step = tableEdge(0.3, 0.0);
  struct Case {
    double x;       // vehicle x [m]
    double pitch;   // positive pitch (nose down) turns the downward view towards −x
    double expect;  // height of the surface under the centre [m]
  };
  // Centre over the floor, view turned towards the table: most zones see the table.
  // Centre over the table, view turned towards the floor: most zones see the floor.
  for (const Case& cs : {Case{-0.03, -15 * kDeg, 0.8}, Case{0.03, 15 * kDeg, 0.5}}) {
    const Pose pose{{cs.x, 0.1, 0.8}, attitude(0.0, cs.pitch, 0.0)};
    const RangerFrame f = castFrame(step, pose, 0.005, 3);
    // Check the premise: the surface under the centre has fewer zones than the other.
    int on_table = 0, on_floor = 0;
    const Vector3d o = pose.p_W + pose.q_WB * f.mount_B;
    for (int i = 0; i < 16; ++i) {
      for (int j = 0; j < 16; ++j) {
        const double r = *step(o, pose.q_WB * f.zoneDirection_B(i, j));
        const double z = (o + r * (pose.q_WB * f.zoneDirection_B(i, j))).z();
        on_table += std::abs(z - 0.3) < 1e-9 ? 1 : 0;
        on_floor += std::abs(z) < 1e-9 ? 1 : 0;
      }
    }
    if (cs.expect == 0.8) {
      ASSERT_GT(on_table, on_floor);
    } else {
      ASSERT_GT(on_floor, on_table);
    }
    const LatticeHeight h = est.estimate(f, pose.q_WB);
    ASSERT_TRUE(h.valid) << toString(h.status);
    EXPECT_GE(h.surfaces, 2);
    EXPECT_NEAR(h.height_m, cs.expect, 0.005) << "x = " << cs.x;
    EXPECT_LT(std::acos(std::min(1.0, h.normal_W.z())), 3.0 * kDeg);
  }
}

/// Per-rotor heights over the edge: the front rotors (x > 0) are over the table, the rear
/// ones over the floor — the partial ground effect the simulator models per rotor.
TEST(LatticeHeight, PerRotorHeightsOverAnEdge) {
  const LatticeHeightEstimator est(params());
  // Centre 6 cm from the edge: closer than about one zone footprint (plus the occlusion by
  // the edge, seen from the offset sensor) either surface may be reported; see the docs.
  const Pose pose{{-0.06, 0.0, 0.6}, Quaterniond::Identity()};
  const LatticeHeight h = est.estimate(castFrame(tableEdge(0.3, 0.0), pose, 0.005, 4), pose.q_WB);
  ASSERT_TRUE(h.valid) << toString(h.status);
  EXPECT_NEAR(h.height_m, 0.6, 0.005);
  const auto rotors = geaware::model::Mixer::rotorPositions_B(kB);
  for (std::size_t i = 0; i < 4; ++i) {
    const bool over_table = pose.p_W.x() + rotors[i].x() > 0.0;
    EXPECT_NEAR(h.rotor_height_m[i], over_table ? 0.3 : 0.6, 0.005) << "rotor " << i + 1;
    // Against the floor under the centre, extended: the rotors over the table are 0.3 m nearer
    // their surface, the others exactly on the plane.
    if (over_table) {
      EXPECT_NEAR(h.rotor_height_offset_m[i], -0.3, 0.005) << "rotor " << i + 1;
    } else {
      EXPECT_EQ(h.rotor_height_offset_m[i], 0.0) << "rotor " << i + 1;
    }
    EXPECT_LT(h.rotor_support_distance_m[i], 0.05)
        << "rotor " << i + 1 << " is inside the footprint";
  }
}

TEST(LatticeHeight, InvalidInputsAreFlagged) {
  const LatticeHeightEstimator est(params());
  const Pose pose{{0.0, 0.0, 0.5}, Quaterniond::Identity()};
  const RangerFrame good = castFrame(plane(Vector3d::UnitZ(), 0.0), pose);

  Quaterniond nanq = pose.q_WB;
  nanq.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(est.estimate(good, nanq).status, LatticeStatus::kNonFiniteInput);
  EXPECT_FALSE(est.estimate(good, nanq).valid);

  RangerFrame f = good;
  f.side = 0;
  EXPECT_EQ(est.estimate(f, pose.q_WB).status, LatticeStatus::kBadFrame);

  f = good;
  f.valid.fill(false);
  EXPECT_EQ(est.estimate(f, pose.q_WB).status, LatticeStatus::kTooFewZones);

  // Only one row of zones: collinear points, no unique plane.
  f = good;
  for (int i = 0; i < 16; ++i) {
    for (int j = 0; j < 16; ++j) f.valid[static_cast<std::size_t>(f.index(i, j))] = i == 7;
  }
  EXPECT_EQ(est.estimate(f, pose.q_WB).status, LatticeStatus::kDegenerate);

  // Every zone reads garbage: no supported surface.
  f = good;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> garbage(0.05, 3.0);
  for (auto& r : f.range_m) r = garbage(rng);
  const LatticeHeight g = est.estimate(f, pose.q_WB);
  EXPECT_FALSE(g.valid);
  EXPECT_EQ(g.status, LatticeStatus::kNoSurface);

  // A rotor-plane centre configured below the ground.
  LatticeHeightParams p = params();
  p.rotor_plane_centre_B = {0.0, 0.0, -1.0};
  EXPECT_EQ(LatticeHeightEstimator(p).estimate(good, pose.q_WB).status,
            LatticeStatus::kSurfaceAbove);
}

TEST(LatticeHeight, DeterministicForTheSameFrame) {
  const LatticeHeightEstimator est(params());
  const Pose pose{{0.0, 0.0, 0.7}, attitude(0.1, 0.1, 0.1)};
  RangerFrame f = castFrame(tableEdge(0.2, 0.05), pose, 0.01, 8);
  for (std::size_t k = 0; k < 256; k += 5) f.range_m[k] = 0.1 + 0.01 * static_cast<double>(k % 50);
  const LatticeHeight a = est.estimate(f, pose.q_WB);
  const LatticeHeight b = est.estimate(f, pose.q_WB);
  EXPECT_EQ(a.height_m, b.height_m);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.surfaces, b.surfaces);
}

}  // namespace
