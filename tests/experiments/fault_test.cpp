// SPDX-License-Identifier: BSD-3-Clause
// Faults injected into a flight (experiments/faults.hpp) and the flags they raise in the
// controller and the estimator; the fault suite's small variant.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "geaware/control/controller_params.hpp"
#include "geaware/experiments/fault_suite.hpp"
#include "geaware/experiments/flight.hpp"
#include "geaware/experiments/table_one.hpp"
#include "geaware/io/vehicle_file.hpp"
#include "test_scenarios.hpp"

namespace geaware::experiments {
namespace {

Fault make(FaultKind kind, double value, double start_s, double duration_s, int motor = 0) {
  Fault f;
  f.kind = kind;
  f.value = value;
  f.start_s = start_s;
  f.duration_s = duration_s;
  f.motor = motor;
  return f;
}

/// Counts ticks with pose-stale, the poses the estimator fused, and the throttle of motor 0.
class Recorder final : public FlightObserver {
 public:
  void onTick(const FlightTick& k) noexcept override {
    if ((k.eskf_flags & estimation::kEskfPoseStale) != 0) ++stale;
    if (k.fault_bits != 0) ++faulted;
    if ((k.output.flags & control::kFlagMotorFailure) != 0 && first_failure_t < 0.0) first_failure_t = k.t_traj_s;
    for (double t : k.throttle) finite = finite && std::isfinite(t) && t >= 0.0 && t <= 1.0;
  }
  int stale = 0;
  int faulted = 0;
  double first_failure_t = -1.0;
  bool finite = true;
};

TEST(Faults, ValidationNamesTheFaultAndField) {
  std::vector<Fault> f = {make(FaultKind::kMotorEffectiveness, 1.5, 1.0, 1.0, 0),
                          make(FaultKind::kMotorStop, 0.0, -1.0, 1.0, 7),
                          make(FaultKind::kGust, 2.0, 1.0, std::numeric_limits<double>::infinity())};
  const auto e = validate(f);
  ASSERT_EQ(e.size(), 4u);
  EXPECT_EQ(e[0].field, "faults[0].value");
  EXPECT_EQ(e[1].field, "faults[1].start_s");
  EXPECT_EQ(e[2].field, "faults[1].motor");
  EXPECT_EQ(e[3].field, "faults[2].duration_s");
  // And a scenario with such a fault is refused before it flies.
  FlightScenario s = test::scenario(1.0, control::AccelerationCompensation::kNone, control::TorqueCompensation::kIndi);
  s.faults = f;
  EXPECT_THROW((void)runFlight(s), InvalidScenario);
}

TEST(Faults, AGustRisesAndFallsOverItsDuration) {
  const FaultInjector inj({make(FaultKind::kGust, 2.0, 1.0, 2.0)}, 1, 3.0);
  EXPECT_EQ(inj.windAt(3.9).x(), 0.0);                  // before: plant time 3.9 = t_traj 0.9
  EXPECT_NEAR(inj.windAt(5.0).x(), 2.0, 1e-12);         // the peak at mid-gust
  EXPECT_NEAR(inj.windAt(4.5).x(), 1.0, 1e-12);         // 1 − cos at a quarter
  EXPECT_EQ(inj.windAt(6.0).x(), 0.0);                  // over
  EXPECT_EQ(inj.activeBits(5.0), 1u);
  EXPECT_EQ(inj.activeBits(6.5), 0u);
}

TEST(Faults, AMocapDropoutLeavesTheEstimatorDeadReckoningAndFlagged) {
  FlightScenario s = test::scenario(1.0, control::AccelerationCompensation::kNone, control::TorqueCompensation::kIndi);
  s.faults = {make(FaultKind::kMocapDropout, 0.0, 3.0, 1.0)};
  Recorder rec;
  const FlightResult r = runFlight(s, &rec);
  EXPECT_TRUE(r.completed);
  // 1 s without poses at 200 Hz: stale after 0.1 s, so ≈ 180 ticks flagged, and none outside.
  EXPECT_GT(rec.stale, 160);
  EXPECT_LT(rec.stale, 200);
  EXPECT_EQ(r.estimation.eskf_flag_ticks[0], static_cast<std::uint64_t>(rec.stale));
  EXPECT_NEAR(rec.faulted, 200, 2);
}

TEST(Faults, AStoppedMotorIsFlaggedAndTheMotorsAreCutWhenTheVehicleTips) {
  FlightScenario s = test::scenario(1.0, control::AccelerationCompensation::kModel, control::TorqueCompensation::kModelIndi);
  s.controller = control::recommendedControllerParams();
  s.faults = {make(FaultKind::kMotorStop, 0.0, 3.0, std::numeric_limits<double>::infinity(), 1)};
  Recorder rec;
  const FlightResult r = runFlight(s, &rec);
  EXPECT_TRUE(rec.finite);
  EXPECT_EQ(r.throttle_faults, 0);
  // Detected within 0.15 s of persistence plus the rotor's spin-down (a 30 ms motor).
  ASSERT_GE(rec.first_failure_t, 3.0);
  EXPECT_LT(rec.first_failure_t, 3.4);
  EXPECT_GT(r.flag_counts[9], 0u);
  // A quadrotor without a motor tips: the controller terminates (every throttle 0) and the
  // vehicle falls; the flight ends on the ground.
  EXPECT_GT(r.flag_counts[10], 0u);
  EXPECT_FALSE(r.completed);
}

TEST(Faults, AWeakMotorIsHeldByTheRotorSpeedLoopAndNotMistakenForAFailure) {
  FlightScenario s = test::scenario(1.0, control::AccelerationCompensation::kModel, control::TorqueCompensation::kModelIndi);
  s.controller = control::recommendedControllerParams();
  s.controller.rotor_speed_ki_per_s = 0.0;
  s.faults = {make(FaultKind::kMotorEffectiveness, 0.8, 3.0, std::numeric_limits<double>::infinity(), 2)};
  const FlightResult open = runFlight(s);  // the paper's open-loop throttle per motor
  s.controller.rotor_speed_ki_per_s = 15.0;
  const FlightResult closed = runFlight(s);
  EXPECT_TRUE(closed.completed);
  EXPECT_EQ(closed.flag_counts[9], 0u);  // 89 % of the speed asked is not "less than half"
  EXPECT_EQ(closed.flag_counts[10], 0u);
  EXPECT_LT(closed.tracking.rmse_all_m, 0.03);
  // Without the loop the motor's deficit is left to the attitude loop alone: tens of cm.
  EXPECT_GT(open.tracking.rmse_all_m, 5.0 * closed.tracking.rmse_all_m);
}

TEST(FaultSuite, RunsAndReportsEachCaseAgainstItsBaseline) {
  FaultSuiteOptions o;
  o.vehicle = io::builtinVehicle();
  std::vector<FaultCase> cases;
  for (const auto& c : faultCases()) {
    if (c.name == "none" || c.name == "mocap 0.5s" || c.name == "motor stop") cases.push_back(c);
  }
  o.cases = cases;
  traj::LemniscateParams at_1m = lemniscateFor(tableOneExperiment(1));
  at_1m.height_m = 1.0;
  o.conditions = {suiteCondition(at_1m, "lem-1m-1mps")};
  for (const char* name : {"indi:none", "model:model_indi", "recommended"}) {
    control::ControllerParams p;
    ASSERT_TRUE(control::parseConfiguration(name, p));
    o.controllers.push_back({control::configurationName(p), p});
  }
  o.seeds = 1;
  o.jobs = 2;
  const FaultSuiteResult r = runFaultSuite(o);
  ASSERT_EQ(r.cells.size(), 3u * 3u);
  for (const auto& c : r.cells) {
    EXPECT_EQ(c.non_finite_commands, 0) << c.cell.case_name << " " << c.cell.controller;
    if (c.cell.case_name == "none") {
      EXPECT_EQ(c.outcome, "finished") << c.cell.controller;
    }
    if (c.cell.case_name == "motor stop") {
      EXPECT_FALSE(c.survivable);
      EXPECT_NE(c.outcome.find("struck"), std::string::npos) << c.cell.controller;
    }
  }
  const io::Json j = faultSuiteJson(r);
  EXPECT_EQ(j["suite"], "faults");
  EXPECT_EQ(j["cells"].size(), 9u);
  EXPECT_TRUE(j["cells"][0].contains("rmse_all_cm"));
  EXPECT_TRUE(j["cells"][0].contains("outcome"));
  ASSERT_EQ(r.checks.size(), 2u);
  EXPECT_TRUE(r.checks[0].pass);
}

}  // namespace
}  // namespace geaware::experiments
