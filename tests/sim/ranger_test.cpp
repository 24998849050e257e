// SPDX-License-Identifier: BSD-3-Clause
// The simulated lattice ranger against closed forms: flat ground at a known height (centre
// zones read h/cos, every return lies on the plane), a tilted plane recovered from a frame,
// max range, grazing rays, noise and outlier statistics, zone order, rate, validation.
#include "geaware/sim/ranger.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "geaware/model/vehicle_model.hpp"
#include "geaware/sim/terrains.hpp"
#include "geaware_test/eigen_matchers.hpp"

namespace geaware::sim {
namespace {

using model::RangerFrame;

RangerParams exact() {
  RangerParams p;
  p.noise_floor_m = 0.0;
  p.noise_fraction = 0.0;
  p.outlier_probability = 0.0;
  return p;
}

PlantState hovering(double height_m, const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity(), double t_s = 0.0) {
  PlantState s;
  s.t_s = t_s;
  s.p_W = Eigen::Vector3d(0.3, -0.2, height_m);
  s.q_WB = q;
  return s;
}

/// World point a zone's return describes.
Eigen::Vector3d hitPoint(const PlantState& s, const RangerFrame& f, int i, int j) {
  const Eigen::Matrix3d R = s.q_WB.toRotationMatrix();
  return s.p_W + R * f.mount_B + f.range_m[f.index(i, j)] * (R * f.zoneDirection_B(i, j));
}

TEST(LatticeRanger, FlatGroundLevelCentreZonesReadHeightOverCosine) {
  const FlatGround ground(0.0);
  const RangerParams p = exact();
  LatticeRanger ranger(p, 1);
  const double h = 0.5;
  const PlantState s = hovering(h);
  const auto f = ranger.sample(s, &ground);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->side, 16);
  EXPECT_DOUBLE_EQ(f->fov_rad, p.fov_rad);
  EXPECT_EQ(f->mount_B, p.mount_B);
  const double h_sensor = h + p.mount_B.z();  // the sensor hangs under the geometric centre
  for (int i = 7; i <= 8; ++i) {
    for (int j = 7; j <= 8; ++j) {
      const Eigen::Vector3d d = f->zoneDirection_B(i, j);
      ASSERT_TRUE(f->valid[f->index(i, j)]);
      EXPECT_NEAR(f->range_m[f->index(i, j)], h_sensor / -d.z(), 1e-12);
    }
  }
  // Every zone returns, and every return lies on the ground plane.
  for (int i = 0; i < 16; ++i) {
    for (int j = 0; j < 16; ++j) {
      ASSERT_TRUE(f->valid[f->index(i, j)]) << i << "," << j;
      EXPECT_NEAR(hitPoint(s, *f, i, j).z(), 0.0, 1e-12) << i << "," << j;
    }
  }
}

TEST(LatticeRanger, ZoneOrderFollowsTheBodyAxes) {
  // Zone (i, j) at index i·N + j looks towards +x_B for large i and +y_B for large j. Yawed by
  // 90°, +x_B is +y_W.
  const FlatGround ground(0.0);
  LatticeRanger ranger(exact(), 1);
  const PlantState s = hovering(1.0, Eigen::Quaterniond(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ())));
  const auto f = ranger.sample(s, &ground);
  ASSERT_TRUE(f);
  const Eigen::Vector3d centre = s.p_W + s.q_WB * f->mount_B;
  EXPECT_GT(hitPoint(s, *f, 15, 8).y() - centre.y(), 0.3);
  EXPECT_LT(hitPoint(s, *f, 0, 8).y() - centre.y(), -0.3);
  EXPECT_LT(hitPoint(s, *f, 8, 15).x() - centre.x(), -0.3);  // +y_B is −x_W
}

TEST(LatticeRanger, TiltedVehicleOverFlatGroundStillHitsThePlane) {
  const FlatGround ground(0.1);
  LatticeRanger ranger(exact(), 1);
  const PlantState s = hovering(0.8, Eigen::Quaterniond(Eigen::AngleAxisd(0.25, Eigen::Vector3d(1, -2, 0.5).normalized())));
  const auto f = ranger.sample(s, &ground);
  ASSERT_TRUE(f);
  for (int k = 0; k < 256; ++k) {
    ASSERT_TRUE(f->valid[k]);
    EXPECT_NEAR(hitPoint(s, *f, k / 16, k % 16).z(), 0.1, 1e-12);
  }
}

TEST(LatticeRanger, SeesTheTiltOfATiltedPlane) {
  // A plane pitched 10° (its +x side lower): the returns lie on it, the +x zones read longer
  // than the −x ones, and a least-squares plane through the returns recovers the normal.
  const double pitch = 10.0 * model::kDegToRad;
  const TiltedPlane plane = TiltedPlane::fromTilt(Eigen::Vector3d(0.3, -0.2, 0.0), 0.0, pitch);
  const Eigen::Vector3d n_true = plane.normalAt(0, 0);
  LatticeRanger ranger(exact(), 1);
  const PlantState s = hovering(0.4);
  const auto f = ranger.sample(s, &plane);
  ASSERT_TRUE(f);
  Eigen::MatrixXd A(256, 3);
  Eigen::VectorXd b(256);
  for (int k = 0; k < 256; ++k) {
    ASSERT_TRUE(f->valid[k]);
    const Eigen::Vector3d p = hitPoint(s, *f, k / 16, k % 16);
    EXPECT_NEAR(n_true.dot(p - Eigen::Vector3d(0.3, -0.2, 0.0)), 0.0, 1e-12);
    A.row(k) << p.x(), p.y(), 1.0;  // z = a·x + b·y + c
    b[k] = p.z();
  }
  EXPECT_GT(f->range_m[f->index(15, 8)], f->range_m[f->index(0, 8)] + 0.05);
  const Eigen::Vector3d abc = A.colPivHouseholderQr().solve(b);
  const Eigen::Vector3d n_fit = Eigen::Vector3d(-abc.x(), -abc.y(), 1.0).normalized();
  EXPECT_MATRIX_NEAR(n_fit, n_true, 1e-9);
  EXPECT_NEAR(std::atan2(-n_fit.x(), n_fit.z()), -pitch, 1e-9);  // fromTilt: n = R_y(pitch)·z
}

/// Any terrain seen only through the Terrain interface (the ranger's generic ray-cast path).
class Opaque final : public Terrain {
 public:
  explicit Opaque(const Terrain& t) : t_(t) {}
  double heightAt(double x, double y) const noexcept override { return t_.heightAt(x, y); }
  Eigen::Vector3d normalAt(double x, double y) const noexcept override { return t_.normalAt(x, y); }
  std::optional<double> rayCast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double r) const noexcept override {
    return t_.rayCast(o, d, r);
  }

 private:
  const Terrain& t_;
};

TEST(LatticeRanger, PlaneShortcutsMatchTheGenericRayCast) {
  // Flat ground and tilted planes are cast in closed form; through the generic path the same
  // seed must give the same frame (same validity, same noise draws) to round-off.
  const FlatGround flat(0.05);
  const TiltedPlane tilted = TiltedPlane::fromTilt(Eigen::Vector3d(0.1, 0.2, -0.1), 0.1, -0.2);
  RangerParams p;
  p.outlier_probability = 0.01;
  p.max_range_m = 1.0;  // some zones out of range
  for (const Terrain* t : {static_cast<const Terrain*>(&flat), static_cast<const Terrain*>(&tilted)}) {
    const Opaque opaque(*t);
    LatticeRanger a(p, 12), b(p, 12);
    for (int k = 0; k < 20; ++k) {
      const PlantState s = hovering(0.3 + 0.04 * k, Eigen::Quaterniond(Eigen::AngleAxisd(0.05 * k, Eigen::Vector3d(1, 1, 0).normalized())));
      const RangerFrame fa = a.measure(s, t);
      const RangerFrame fb = b.measure(s, &opaque);
      for (int z = 0; z < 256; ++z) {
        ASSERT_EQ(fa.valid[z], fb.valid[z]) << "frame " << k << " zone " << z;
        EXPECT_NEAR(fa.range_m[z], fb.range_m[z], 1e-12) << "frame " << k << " zone " << z;
      }
    }
  }
}

TEST(LatticeRanger, ZonesBeyondMaxRangeHaveNoReturn) {
  const FlatGround ground(0.0);
  const RangerParams p = exact();  // max 4 m
  LatticeRanger ranger(p, 1);
  // 5 m up: nothing returns.
  auto f = ranger.sample(hovering(5.0), &ground);
  ASSERT_TRUE(f);
  for (int k = 0; k < 256; ++k) {
    EXPECT_FALSE(f->valid[k]);
    EXPECT_EQ(f->range_m[k], 0.0);
  }
  // 3.9 m up: exactly the zones whose slant range is within 4 m return.
  f = ranger.sample(hovering(3.9, Eigen::Quaterniond::Identity(), 1.0), &ground);
  ASSERT_TRUE(f);
  int valid = 0;
  for (int i = 0; i < 16; ++i) {
    for (int j = 0; j < 16; ++j) {
      const double slant = (3.9 + p.mount_B.z()) / -f->zoneDirection_B(i, j).z();
      EXPECT_EQ(f->valid[f->index(i, j)], slant <= p.max_range_m) << i << "," << j;
      valid += f->valid[f->index(i, j)];
    }
  }
  EXPECT_GT(valid, 0);
  EXPECT_LT(valid, 256);
}

TEST(LatticeRanger, GrazingRaysHaveNoReturn) {
  // Rolled 65°: the outer zones on one side meet the ground at more than 80° from its normal.
  const FlatGround ground(0.0);
  RangerParams p = exact();
  p.max_range_m = 100.0;
  LatticeRanger ranger(p, 1);
  const PlantState s = hovering(1.0, Eigen::Quaterniond(Eigen::AngleAxisd(65.0 * model::kDegToRad, Eigen::Vector3d::UnitX())));
  const auto f = ranger.sample(s, &ground);
  ASSERT_TRUE(f);
  int grazing = 0;
  for (int i = 0; i < 16; ++i) {
    for (int j = 0; j < 16; ++j) {
      const Eigen::Vector3d d_W = s.q_WB * f->zoneDirection_B(i, j);
      const bool should = -d_W.z() >= std::cos(p.max_incidence_rad);
      EXPECT_EQ(f->valid[f->index(i, j)], should) << i << "," << j;
      grazing += !should;
    }
  }
  EXPECT_GT(grazing, 0);
}

TEST(LatticeRanger, RangeNoiseGrowsWithRange) {
  // σ = floor + fraction·r. The centre zone over 4,000 frames at two heights: std error of a
  // std ≈ 1.1 %; allow 5 %; the mean is unbiased within 5 standard errors.
  const FlatGround ground(0.0);
  RangerParams p;
  p.outlier_probability = 0.0;
  p.noise_floor_m = 0.003;
  p.noise_fraction = 0.01;
  for (double h : {0.3, 3.0}) {
    LatticeRanger ranger(p, 9);
    const PlantState s = hovering(h);
    RangerFrame geometry;
    geometry.side = p.side;
    geometry.fov_rad = p.fov_rad;
    const double r_true = (h + p.mount_B.z()) / -geometry.zoneDirection_B(8, 8).z();
    const double sigma = p.noise_floor_m + p.noise_fraction * r_true;
    constexpr int kN = 4000;
    double s1 = 0, s2 = 0;
    for (int k = 0; k < kN; ++k) {
      const RangerFrame f = ranger.measure(s, &ground);
      const double e = f.range_m[f.index(8, 8)] - r_true;
      s1 += e;
      s2 += e * e;
    }
    EXPECT_NEAR(s1 / kN, 0.0, 5 * sigma / std::sqrt(kN)) << "h = " << h;
    EXPECT_NEAR(std::sqrt(s2 / kN) / sigma, 1.0, 0.05) << "h = " << h;
  }
}

TEST(LatticeRanger, OutliersAppearAtTheConfiguredRate) {
  // 10 m up nothing returns, so every valid zone is an outlier: 2,000 frames × 256 zones at
  // p = 0.01, std error of the fraction ≈ 2e-4; allow 1e-3. Outliers lie in the working range.
  const FlatGround ground(0.0);
  RangerParams p = exact();
  p.outlier_probability = 0.01;
  LatticeRanger ranger(p, 4);
  long outliers = 0;
  for (int k = 0; k < 2000; ++k) {
    const RangerFrame f = ranger.measure(hovering(10.0), &ground);
    for (int z = 0; z < 256; ++z) {
      if (!f.valid[z]) continue;
      ++outliers;
      EXPECT_GE(f.range_m[z], p.min_range_m);
      EXPECT_LE(f.range_m[z], p.max_range_m);
    }
  }
  EXPECT_NEAR(static_cast<double>(outliers) / (2000.0 * 256.0), 0.01, 1e-3);
}

TEST(LatticeRanger, FramesAtItsRateAndSmallerLattices) {
  const FlatGround ground(0.0);
  RangerParams p = exact();
  p.side = 8;
  LatticeRanger ranger(p, 1);
  int frames = 0;
  for (int k = 0; k < 1000; ++k) {
    const auto f = ranger.sample(hovering(1.0, Eigen::Quaterniond::Identity(), k * 1e-3), &ground);
    if (!f) continue;
    ++frames;
    EXPECT_EQ(k % 10, 0);
    EXPECT_EQ(f->side, 8);
    for (int z = 0; z < 64; ++z) EXPECT_TRUE(f->valid[z]);
    for (int z = 64; z < RangerFrame::kMaxZones; ++z) EXPECT_FALSE(f->valid[z]);
  }
  EXPECT_EQ(frames, 100);
}

TEST(LatticeRanger, NoTerrainNoReturns) {
  LatticeRanger ranger(exact(), 1);
  const auto f = ranger.sample(hovering(0.2), nullptr);
  ASSERT_TRUE(f);
  for (int k = 0; k < 256; ++k) EXPECT_FALSE(f->valid[k]);
}

TEST(LatticeRanger, ValidationNamesTheFields) {
  RangerParams p;
  p.side = 17;
  p.min_range_m = 5.0;
  p.fov_rad = -1.0;
  const auto e = p.validate();
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[0].field, "side");
  EXPECT_EQ(e[1].field, "fov_rad");
  EXPECT_EQ(e[2].field, "min_range_m");
  EXPECT_THROW(LatticeRanger(p, 1), model::InvalidParameters);
}

}  // namespace
}  // namespace geaware::sim
