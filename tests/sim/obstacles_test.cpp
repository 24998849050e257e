// SPDX-License-Identifier: BSD-3-Clause
// Boxes around the vehicle (sim/obstacles.hpp): nearest points and ray casts against closed
// forms, the ceiling and wall contribution against the image law rotor by rotor, the sign of a
// partial ceiling's torque, strikes, and the single-beam ranger.
#include "geaware/sim/obstacles.hpp"

#include <cmath>
#include <memory>
#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "geaware/model/units.hpp"
#include "geaware/sim/plant.hpp"
#include "geaware/sim/terrains.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace geaware::sim {
namespace {

TruthParams paperTruth() { return fromNominal(geaware_test::paperParams()); }

/// A slab overhead whose underside is at z_m, over x in [x0, x1] (wide in y).
std::shared_ptr<const Obstacles> slab(double z_m, double x0 = -5.0, double x1 = 5.0) {
  return std::make_shared<const Obstacles>(std::vector<Box>{
      boxFromCorners(Eigen::Vector3d(x0, -5.0, z_m), Eigen::Vector3d(x1, 5.0, z_m + 0.2), 0.0, "ceiling")});
}

TEST(Obstacles, NearestPointsOfAnAxisAlignedAndAYawedBox) {
  const Obstacles o({boxFromCorners(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3), 0.0, "a")});
  BoxProximity p = o.proximity(0, Eigen::Vector3d(0.5, 1.0, 3.4));  // above the top face
  EXPECT_NEAR(p.distance_m, 0.4, 1e-15);
  EXPECT_TRUE(p.normal_W.isApprox(Eigen::Vector3d::UnitZ()));
  p = o.proximity(0, Eigen::Vector3d(1.3, 2.4, 1.0));  // beyond an edge: the edge is nearest
  EXPECT_NEAR(p.distance_m, 0.5, 1e-15);
  EXPECT_TRUE(p.normal_W.isApprox(Eigen::Vector3d(0.6, 0.8, 0.0)));
  EXPECT_TRUE(o.proximity(0, Eigen::Vector3d(0.5, 0.5, 0.5)).inside);
  EXPECT_EQ(o.containing(Eigen::Vector3d(0.5, 0.5, 0.5)), std::optional<std::size_t>(0));
  EXPECT_FALSE(o.containing(Eigen::Vector3d(-0.1, 0.5, 0.5)));
  // Yawed by 30°: a point 0.25 m out along the box's rotated x axis from the face centre.
  const double yaw = 30.0 * model::kDegToRad;
  const Obstacles y({boxFromCorners(Eigen::Vector3d(-1, -1, 0), Eigen::Vector3d(1, 1, 1), yaw, "yawed")});
  const Eigen::Vector3d x_axis(std::cos(yaw), std::sin(yaw), 0.0);
  p = y.proximity(0, 1.25 * x_axis + Eigen::Vector3d(0, 0, 0.5));
  EXPECT_NEAR(p.distance_m, 0.25, 1e-12);
  EXPECT_TRUE(p.normal_W.isApprox(x_axis, 1e-12));
  EXPECT_NEAR(y.clearance(1.25 * x_axis + Eigen::Vector3d(0, 0, 0.5)), 0.25, 1e-12);
  EXPECT_THROW(boxFromCorners(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 1)), std::invalid_argument);
}

TEST(Obstacles, RayCastsMeetTheFacesAtTheClosedFormDistance) {
  const auto o = slab(1.0);
  // Straight up from z = 0.7: 0.3 m, head-on.
  auto h = o->rayCast(Eigen::Vector3d(0, 0, 0.7), Eigen::Vector3d::UnitZ(), 4.0);
  ASSERT_TRUE(h);
  EXPECT_NEAR(h->distance_m, 0.3, 1e-12);
  EXPECT_NEAR(h->cos_incidence, 1.0, 1e-12);
  // Tilted by 40°: 0.3/cos 40°, incidence cos 40°.
  const double th = 40.0 * model::kDegToRad;
  h = o->rayCast(Eigen::Vector3d(0, 0, 0.7), Eigen::Vector3d(std::sin(th), 0, std::cos(th)), 4.0);
  ASSERT_TRUE(h);
  EXPECT_NEAR(h->distance_m, 0.3 / std::cos(th), 1e-12);
  EXPECT_NEAR(h->cos_incidence, std::cos(th), 1e-12);
  // Down, sideways past it, or beyond the range: nothing. From inside: 0.
  EXPECT_FALSE(o->rayCast(Eigen::Vector3d(0, 0, 0.7), -Eigen::Vector3d::UnitZ(), 4.0));
  EXPECT_FALSE(o->rayCast(Eigen::Vector3d(0, 0, 0.7), Eigen::Vector3d::UnitX(), 4.0));
  EXPECT_FALSE(o->rayCast(Eigen::Vector3d(0, 0, 0.7), Eigen::Vector3d::UnitZ(), 0.25));
  h = o->rayCast(Eigen::Vector3d(0, 0, 1.1), Eigen::Vector3d::UnitX(), 4.0);
  ASSERT_TRUE(h);
  EXPECT_EQ(h->distance_m, 0.0);
  // The nearer of two boxes.
  const Obstacles two({boxFromCorners(Eigen::Vector3d(2, -1, 0), Eigen::Vector3d(3, 1, 1)),
                       boxFromCorners(Eigen::Vector3d(1, -1, 0), Eigen::Vector3d(1.5, 1, 1))});
  h = two.rayCast(Eigen::Vector3d(0, 0, 0.5), Eigen::Vector3d::UnitX(), 4.0);
  ASSERT_TRUE(h);
  EXPECT_NEAR(h->distance_m, 1.0, 1e-12);
}

ContributionContext hoverAt(const Eigen::Vector3d& p_W, double n_rpm) {
  ContributionContext ctx;
  ctx.body.p_W = p_W;
  ctx.R_WB.setIdentity();
  ctx.n_rpm.fill(n_rpm);
  return ctx;
}

TEST(Obstacles, ACeilingAddsTheImageLawsThrustRotorByRotor) {
  const TruthParams truth = paperTruth();
  const RotorGeometry g = truth.rotorGeometry();
  const double n = 9000.0;
  ProximityContribution c(truth, slab(1.15));
  const Wrench w = c.wrench(hoverAt(Eigen::Vector3d(0, 0, 1.0), n));
  double expected = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    const double d = 1.15 - (1.0 + g.position_B[i].z());
    const double k = g.radius_m / (4.0 * d);
    expected += g.k_T_N_per_rpm2[i] * n * n * (1.0 / (1.0 - k * k) - 1.0);
  }
  EXPECT_GT(expected, 0.0);
  EXPECT_NEAR(w.force_B.z(), expected, 1e-9 * expected);
  EXPECT_NEAR(w.force_B.head<2>().norm(), 0.0, 1e-12);
  // Far from every box: nothing.
  const Wrench far = c.wrench(hoverAt(Eigen::Vector3d(0, 0, -30.0), n));
  EXPECT_LT(far.force_B.norm(), 1e-4 * expected);
}

TEST(Obstacles, AWallPullsTheVehicleTowardIt) {
  const TruthParams truth = paperTruth();
  const RotorGeometry g = truth.rotorGeometry();
  const double n = 9000.0;
  const double y_wall = 0.45;
  ProximityContribution c(truth, std::make_shared<const Obstacles>(std::vector<Box>{
                                     boxFromCorners(Eigen::Vector3d(-5, y_wall, -5), Eigen::Vector3d(5, y_wall + 0.2, 5))}));
  const Wrench w = c.wrench(hoverAt(Eigen::Vector3d(0, 0, 1.0), n));
  double expected = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    const double d = y_wall - g.position_B[i].y();
    expected += g.k_T_N_per_rpm2[i] * n * n * g.radius_m * g.radius_m / (32.0 * d * d);
  }
  EXPECT_NEAR(w.force_B.y(), expected, 1e-9 * expected);
  EXPECT_NEAR(w.force_B.z(), 0.0, 1e-12);
  EXPECT_NEAR(w.force_B.x(), 0.0, 1e-12);
}

TEST(Obstacles, APartialCeilingTiltsTheVehicleTowardIt) {
  // The ceiling covers x > 0 only: the front rotors gain thrust and lift the front (τ_y < 0),
  // the way partial ground effect lifts the side over the table.
  const TruthParams truth = paperTruth();
  ProximityContribution c(truth, slab(1.15, 0.0, 5.0));
  const Wrench w = c.wrench(hoverAt(Eigen::Vector3d(0, 0, 1.0), 9000.0));
  EXPECT_GT(w.force_B.z(), 0.0);
  EXPECT_LT(w.torque_B.y(), 0.0);
}

TEST(Obstacles, ARotorRimInsideABoxIsAStrike) {
  const TruthParams truth = paperTruth();
  Plant plant(truth, std::make_shared<FlatGround>(0.0));
  plant.setObstacles(slab(1.15));
  EXPECT_THROW(plant.setObstacles(slab(2.0)), std::logic_error);
  PlantState x;
  x.p_W = Eigen::Vector3d(0, 0, 1.16);  // the rotor plane inside the slab
  const auto crash = obstacleStrike(*plant.obstacles(), truth, x.p_W, Eigen::Matrix3d::Identity(), 0.5, rimUnitCircle(8));
  ASSERT_TRUE(crash);
  EXPECT_TRUE(crash->obstacle);
  EXPECT_EQ(crash->part, StrikePart::kRotorDisc);
  EXPECT_NE(describe(*crash).find("struck an obstacle"), std::string::npos);
  EXPECT_FALSE(obstacleStrike(*plant.obstacles(), truth, Eigen::Vector3d(0, 0, 1.0), Eigen::Matrix3d::Identity(), 0.5, rimUnitCircle(8)));
}

TEST(Obstacles, APlantUnderACeilingIsPulledIntoIt) {
  // Two plants with the same throttles at 1 m, one 0.1 m under a ceiling: the one under it
  // accelerates upward by the contribution's force over the mass at once, and climbs into the
  // ceiling, which ends its flight.
  const TruthParams truth = paperTruth();
  PlantState x0;
  x0.p_W = Eigen::Vector3d(0, 0, 1.0);
  const double n_hover = std::sqrt(truth.mass_kg * truth.gravity_mps2 / (4.0 * truth.k_T_N_per_rpm2));
  x0.n_rpm.fill(n_hover);
  Plant open(truth, std::make_shared<FlatGround>(0.0), PlantConfig{}, x0);
  Plant under(truth, std::make_shared<FlatGround>(0.0), PlantConfig{}, x0);
  const auto ceiling = slab(1.1);
  under.setObstacles(ceiling);
  std::array<double, 4> thr{};
  thr.fill(open.throttleForSteadySpeed(n_hover));
  (void)open.step(thr);
  (void)under.step(thr);
  ProximityContribution c(truth, ceiling);
  const double pull = c.wrench(hoverAt(under.centreOfMassState().p_W, n_hover)).force_B.z() / truth.mass_kg;
  EXPECT_GT(pull, 0.05);
  EXPECT_NEAR(under.state().a_W.z() - open.state().a_W.z(), pull, 0.02 * pull);
  bool struck = false;
  for (int k = 0; k < 3000 && !struck; ++k) struck = under.step(thr).crash.has_value();
  ASSERT_TRUE(struck);
  EXPECT_TRUE(under.crash()->obstacle);
}

TEST(BeamRanger, AnUpwardBeamReadsTheCeilingWithItsNoise) {
  const auto o = slab(1.3);
  BeamRangerParams p;  // up, 50 Hz
  p.outlier_probability = 0.0;
  BeamRanger r(p, 7, 0);
  PlantState x;
  x.p_W = Eigen::Vector3d(0, 0, 1.0);
  double sum = 0.0;
  double sum2 = 0.0;
  int n = 0;
  for (int k = 0; k < 20000; ++k) {
    x.t_s = k * 1e-3;
    if (const auto b = r.sample(x, o.get(), nullptr)) {
      ASSERT_TRUE(b->valid);
      sum += b->range_m;
      sum2 += b->range_m * b->range_m;
      ++n;
    }
  }
  EXPECT_EQ(n, 1000);  // 20 s at 50 Hz
  const double mean = sum / n;
  const double sd = std::sqrt(sum2 / n - mean * mean);
  const double sigma = p.noise_floor_m + p.noise_fraction * 0.3;
  EXPECT_NEAR(mean, 0.3, 4.0 * sigma / std::sqrt(n));
  EXPECT_NEAR(sd, sigma, 0.1 * sigma);
  // No obstacle: no return.
  BeamRanger empty(p, 7, 0);
  x.t_s = 0.0;
  const auto b = empty.sample(x, nullptr, nullptr);
  ASSERT_TRUE(b);
  EXPECT_FALSE(b->valid);
}

TEST(BeamRanger, AGrazingBeamHasNoReturn) {
  const auto o = slab(1.3);
  BeamRangerParams p;
  p.outlier_probability = 0.0;
  const double th = 85.0 * model::kDegToRad;  // beyond the 80° incidence limit
  p.direction_B = Eigen::Vector3d(std::sin(th), 0.0, std::cos(th));
  BeamRanger r(p, 7, 0);
  PlantState x;
  x.p_W = Eigen::Vector3d(0, 0, 1.0);
  const auto b = r.sample(x, o.get(), nullptr);
  ASSERT_TRUE(b);
  EXPECT_FALSE(b->valid);
  BeamRangerParams bad = p;
  bad.direction_B = Eigen::Vector3d(0, 0, 2);
  EXPECT_FALSE(bad.validate().empty());
}

}  // namespace
}  // namespace geaware::sim
