// SPDX-License-Identifier: BSD-3-Clause
// Spearman rank correlation with ties (paper eq. 4), and the supplementary table's signs on a
// synthetic platform log.

#include "geaware/ident/correlation.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "synthetic.hpp"

namespace {

using geaware::ident::averageRanks;
using geaware::ident::pearson;
using geaware::ident::spearman;

TEST(Correlation, TiesGetAverageRanks) {
  EXPECT_EQ(averageRanks(std::vector<double>{3, 1, 3, 3, 2}), (std::vector<double>{4, 1, 4, 4, 2}));
  EXPECT_EQ(averageRanks(std::vector<double>{5, 5}), (std::vector<double>{1.5, 1.5}));
}

TEST(Correlation, HandComputedCaseWithTies) {
  // x ranks (1, 2.5, 2.5, 4), y ranks (1, 2, 3, 4): deviations (−1.5, 0, 0, 1.5) and
  // (−1.5, −0.5, 0.5, 1.5); r = 4.5/√(4.5·5) = 0.9486833.
  EXPECT_NEAR(spearman(std::vector<double>{1, 2, 2, 3}, std::vector<double>{10, 20, 30, 40}),
              4.5 / std::sqrt(22.5), 1e-15);
  // Both tied: x ranks (1.5, 1.5, 3), y ranks (1, 2.5, 2.5): r = 0.75/√(1.5·1.5) = 0.5.
  EXPECT_NEAR(spearman(std::vector<double>{1, 1, 2}, std::vector<double>{0, 5, 5}), 0.5, 1e-15);
  // A constant variable has no rank correlation.
  EXPECT_TRUE(std::isnan(spearman(std::vector<double>{1, 1, 1}, std::vector<double>{1, 2, 3})));
}

TEST(Correlation, WithoutTiesEqualsTheClassicFormula) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> x, y;
  for (int i = 0; i < 500; ++i) {
    x.push_back(g(rng));
    y.push_back(x.back() + g(rng));
  }
  const auto rx = averageRanks(x);
  const auto ry = averageRanks(y);
  double d2 = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) d2 += (rx[i] - ry[i]) * (rx[i] - ry[i]);
  const double n = static_cast<double>(x.size());
  EXPECT_NEAR(spearman(x, y), 1.0 - 6.0 * d2 / (n * (n * n - 1.0)), 1e-12);
}

TEST(Correlation, InvariantUnderMonotoneTransformsUnlikePearson) {
  std::mt19937_64 rng(4);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> x, y, fx, gy;
  for (int i = 0; i < 1000; ++i) {
    x.push_back(g(rng));
    y.push_back(x.back() + 0.5 * g(rng));
    fx.push_back(std::exp(3.0 * x.back()));
    gy.push_back(std::pow(y.back(), 3.0));
  }
  EXPECT_NEAR(spearman(fx, gy), spearman(x, y), 1e-12);
  // Spearman is Pearson of the ranks, and a monotone map gives 1 where Pearson does not.
  EXPECT_NEAR(spearman(x, y), pearson(averageRanks(x), averageRanks(y)), 1e-15);
  EXPECT_NEAR(spearman(x, fx), 1.0, 1e-15);
  EXPECT_LT(pearson(x, fx), 0.8);
}

TEST(Correlation, PlatformTableHasThePapersSigns) {
  const auto& p = geaware_test::paperParams();
  ident_test::PlatformSpec spec;
  spec.level_samples = 5000;
  spec.tilted_samples = 5000;
  const auto table = geaware::ident::platformCorrelations(ident_test::syntheticPlatform(spec, 1), p);
  ASSERT_EQ(table.r.rows(), 6);
  ASSERT_EQ(table.r.cols(), 5);
  EXPECT_EQ(table.samples[3], 5000u);
  // τ_B follows its N_base component; the leveling torque (negative) grows with thrust; f_G
  // falls with height.
  EXPECT_GT(table.r(1, 0), 0.9);   // x_Wᵀτ_B vs N_base(2)
  EXPECT_GT(table.r(3, 1), 0.9);   // z_Wᵀτ_B vs N_base(4)
  EXPECT_LT(table.r(0, 2), -0.1);  // y_Wᵀτ_G vs N_base(1)
  EXPECT_LT(table.r(4, 4), -0.3);  // f_G vs h
  EXPECT_NEAR(table.r(4, 0), 0.0, 0.05);  // x_Wᵀτ_B vs h: no relation
}

}  // namespace
