// SPDX-License-Identifier: BSD-3-Clause
// Disturbances: the turbulence intensity law, turbulence statistics near and far from the
// ground, its Contribution interface, wind (mean and gusts), determinism, validation.
#include "geaware/sim/disturbances.hpp"

#include <cmath>
#include <limits>
#include <memory>

#include <gtest/gtest.h>

#include "geaware/model/vehicle_model.hpp"
#include "geaware/sim/terrains.hpp"
#include "geaware/sim/truth_params.hpp"
#include "geaware_test/eigen_matchers.hpp"
#include "geaware_test/paper_vehicle.hpp"

namespace geaware::sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::array<double, 4> all(double h) { return {h, h, h, h}; }

TEST(TurbulenceIntensity, OneAtTheGroundZeroFromTheCutoffDecreasingBetween) {
  const GroundTurbulenceParams p;  // h_s = 0.15 m, h_max = 2 m
  EXPECT_DOUBLE_EQ(turbulenceIntensity(p, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(turbulenceIntensity(p, -0.05), 1.0);
  EXPECT_EQ(turbulenceIntensity(p, 2.0), 0.0);
  EXPECT_EQ(turbulenceIntensity(p, 5.0), 0.0);
  EXPECT_EQ(turbulenceIntensity(p, kInf), 0.0);
  EXPECT_EQ(turbulenceIntensity(p, std::nan("")), 0.0);
  const double f_max = 0.0225 / (4.0 + 0.0225);
  EXPECT_NEAR(turbulenceIntensity(p, 0.15), (0.5 - f_max) / (1 - f_max), 1e-12);
  EXPECT_NEAR(turbulenceIntensity(p, 0.12), 0.61, 0.01);  // the values documented in the header
  EXPECT_NEAR(turbulenceIntensity(p, 0.3), 0.20, 0.01);
  EXPECT_NEAR(turbulenceIntensity(p, 1.0), 0.017, 0.001);
  double last = 1.0;
  for (double h = 0.01; h < 2.0; h += 0.01) {
    const double s = turbulenceIntensity(p, h);
    EXPECT_LT(s, last) << h;
    EXPECT_GT(s, 0.0) << h;
    last = s;
  }
}

TEST(GroundTurbulence, StrongerNearTheGroundThanAtOneMetreAndZeroFarAway) {
  // 200 s at 1 kHz, τ_c = 20 ms: ≈ 5,000 correlation times, std error of a std ≈ 1 %; the std
  // at each height must be s(h)·σ within 6 %.
  const GroundTurbulenceParams p;
  GroundTurbulence turb(p, 8);
  const PlantState state;
  constexpr int kN = 200'000;
  Eigen::Array3d f_low = Eigen::Array3d::Zero(), t_low = Eigen::Array3d::Zero(), f_high = Eigen::Array3d::Zero();
  for (int k = 0; k < kN; ++k) {
    turb.beginStep(k * 1e-3, 1e-3, state);
    const Wrench low = turb.wrenchAt(all(0.12));
    const Wrench high = turb.wrenchAt(all(1.0));
    const Wrench far = turb.wrenchAt(all(3.0));
    f_low += low.force_B.array().square();
    t_low += low.torque_B.array().square();
    f_high += high.force_B.array().square();
    ASSERT_EQ(far.force_B, Eigen::Vector3d::Zero());
    ASSERT_EQ(far.torque_B, Eigen::Vector3d::Zero());
    ASSERT_EQ(turb.wrenchAt(all(kInf)).force_B, Eigen::Vector3d::Zero());
  }
  const double s_low = turbulenceIntensity(p, 0.12);
  const double s_high = turbulenceIntensity(p, 1.0);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(std::sqrt(f_low[i] / kN) / (s_low * p.force_std_N[i]), 1.0, 0.06) << "axis " << i;
    EXPECT_NEAR(std::sqrt(t_low[i] / kN) / (s_low * p.torque_std_Nm[i]), 1.0, 0.06) << "axis " << i;
    EXPECT_NEAR(std::sqrt(f_high[i] / kN) / (s_high * p.force_std_N[i]), 1.0, 0.06) << "axis " << i;
    EXPECT_GT(f_low[i], 100.0 * f_high[i]);  // (0.61/0.017)² ≈ 1,300
  }
}

TEST(GroundTurbulence, AsAContributionItUsesEachRotorsDistance) {
  GroundTurbulence turb(GroundTurbulenceParams{}, 3);
  turb.beginStep(0.0, 1e-3, PlantState{});
  ContributionContext ctx;
  ctx.surroundings.ground_distance_m = {0.1, 0.1, kInf, kInf};  // half over a table edge
  const Wrench w = turb.wrench(ctx);
  EXPECT_MATRIX_NEAR(w.force_B, turb.wrenchAt(all(0.1)).force_B * 0.5, 1e-15);
  EXPECT_MATRIX_NEAR(w.torque_B, turb.wrenchAt(all(0.1)).torque_B * 0.5, 1e-15);
  EXPECT_STREQ(turb.name(), "ground_turbulence");
  // Held over the step: the RK4 stages see the same noise.
  EXPECT_EQ(turb.wrench(ctx).force_B, w.force_B);
}

TEST(GroundTurbulence, DeterministicPerSeed) {
  GroundTurbulence a(GroundTurbulenceParams{}, 5), b(GroundTurbulenceParams{}, 5), c(GroundTurbulenceParams{}, 6);
  int differ = 0;
  for (int k = 0; k < 100; ++k) {
    a.beginStep(k * 1e-3, 1e-3, PlantState{});
    b.beginStep(k * 1e-3, 1e-3, PlantState{});
    c.beginStep(k * 1e-3, 1e-3, PlantState{});
    EXPECT_EQ(a.wrenchAt(all(0.1)).force_B, b.wrenchAt(all(0.1)).force_B);
    differ += a.wrenchAt(all(0.1)).force_B != c.wrenchAt(all(0.1)).force_B;
  }
  EXPECT_EQ(differ, 100);
}

TEST(GroundTurbulence, InAPlantItShakesTheVehicleNearTheGroundOnly) {
  // Only the turbulence acts (gravity, rotors and motor torques off): a vehicle held at rest
  // 0.12 m above the ground drifts and spins; at 3 m it stays exactly where it is.
  PlantConfig cfg;
  cfg.gravity = false;
  cfg.rotor_aerodynamics = false;
  cfg.motor_reaction = false;
  cfg.gyroscopic = false;
  cfg.ground_strikes = false;
  const TruthParams truth = fromNominal(geaware_test::paperParams());
  for (double h : {0.12, 3.0}) {
    PlantState s0;
    s0.p_W = Eigen::Vector3d(0.0, 0.0, h);
    Plant plant(truth, std::make_shared<FlatGround>(0.0), cfg, s0);
    plant.addContribution(std::make_unique<GroundTurbulence>(GroundTurbulenceParams{}, 4));
    for (int k = 0; k < 500; ++k) (void)plant.step({0.0, 0.0, 0.0, 0.0});
    if (h < 1.0) {
      EXPECT_GT(plant.state().v_W.norm(), 1e-3);
      EXPECT_GT(plant.state().w_B.norm(), 1e-2);
    } else {
      EXPECT_EQ(plant.state().v_W, Eigen::Vector3d::Zero());
      EXPECT_EQ(plant.state().w_B, Eigen::Vector3d::Zero());
    }
  }
}

TEST(Wind, SteadyWindIsTheConfiguredAirVelocity) {
  WindParams p;
  p.mean_W_mps = Eigen::Vector3d(2.0, -1.0, 0.0);
  Wind wind(p, 1);
  EXPECT_EQ(wind.velocity_W(), p.mean_W_mps);
  for (int k = 0; k < 1000; ++k) ASSERT_EQ(wind.advance(1e-3), p.mean_W_mps);
}

TEST(Wind, GustsAddZeroMeanNoiseOfTheConfiguredStd) {
  // T = 0.5 s, 2,000 s at 10 ms: ≈ 4,000 correlation times, std error of the std ≈ 1.1 %
  // (allow 6 %), of the mean 1.6 % of σ (allow 8 %).
  WindParams p;
  p.mean_W_mps = Eigen::Vector3d(3.0, 0.0, 0.0);
  p.gust_std_mps = Eigen::Vector3d(1.0, 0.5, 0.2);
  p.gust_correlation_time_s = 0.5;
  Wind wind(p, 2);
  constexpr int kN = 200'000;
  Eigen::Array3d s1 = Eigen::Array3d::Zero(), s2 = Eigen::Array3d::Zero();
  for (int k = 0; k < kN; ++k) {
    const Eigen::Array3d e = (wind.advance(0.01) - p.mean_W_mps).array();
    s1 += e;
    s2 += e.square();
  }
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(s1[i] / kN / p.gust_std_mps[i], 0.0, 0.08) << "axis " << i;
    EXPECT_NEAR(std::sqrt(s2[i] / kN) / p.gust_std_mps[i], 1.0, 0.06) << "axis " << i;
  }
}

TEST(Disturbances, ValidationNamesTheFields) {
  GroundTurbulenceParams t;
  t.force_std_N.x() = -1.0;
  t.correlation_time_s = 0.0;
  auto e = t.validate();
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].field, "force_std_N");
  EXPECT_EQ(e[1].field, "correlation_time_s");
  EXPECT_THROW(GroundTurbulence(t, 1), model::InvalidParameters);
  WindParams w;
  w.mean_W_mps.z() = std::nan("");
  e = w.validate();
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].field, "mean_W_mps");
  EXPECT_THROW(Wind(w, 1), model::InvalidParameters);
}

}  // namespace
}  // namespace geaware::sim
