// SPDX-License-Identifier: BSD-3-Clause
// The stepped world against the in-process runner: fed, tick by tick, the throttles a
// runFlight() of the same scenario commanded, it must give that flight's truth bit for bit (same
// start, same disturbance and sensor streams, same order of sensing and stepping), in the
// as-built world with every disturbance on; and it refuses what it does not fly.

#include "geaware/experiments/stepped_world.hpp"

#include <array>
#include <memory>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "geaware/experiments/world_setup.hpp"
#include "test_scenarios.hpp"

namespace geaware::experiments {
namespace {

struct Recorded {
  std::vector<std::array<double, 4>> throttle;
  std::vector<sim::PlantState> truth;
};

class Recorder final : public FlightObserver {
 public:
  explicit Recorder(Recorded& r) : r_(r) {}
  void onTick(const FlightTick& k) noexcept override {
    r_.throttle.push_back(k.throttle);
    r_.truth.push_back(k.truth);
  }

 private:
  Recorded& r_;
};

FlightScenario asBuiltWithEverything(std::uint64_t seed) {
  FlightScenario s = test::scenario(0.12, control::AccelerationCompensation::kModel,
                                    control::TorqueCompensation::kModelIndi);
  applyWorld(s, defaultWorld(s.vehicle, true, ""));
  EXPECT_TRUE(control::parseConfiguration("recommended", s.controller));
  s.disturbances.turbulence = true;
  s.disturbances.unsteadiness = true;
  s.disturbances.wind = true;
  s.seed = seed;
  return s;
}

TEST(SteppedWorld, FedTheRunnersThrottlesItReproducesTheRunnersTruthBitForBit) {
  const FlightScenario s = asBuiltWithEverything(11);
  Recorded flown;
  Recorder recorder(flown);
  const FlightResult r = runFlight(s, &recorder);
  ASSERT_TRUE(r.completed) << r.crash_description;
  ASSERT_GT(flown.throttle.size(), 1000u);

  SteppedWorld w(s);
  std::size_t tick = 0;
  for (;;) {
    (void)w.sense();
    if (w.controlTickDue()) {
      ASSERT_LT(tick, flown.truth.size());
      const sim::PlantState& a = w.truth();
      const sim::PlantState& b = flown.truth[tick];
      ASSERT_EQ(a.t_s, b.t_s) << "tick " << tick;
      for (int i = 0; i < 3; ++i) {
        ASSERT_EQ(a.p_W[i], b.p_W[i]) << "tick " << tick << " p[" << i << "]";
        ASSERT_EQ(a.v_W[i], b.v_W[i]) << "tick " << tick << " v[" << i << "]";
        ASSERT_EQ(a.w_B[i], b.w_B[i]) << "tick " << tick << " w[" << i << "]";
      }
      ASSERT_EQ(a.q_WB.coeffs(), b.q_WB.coeffs()) << "tick " << tick;
      ASSERT_EQ(a.n_rpm, b.n_rpm) << "tick " << tick;
      w.setThrottle(flown.throttle[tick]);
      ++tick;
    }
    if (w.lastStep()) break;
    ASSERT_TRUE(w.step()) << "struck at t = " << w.time_s() << " s";
  }
  EXPECT_EQ(tick, flown.truth.size());
  const FlightResult again = w.finish(0.0);
  EXPECT_TRUE(again.completed);
  EXPECT_EQ(again.control_ticks, r.control_ticks);
  EXPECT_EQ(again.tracking.rmse_all_m, r.tracking.rmse_all_m);
  EXPECT_EQ(again.tracking.samples, r.tracking.samples);
  EXPECT_EQ(again.simulated_s, r.simulated_s);
}

TEST(SteppedWorld, ADifferentSeedIsADifferentFlight) {
  const FlightScenario a = asBuiltWithEverything(11);
  const FlightScenario b = asBuiltWithEverything(12);
  SteppedWorld wa(a);
  SteppedWorld wb(b);
  for (int k = 0; k < 200; ++k) {
    (void)wa.sense();
    (void)wb.sense();
    ASSERT_TRUE(wa.step());
    ASSERT_TRUE(wb.step());
  }
  EXPECT_NE(wa.truth().p_W, wb.truth().p_W);
}

TEST(SteppedWorld, CutThrottlesStrikeTheGroundAndEndTheFlight) {
  const FlightScenario s = asBuiltWithEverything(3);
  SteppedWorld w(s);
  bool struck = false;
  for (int k = 0; k < 20000 && !struck; ++k) {
    (void)w.sense();
    if (w.controlTickDue()) w.setThrottle({0.0, 0.0, 0.0, 0.0});
    struck = !w.step();
  }
  ASSERT_TRUE(struck);
  EXPECT_TRUE(w.crashed());
  EXPECT_FALSE(w.step()) << "a struck flight does not step again";
  const FlightResult r = w.finish(0.0);
  EXPECT_FALSE(r.completed);
  EXPECT_FALSE(r.crash_description.empty());
}

TEST(SteppedWorld, RefusesFaultsOpenLoopAndInvalidScenarios) {
  FlightScenario open = asBuiltWithEverything(1);
  open.loop = LoopMode::kOpenLoopHover;
  EXPECT_THROW(SteppedWorld{open}, std::invalid_argument);
  FlightScenario faulty = asBuiltWithEverything(1);
  faulty.faults.push_back(Fault{});
  EXPECT_THROW(SteppedWorld{faulty}, std::invalid_argument);
  FlightScenario bad = asBuiltWithEverything(1);
  bad.plant_rate_hz = -1.0;
  EXPECT_THROW(SteppedWorld{bad}, InvalidScenario);
  // Obstacles (a ceiling far overhead) would fly without their effects, strikes or rangers.
  FlightScenario roofed = asBuiltWithEverything(1);
  roofed.obstacles = std::make_shared<const sim::Obstacles>(std::vector<sim::Box>{
      sim::boxFromCorners(Eigen::Vector3d(-50, -50, 20), Eigen::Vector3d(50, 50, 21), 0.0, "roof")});
  EXPECT_THROW(SteppedWorld{roofed}, std::invalid_argument);
}

}  // namespace
}  // namespace geaware::experiments
