// SPDX-License-Identifier: BSD-3-Clause
// F_G learned in flight (issue 13 item 3) in the as-built world: `recommended+learn0` starts
// from no ground-effect model at all and descends slowly from 1.2 m to 0.1 m; what it has
// learned by the end is compared with the truth's own in-flight curve (the as-built
// aerodynamics, thrust at h over thrust far from the ground, level and at rest). The same
// flight without learning, and the paper's configuration rows, are untouched (the learner is
// off unless the configuration says "+learn"). The leveling torque's scale, learned with F_G, is
// compared with the truth's own ground torque on the states flown (at the end).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "geaware/control/controller.hpp"
#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/flight_setup.hpp"
#include "geaware/experiments/world_setup.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "geaware/model/ground_effect.hpp"
#include "geaware/model/vehicle_model.hpp"
#include "geaware/sim/plant.hpp"
#include "geaware/sim/rotor_aerodynamics.hpp"
#include "geaware/sim/terrains.hpp"

namespace geaware::experiments {
namespace {

/// The truth's F_G in flight at height h of the rotor plane: level, at rest, one rotor speed.
double truthRatio(const sim::TruthParams& truth, double h_m) {
  const sim::RotorGeometry geometry = truth.rotorGeometry();
  const sim::RotorAerodynamics aero(geometry, truth.aero);
  const sim::FlatGround ground(0.0);
  const auto thrustAt = [&](double h) {
    const Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    const Eigen::Vector3d p_com = Eigen::Vector3d(0.0, 0.0, h) + truth.cog_offset_B;
    const sim::RotorSurroundings around = sim::rotorSurroundings(&ground, p_com, R, geometry.position_B);
    return aero.compute({9000.0, 9000.0, 9000.0, 9000.0}, R, Eigen::Vector3d::Zero(),
                        Eigen::Vector3d::Zero(), aero.flightFactors(around.ground_distance_m))
        .wrench.force_B.z();
  };
  return thrustAt(h_m) / thrustAt(50.0) - 1.0;
}

FlightScenario descent(const std::string& controller) {
  FlightScenario s;
  s.vehicle = io::builtinVehicle();
  applyWorld(s, defaultWorld(s.vehicle, true, ""));
  EXPECT_TRUE(control::parseConfiguration(controller, s.controller));
  TrajectoryOptions t;
  t.lemniscate = false;
  t.from_height_m = 1.2;
  t.height_m = 0.1;
  t.speed_mps = 0.05;  // 22 s of descent
  s.trajectory = makeTrajectory(t);
  s.seed = 4;
  return s;
}

/// The 1 m/s, ±1.5 × ±0.8 m lemniscate from `height_m` (rising by `swing_m` mid-lap), as built
/// or in the ideal world.
FlightScenario lemniscateFlight(const std::string& controller, double height_m, double swing_m,
                                int laps, std::uint64_t seed, bool as_built = true) {
  FlightScenario s;
  s.vehicle = io::builtinVehicle();
  applyWorld(s, defaultWorld(s.vehicle, as_built, ""));
  EXPECT_TRUE(control::parseConfiguration(controller, s.controller));
  TrajectoryOptions t;
  t.height_m = height_m;
  t.height_swing_m = swing_m;
  t.speed_mps = 1.0;
  t.extent_x_m = 1.5;
  t.extent_y_m = 0.8;
  t.laps = laps;
  s.trajectory = makeTrajectory(t);
  s.seed = seed;
  return s;
}

TEST(LearningFlight, FromNoModelTheLearnedCurveIsTheTruthsWithin15PercentOver10To30cm) {
  const FlightScenario s = descent("recommended+learn0");
  ASSERT_EQ(s.controller.learn_ground_effect, control::GroundEffectLearning::kFromNothing);
  const FlightResult r = runFlight(s);
  ASSERT_TRUE(r.completed) << r.crash_description;
  ASSERT_TRUE(s.truth.has_value());
  ASSERT_TRUE(r.learned_ground_effect.has_value());
  const LearnedGroundEffect& learned = *r.learned_ground_effect;
  EXPECT_GT(learned.samples, 1000u);
  for (double h = 0.10; h <= 0.30 + 1e-9; h += 0.02) {
    const double truth = truthRatio(*s.truth, h);
    EXPECT_NEAR(learned.ratio(h), truth, 0.15 * truth) << "h = " << h << " m";
  }
  // Tracking: no worse than with the vehicle file's F_G (the paper's curve, not the truth's).
  const FlightResult file = runFlight(descent("recommended"));
  ASSERT_TRUE(file.completed) << file.crash_description;
  EXPECT_LE(r.tracking.rmse_all_m, 1.2 * file.tracking.rmse_all_m);
}

// The paper's configuration flies the same descent into the ground (the as-built world's F_G
// is not the vehicle file's); learning F_G from nothing in flight, it lands in its final hover.
TEST(LearningFlight, ThePapersConfigurationLearningFromNothingFinishesTheDescent) {
  const FlightResult paper = runFlight(descent("model:model_indi"));
  const FlightResult learning = runFlight(descent("model:model_indi+learn0"));
  EXPECT_FALSE(paper.completed);
  ASSERT_TRUE(learning.completed) << learning.crash_description;
  EXPECT_LT(learning.tracking.rmse_z_m, 0.02);
}

// Poor excitation: a lemniscate at one height (0.12 m), learning from the vehicle file. Knots
// far from 0.12 m keep the vehicle file's values where they lie below what was learned there,
// and tracking is not worse than without learning.
TEST(LearningFlight, AtOneHeightTheCurveElsewhereDoesNotDriftAndTrackingIsNoWorse) {
  const auto lemniscate = [](const std::string& controller) {
    return lemniscateFlight(controller, 0.12, 0.0, 1, 2);
  };
  const FlightScenario s = lemniscate("recommended+learn");
  const FlightResult r = runFlight(s);
  const FlightResult fixed = runFlight(lemniscate("recommended"));
  ASSERT_TRUE(r.completed) << r.crash_description;
  ASSERT_TRUE(fixed.completed) << fixed.crash_description;
  ASSERT_TRUE(r.learned_ground_effect.has_value());
  const LearnedGroundEffect& g = *r.learned_ground_effect;
  const model::VehicleModel vehicle(s.vehicle);
  // Knots the vehicle never reached are not learned, never raised above the file's curve, and
  // lowered only as far as the curve must fall from what was learned at 0.12 m (F_G does not
  // grow away from the ground).
  const double at_flight_height = g.ratio(0.12);
  for (std::size_t k = 0; k < g.heights_m.size(); ++k) {
    if (k + 1 < g.heights_m.size()) {
      EXPECT_GE(g.f_g[k], g.f_g[k + 1]) << k;
    }
    if (g.heights_m[k] < 0.2) continue;
    const double file = vehicle.groundEffect().thrustRatio(g.heights_m[k]);
    EXPECT_FALSE(g.learned[k]) << g.heights_m[k];
    EXPECT_LE(g.f_g[k], file + 1e-12) << "knot " << g.heights_m[k] << " m";
    EXPECT_GE(g.f_g[k], std::min(file, at_flight_height) - 1e-12) << "knot " << g.heights_m[k] << " m";
    if (file <= at_flight_height) {
      EXPECT_NEAR(g.f_g[k], file, 2e-3) << "knot " << g.heights_m[k] << " m";
    }
  }
  EXPECT_LE(r.tracking.rmse_all_m, 1.05 * fixed.tracking.rmse_all_m);
  EXPECT_GT(g.samples, 1000u);
}

/// Tracking error (reference vs true position) over the trajectory time [from_s, to_s].
class WindowRms final : public FlightObserver {
 public:
  WindowRms(double from_s, double to_s) : from_s_(from_s), to_s_(to_s) {}
  void onTick(const FlightTick& tick) noexcept override {
    if (!tick.in_trajectory || tick.t_traj_s < from_s_ || tick.t_traj_s > to_s_) return;
    sum_ += (tick.input.reference.p_W - tick.truth.p_W).squaredNorm();
    ++n_;
  }
  [[nodiscard]] double rms() const { return n_ == 0 ? std::nan("") : std::sqrt(sum_ / static_cast<double>(n_)); }

 private:
  double from_s_, to_s_, sum_ = 0.0;
  long n_ = 0;
};

// Issue 13 item 3's scenario: two laps of the 1 m/s lemniscate whose height sweeps 0.1–0.3 m
// (0.1 m at the start and at each lap's end, 0.3 m mid-lap), `recommended+learn0` starting from
// no ground-effect model at all against `recommended` with the vehicle file's (platform) F_G.
// On the second lap it tracks within 1.2× of the file's model, and its learned curve is the
// truth's in-flight one within 15 % over 0.1–0.3 m.
TEST(LearningFlight, TwoSweepingLapsFromNoModelTrackAsThePlatformModelOnTheSecond) {
  const auto laps = [](const std::string& controller) {
    return lemniscateFlight(controller, 0.10, 0.20, 2, 5);
  };
  const FlightScenario s = laps("recommended+learn0");
  const double half = 0.5 * s.trajectory->duration();  // the phase profile is symmetric
  WindowRms learning_lap2(half, 2.0 * half);
  const FlightResult r = runFlight(s, &learning_lap2);
  WindowRms file_lap2(half, 2.0 * half);
  const FlightResult file = runFlight(laps("recommended"), &file_lap2);
  ASSERT_TRUE(r.completed) << r.crash_description;
  ASSERT_TRUE(file.completed) << file.crash_description;
  EXPECT_LE(learning_lap2.rms(), 1.2 * file_lap2.rms());
  ASSERT_TRUE(r.learned_ground_effect.has_value());
  const LearnedGroundEffect& learned = *r.learned_ground_effect;
  for (double h = 0.10; h <= 0.30 + 1e-9; h += 0.02) {
    const double truth = truthRatio(*s.truth, h);
    EXPECT_NEAR(learned.ratio(h), truth, 0.15 * truth) << "h = " << h << " m";
  }
  RecordProperty("lap2_rmse_learn0_cm", std::to_string(100.0 * learning_lap2.rms()));
  RecordProperty("lap2_rmse_file_cm", std::to_string(100.0 * file_lap2.rms()));
}

// The learner is off unless the configuration asks for it: no curve in the result, and the
// names round-trip.
TEST(LearningFlight, OffByDefaultAndNamedInTheConfiguration) {
  control::ControllerParams p;
  ASSERT_TRUE(control::parseConfiguration("recommended", p));
  EXPECT_EQ(p.learn_ground_effect, control::GroundEffectLearning::kOff);
  ASSERT_TRUE(control::parseConfiguration("model:model_indi+learn0", p));
  EXPECT_EQ(p.learn_ground_effect, control::GroundEffectLearning::kFromNothing);
  EXPECT_EQ(control::configurationName(p), "model:model_indi+learn0");
  ASSERT_TRUE(control::parseConfiguration("recommended+learn", p));
  EXPECT_EQ(control::configurationName(p), "recommended+learn");
  EXPECT_FALSE(control::parseConfiguration("recommended+learn1", p));
  EXPECT_FALSE(control::parseConfiguration("+learn", p));
  control::ControllerParams indi;
  ASSERT_TRUE(control::parseConfiguration("indi:indi+learn", indi));
  EXPECT_FALSE(indi.validate().empty()) << "learning needs acceleration 'model'";
  const FlightResult r = runFlight(descent("recommended"));
  EXPECT_FALSE(r.learned_ground_effect.has_value());
}


// The leveling torque's scale, learned with F_G. The truth has no M_G: its leveling torque comes
// out of the rotors' thrust differences (docs/sim-aerodynamics.md), and its shape in h is not the
// vehicle file's. What a scale on the file's shape can get right is the truth's own ground torque
// on the states flown: at every tick the learner's gates pass, the truth's torque with the floor
// less the same 50 m up, regressed on the same regressor with the same biases. The learned scale
// is compared with that, in the as-built and the ideal worlds.

/// The truth's own ground torque on the flown states, regressed like the learner: the scale
/// s and body biases minimising Σ |τ_ground − s·x − b|² over the ticks the learner's gates pass.
class TruthLevelingFit final : public FlightObserver {
 public:
  TruthLevelingFit(const sim::TruthParams& truth, const model::VehicleParams& file)
      : truth_(truth), geometry_(truth.rotorGeometry()), aero_(geometry_, truth.aero), file_(file),
        gear_m_(file.min_rotor_plane_height_m) {}
  void onTick(const FlightTick& tick) noexcept override {
    if (!tick.controller_active || !tick.in_trajectory) return;
    const sim::PlantState& st = tick.truth;
    const Eigen::Matrix3d R = st.q_WB.toRotationMatrix();
    const double h = tick.true_height_m;
    if (h <= gear_m_ + 0.01 || st.v_W.head<2>().norm() > 1.5 || std::abs(st.v_W.z()) > 0.5) return;
    const auto wrench = [&](double lift) {
      const Eigen::Vector3d p_com = st.p_W + Eigen::Vector3d(0.0, 0.0, lift) + R * truth_.cog_offset_B;
      const sim::RotorSurroundings around = sim::rotorSurroundings(&ground_, p_com, R, geometry_.position_B);
      return aero_.compute(st.n_rpm, R, st.v_W, st.w_B, aero_.flightFactors(around.ground_distance_m)).wrench;
    };
    const auto near = wrench(0.0);
    const auto far = wrench(50.0);
    const Eigen::Vector3d tau = near.torque_B - far.torque_B;
    const Eigen::Vector3d x =
        R.transpose() * (file_.levelingShape(h) * far.force_B.z() * R.col(2).cross(Eigen::Vector3d::UnitZ()));
    if (x.head<2>().norm() < 0.004) return;
    for (int a = 0; a < 2; ++a) {
      Eigen::Vector3d phi(x(a), a == 0 ? 1.0 : 0.0, a == 1 ? 1.0 : 0.0);
      A_ += phi * phi.transpose();
      c_ += phi * tau(a);
    }
  }
  [[nodiscard]] double scale() const { return A_.ldlt().solve(c_)(0); }

 private:
  const sim::TruthParams& truth_;
  sim::RotorGeometry geometry_;
  sim::RotorAerodynamics aero_;
  model::GroundEffectModel file_;
  double gear_m_;
  sim::FlatGround ground_{0.0};
  Eigen::Matrix3d A_ = Eigen::Matrix3d::Zero();
  Eigen::Vector3d c_ = Eigen::Vector3d::Zero();
};

// Two laps sweeping 0.1–0.3 m from no model at all: the scale is learned, within 15 % of the
// truth's own on the states flown, in both worlds.
TEST(LevelingFlight, TwoSweepingLapsLearnTheTruthsLevelingWithin15Percent) {
  for (const bool as_built : {true, false}) {
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
      const FlightScenario s = lemniscateFlight("recommended+learn0", 0.10, 0.20, 2, seed, as_built);
      TruthLevelingFit truth(*s.truth, s.vehicle);
      const FlightResult r = runFlight(s, &truth);
      ASSERT_TRUE(r.completed) << r.crash_description;
      ASSERT_TRUE(r.learned_ground_effect.has_value());
      const LearnedGroundEffect& g = *r.learned_ground_effect;
      const std::string world = as_built ? "as built" : "ideal";
      EXPECT_TRUE(g.leveling_learned) << world << ", seed " << seed;
      EXPECT_NEAR(g.leveling_scale, truth.scale(), 0.15 * truth.scale()) << world << ", seed " << seed;
      std::printf("%s, seed %d: learned scale %.3f (%llu samples), the truth's on the states flown %.3f\n",
                  world.c_str(), static_cast<int>(seed), g.leveling_scale,
                  static_cast<unsigned long long>(g.leveling_samples), truth.scale());
    }
  }
}

// A level descent from 1.2 m to 0.1 m tilts the vehicle too little to excite the scale: it is
// not learned, and the controller keeps its start (none with "+learn0", the file's with
// "+learn").
TEST(LevelingFlight, ALevelDescentLeavesTheScaleAtItsStart) {
  for (const auto& [controller, start] : {std::pair<std::string, double>{"model:model_indi+learn0", 0.0},
                                          std::pair<std::string, double>{"recommended+learn", 1.0}}) {
    const FlightScenario s = descent(controller);
    const FlightResult r = runFlight(s);
    ASSERT_TRUE(r.completed) << controller << ": " << r.crash_description;
    ASSERT_TRUE(r.learned_ground_effect.has_value());
    EXPECT_FALSE(r.learned_ground_effect->leveling_learned) << controller;
    EXPECT_EQ(r.learned_ground_effect->leveling_scale, start) << controller;
  }
}

}  // namespace
}  // namespace geaware::experiments
