// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/experiments/tracking_metrics.hpp"
#include "geaware/experiments/flight_summary.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace {

using geaware::experiments::TrackingAccumulator;

TEST(TrackingMetrics, ClosedFormOnAHandfulOfErrors) {
  TrackingAccumulator acc;
  acc.add({0.03, 0.04, 0.0});  // ‖e‖ = 0.05
  acc.add({0.0, 0.0, -0.12});  // ‖e‖ = 0.12
  const auto m = acc.result();
  EXPECT_EQ(m.samples, 2u);
  EXPECT_NEAR(m.rmse_xy_m, std::sqrt((0.0025 + 0.0) / 2.0), 1e-15);
  EXPECT_NEAR(m.rmse_z_m, std::sqrt(0.0144 / 2.0), 1e-15);
  EXPECT_NEAR(m.rmse_all_m, std::sqrt((0.0025 + 0.0144) / 2.0), 1e-15);
  EXPECT_DOUBLE_EQ(m.max_m, 0.12);
  EXPECT_NEAR(m.std_m, 0.035, 1e-15);  // norms 0.05 and 0.12: mean 0.085, σ = 0.035
}

TEST(TrackingMetrics, RmseAllCombinesXyAndZ) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n(0.0, 0.05);
  TrackingAccumulator acc;
  for (int i = 0; i < 10000; ++i) acc.add({n(rng), n(rng), 0.5 * n(rng)});
  const auto m = acc.result();
  EXPECT_NEAR(m.rmse_all_m * m.rmse_all_m, m.rmse_xy_m * m.rmse_xy_m + m.rmse_z_m * m.rmse_z_m, 1e-15);
  EXPECT_NEAR(m.rmse_z_m, 0.025, 0.001);  // the generating σ, within sampling error
  EXPECT_GE(m.max_m, m.rmse_all_m);
}

TEST(TrackingMetrics, NonFiniteSamplesAreCountedNotUsed) {
  TrackingAccumulator acc;
  acc.add({0.1, 0.0, 0.0});
  acc.add({std::nan(""), 0.0, 0.0});
  EXPECT_EQ(acc.result().samples, 1u);
  EXPECT_EQ(acc.rejected(), 1u);
  EXPECT_DOUBLE_EQ(acc.result().rmse_all_m, 0.1);
  EXPECT_EQ(TrackingAccumulator().result().samples, 0u);
}

}  // namespace

// A flight that ended before its trajectory (a strike in the start hover) has no tracking
// error: its JSON metrics are null and its summary says so, not RMSE 0 (issue 16's sweep).
namespace {

TEST(TrackingMetrics, NoSampleIsNullNotZero) {
  geaware::experiments::FlightScenario s;
  geaware::experiments::FlightResult r;
  r.tracking = TrackingAccumulator().result();
  const auto j = geaware::experiments::flightJson(s, r);
  for (const char* key : {"rmse_xy_cm", "rmse_z_cm", "rmse_all_cm", "max_cm", "std_cm"}) {
    EXPECT_TRUE(j[key].is_null()) << key;
  }
  EXPECT_NE(geaware::experiments::formatFlight(r).find("RMSE none: no sample on the trajectory"),
            std::string::npos);
  TrackingAccumulator one;
  one.add({0.0, 0.0, 0.0});
  r.tracking = one.result();
  EXPECT_EQ(geaware::experiments::flightJson(s, r)["rmse_all_cm"], 0.0);
}

}  // namespace
