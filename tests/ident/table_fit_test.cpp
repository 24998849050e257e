// SPDX-License-Identifier: BSD-3-Clause
// Ground-effect curves identified as tables (ident/table_fit.hpp): synthetic logs generated
// from a vehicle whose F_G and M_G ARE tables give back the knot values within their reported
// standard errors, the standard errors are honest, the sparse solver agrees with the dense one,
// and logs that cannot separate k_T from F_G are refused with a message that says why.

#include "geaware/ident/table_fit.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "geaware/ident/leveling_fit.hpp"
#include "geaware/ident/platform_fit.hpp"
#include "synthetic.hpp"

namespace {

namespace ident = geaware::ident;
namespace model = geaware::model;
using ident_test::withinSigmas;

/// The paper vehicle with both curves as tables: F_G at the synthetic level heights up to
/// 0.5 m (the heights above follow the tail), M_G at the tilted heights, sampled from the
/// closed forms.
model::VehicleParams tableVehicle() {
  model::VehicleParams p = geaware_test::paperParams();
  const model::GroundEffectModel formula(p);
  for (double h : ident_test::PlatformSpec{}.level_heights_m) {
    if (h > 0.5) continue;
    p.additional_thrust.table.heights_m.push_back(h);
    p.additional_thrust.table.values.push_back(formula.thrustRatio(h));
  }
  for (double h : ident_test::PlatformSpec{}.tilted_heights_m) {
    p.leveling_torque.table.heights_m.push_back(h);
    p.leveling_torque.table.values.push_back(formula.levelingCoefficient(h));
  }
  EXPECT_TRUE(p.validate().empty());
  return p;
}

TEST(TableBasis, HatsBetweenKnotsHeldBelowInverseSquareAbove) {
  const std::vector<double> k = {0.1, 0.2, 0.4};
  int index[2];
  double weight[2];
  ASSERT_EQ(ident::tableBasis(k, 0.05, index, weight), 1);
  EXPECT_EQ(index[0], 0);
  EXPECT_EQ(weight[0], 1.0);
  ASSERT_EQ(ident::tableBasis(k, 0.25, index, weight), 2);
  EXPECT_EQ(index[0], 1);
  EXPECT_EQ(index[1], 2);
  EXPECT_NEAR(weight[0], 0.75, 1e-15);
  EXPECT_NEAR(weight[1], 0.25, 1e-15);
  ASSERT_EQ(ident::tableBasis(k, 0.2, index, weight), 1);  // on a knot: that knot alone
  EXPECT_EQ(index[0], 1);
  ASSERT_EQ(ident::tableBasis(k, 0.8, index, weight), 1);
  EXPECT_EQ(index[0], 2);
  EXPECT_NEAR(weight[0], 0.25, 1e-15);
  EXPECT_NEAR(ident::tableValue(k, {3.0, 2.0, 1.0}, 0.3), 1.5, 1e-15);
}

TEST(TableKnots, DistinctHeightsUpToTheTopOrThinnedByCount) {
  const std::vector<double> h = {0.3, 0.1, 0.1, 0.2, 0.30004, 0.6, 0.2};
  ident::TableOptions o;
  o.top_m = 0.5;
  EXPECT_EQ(ident::chooseKnots(h, o, "log", "F_G"), (std::vector<double>{0.1, 0.2, 0.3}));
  std::vector<double> many;
  for (int i = 0; i < 1000; ++i) many.push_back(0.05 + 0.001 * i);
  o.top_m = 10.0;
  o.max_knots = 20;
  const auto k = ident::chooseKnots(many, o, "log", "F_G");
  EXPECT_EQ(k.size(), 20u);
  EXPECT_DOUBLE_EQ(k.front(), 0.05);
  EXPECT_DOUBLE_EQ(k.back(), 1.049);
  o.heights_m = {0.1, 0.1};
  EXPECT_THROW((void)ident::chooseKnots(h, o, "log", "F_G"), ident::IdentError);
  o.heights_m = {};
  o.top_m = 0.15;
  try {
    (void)ident::chooseKnots(h, o, "my.csv", "F_G");
    FAIL() << "one distinct height must not make a table";
  } catch (const ident::IdentError& e) {
    EXPECT_NE(std::string(e.what()).find("my.csv"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("at least 2"), std::string::npos) << e.what();
  }
}

TEST(TableKnots, CountingDistinctHeightsGivesTheKnotsOfSortingThemAll) {
  // The oracle: every height to 0.1 mm sorted, distinct runs, or quantiles by count. chooseKnots
  // counts distinct heights instead (and sorts only when there are very many): the same knots,
  // bit for bit, for few and many distinct heights, thinned or not, runs or shuffled.
  const auto oracle = [](const std::vector<double>& h, const ident::TableOptions& o) {
    std::vector<double> sorted;
    for (const double x : h) {
      if (x <= o.top_m) sorted.push_back(std::round(x * 1e4) / 1e4);
    }
    std::sort(sorted.begin(), sorted.end());
    std::vector<double> distinct;
    for (const double x : sorted) {
      if (distinct.empty() || x != distinct.back()) distinct.push_back(x);
    }
    if (distinct.size() <= o.max_knots) return distinct;
    std::vector<double> knots;
    const std::size_t m = std::max<std::size_t>(o.max_knots, 2);
    for (std::size_t q = 0; q < m; ++q) {
      const double x = sorted[q * (sorted.size() - 1) / (m - 1)];
      if (knots.empty() || x > knots.back()) knots.push_back(x);
    }
    return knots;
  };
  std::mt19937_64 rng(21);
  for (const int levels : {2, 14, 37, 150, 5000}) {
    std::uniform_int_distribution<int> level(0, levels - 1);
    std::normal_distribution<double> jitter(0.0, 2e-5);
    for (const std::size_t max_knots : {std::size_t{1}, std::size_t{2}, std::size_t{10}, std::size_t{120}}) {
      std::vector<double> h(20000);
      for (std::size_t i = 0; i < h.size(); ++i) {
        // Runs of one height, or shuffled heights; each near a level, so rounding merges some.
        const int l = i % 3 == 0 ? level(rng) : static_cast<int>(i / 400 % static_cast<std::size_t>(levels));
        h[i] = std::abs(0.05 + 0.0137 * l + jitter(rng));
      }
      ident::TableOptions o;
      o.top_m = 0.05 + 0.0137 * 0.8 * levels;
      o.max_knots = max_knots;
      const auto expected = oracle(h, o);
      if (expected.size() < 2) continue;
      const auto got = ident::chooseKnots(h, o, "log", "F_G");
      ASSERT_EQ(got.size(), expected.size()) << levels << " levels, " << max_knots << " knots";
      for (std::size_t k = 0; k < got.size(); ++k) {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(got[k]), std::bit_cast<std::uint64_t>(expected[k])) << k;
      }
    }
  }
}

TEST(TableFit, SparseSolverAgreesWithTheDenseOne) {
  // The same 3-parameter problem written densely and sparsely: the same estimate and covariance.
  const auto log = ident_test::syntheticPlatform({}, 21);
  const auto row = [&](std::size_t i, double* x) {
    x[0] = log.n_rpm[0][i] * log.n_rpm[0][i];
    x[1] = log.h_m[i];
    x[2] = 1.0;
  };
  const auto dense = ident::fitLinear(log.size(), 3, [&](std::size_t i, double* x, double& y, double& w) {
    row(i, x);
    y = log.f_N[2][i];
    w = 1.0;
    return true;
  });
  const auto sparse = ident::fitSparseLinear(
      log.size(), 3, [&](std::size_t i, int* index, double* value, int& count, double& y, double& w) {
        row(i, value);
        index[0] = 0;
        index[1] = 1;
        index[2] = 2;
        count = 3;
        y = log.f_N[2][i];
        w = 1.0;
        return true;
      });
  ASSERT_TRUE(dense.ok && sparse.ok);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(sparse.x(a), dense.x(a), 1e-9 * std::abs(dense.x(a)));
    EXPECT_NEAR(sparse.covariance(a, a), dense.covariance(a, a), 1e-6 * dense.covariance(a, a));
  }
  EXPECT_EQ(sparse.stats.outliers, dense.stats.outliers);
}

TEST(TableFit, AdditionalThrustKnotsComeBackWithinTheirStandardErrors) {
  const model::VehicleParams p = tableVehicle();
  ident_test::PlatformSpec spec;
  spec.tilted_samples = 0;
  double z2 = 0.0;
  int count = 0;
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
    SCOPED_TRACE(seed);
    const auto fit = ident::fitAdditionalThrustTable(ident_test::syntheticPlatform(spec, seed, p));
    EXPECT_TRUE(withinSigmas(fit.k_T_N_per_rpm2, p.rotor.k_T_N_per_rpm2));
    ASSERT_EQ(fit.F_G.heights_m, p.additional_thrust.table.heights_m);
    for (std::size_t j = 0; j < fit.F_G.values.size(); ++j) {
      const auto& e = fit.F_G.values[j];
      const double truth = p.additional_thrust.table.values[j];
      EXPECT_TRUE(withinSigmas(e, truth)) << "knot " << fit.F_G.heights_m[j] << " m";
      z2 += std::pow((e.value - truth) / e.std_error, 2);
      ++count;
    }
    EXPECT_GT(fit.tail_samples, 0u);
    EXPECT_NEAR(fit.stats.residual_rms, spec.sigma_force_N, 0.1 * spec.sigma_force_N);
    EXPECT_TRUE(fit.warnings.empty()) << fit.warnings.front();
  }
  // Honest errors: 50 z-scores (correlated through k_T) with mean square near 1.
  EXPECT_GT(z2 / count, 0.4);
  EXPECT_LT(z2 / count, 1.9);
}

TEST(TableFit, LevelingKnotsComeBackWithinTheirStandardErrors) {
  const model::VehicleParams p = tableVehicle();
  ident_test::PlatformSpec spec;
  spec.level_samples = 0;
  const ident::LevelingInputs in{p.rotor.k_T_N_per_rpm2, p.rotor.k_TY_N_per_rpm2,
                                 p.diagonal_rotor_distance_m};
  double z2 = 0.0;
  int count = 0;
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
    SCOPED_TRACE(seed);
    const auto fit = ident::fitLevelingTable(ident_test::syntheticPlatform(spec, seed, p), in);
    ASSERT_EQ(fit.M_G.heights_m, p.leveling_torque.table.heights_m);
    for (std::size_t j = 0; j < fit.M_G.values.size(); ++j) {
      const auto& e = fit.M_G.values[j];
      const double truth = p.leveling_torque.table.values[j];
      EXPECT_TRUE(withinSigmas(e, truth)) << "knot " << fit.M_G.heights_m[j] << " m";
      z2 += std::pow((e.value - truth) / e.std_error, 2);
      ++count;
    }
    EXPECT_NEAR(fit.peak_height_m, 0.18, 0.021);  // the closed form peaks at 0.186 m
    EXPECT_TRUE(fit.warnings.empty()) << fit.warnings.front();
  }
  EXPECT_GT(z2 / count, 0.5);
  EXPECT_LT(z2 / count, 1.6);
}

TEST(TableFit, WithoutSamplesAboveTheTopKnotKTCannotBeSeparated) {
  ident_test::PlatformSpec spec;
  spec.tilted_samples = 0;
  spec.level_heights_m = {0.08, 0.1, 0.15, 0.2, 0.3, 0.4};
  const auto log = ident_test::syntheticPlatform(spec, 3);
  try {
    (void)ident::fitAdditionalThrustTable(log);
    FAIL() << "a table up to the highest logged height leaves k_T undetermined";
  } catch (const ident::IdentError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(log.source), std::string::npos) << msg;
    EXPECT_NE(msg.find("above the top knot (0.4 m)"), std::string::npos) << msg;
  }
  // Setting the top knot lower hands the highest height to the tail, and the fit works.
  ident::PlatformFitOptions o;
  o.thrust_table.top_m = 0.35;
  const auto fit = ident::fitAdditionalThrustTable(log, o);
  EXPECT_EQ(fit.F_G.heights_m.back(), 0.3);
  EXPECT_GT(fit.tail_samples, 1000u);
}

TEST(TableFit, RobustLossIgnoresFivePercentGrossOutliers) {
  const model::VehicleParams p = tableVehicle();
  ident_test::PlatformSpec spec;
  spec.tilted_samples = 0;
  spec.outlier_fraction = 0.05;
  const auto fit = ident::fitAdditionalThrustTable(ident_test::syntheticPlatform(spec, 7, p));
  EXPECT_TRUE(withinSigmas(fit.k_T_N_per_rpm2, p.rotor.k_T_N_per_rpm2));
  for (std::size_t j = 0; j < fit.F_G.values.size(); ++j) {
    EXPECT_TRUE(withinSigmas(fit.F_G.values[j], p.additional_thrust.table.values[j])) << j;
  }
  EXPECT_GT(fit.stats.outliers, 800u);  // ~1000 gross errors among 20,000 samples
}

}  // namespace
