// SPDX-License-Identifier: BSD-3-Clause
// Platform rows that stand for several samples (the count column of a stand table's mean rows,
// issue 11): the leveling fits and the correlation table weigh each row as its count, so they
// give what the log expanded to its counts (each row repeated count times) gives. Ignoring the
// counts gives something else, by far more than the rounding between the two.

#include <cmath>
#include <cstdint>
#include <random>
#include <tuple>

#include <gtest/gtest.h>

#include "geaware/ident/correlation.hpp"
#include "geaware/ident/leveling_fit.hpp"
#include "synthetic.hpp"

namespace {

namespace ident = geaware::ident;

ident::LevelingInputs truthInputs() {
  const auto& p = geaware_test::paperParams();
  return {p.rotor.k_T_N_per_rpm2, p.rotor.k_TY_N_per_rpm2, p.diagonal_rotor_distance_m};
}

/// A platform log of a few hundred mean rows, each of 1 to 12 samples: the model's values plus
/// the noise of a mean of that many samples (σ/√count).
ident::PlatformLog countedLog(std::uint64_t seed) {
  ident_test::PlatformSpec spec;
  spec.level_samples = 150;
  spec.tilted_samples = 250;
  const double sigma_force_N = spec.sigma_force_N;
  const double sigma_torque_Nm = spec.sigma_torque_Nm;
  spec.sigma_force_N = 0.0;
  spec.sigma_torque_Nm = 0.0;
  ident::PlatformLog log = ident_test::syntheticPlatform(spec, seed);
  std::mt19937_64 rng(seed + 100);
  std::uniform_int_distribution<int> count(1, 12);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (std::size_t i = 0; i < log.size(); ++i) {
    log.count.push_back(count(rng));
    const double root = std::sqrt(log.count.back());
    for (auto& f : log.f_N) f[i] += sigma_force_N / root * noise(rng);
    for (auto& t : log.tau_Nm) t[i] += sigma_torque_Nm / root * noise(rng);
  }
  return log;
}

/// Plain weighted least squares: the robust loss and the outlier test, which act on the
/// residuals of rows (weighted) or of samples (expanded) and so may drop different ones, are off.
ident::LevelingFitOptions plainOptions() {
  ident::LevelingFitOptions o;
  o.robust.loss = ident::RobustLoss::kNone;
  o.robust.outlier_sigmas = 0.0;
  return o;
}

/// The log expanded to its counts: row i repeated count[i] times, no count column.
ident::PlatformLog expanded(const ident::PlatformLog& log) {
  ident::PlatformLog out;
  out.source = log.source + "_expanded";
  out.first_data_line = 2;
  for (std::size_t i = 0; i < log.size(); ++i) {
    for (int k = 0; k < static_cast<int>(log.count[i]); ++k) {
      out.t_s.push_back(static_cast<double>(out.t_s.size()));
      out.h_m.push_back(log.h_m[i]);
      out.tilt_deg.push_back(log.tilt_deg[i]);
      for (std::size_t a = 0; a < 4; ++a) out.n_rpm[a].push_back(log.n_rpm[a][i]);
      for (std::size_t a = 0; a < 3; ++a) {
        out.f_N[a].push_back(log.f_N[a][i]);
        out.tau_Nm[a].push_back(log.tau_Nm[a][i]);
      }
    }
  }
  return out;
}

ident::PlatformLog withoutCounts(ident::PlatformLog log) {
  log.count.clear();
  return log;
}

TEST(CountRows, WeightedRanksAreTheExpandedRanks) {
  // Values 3, 1, 3 with counts 2, 3, 1: expanded 1 1 1 3 3 3, ranks 1–3 → 2, 4–6 → 5.
  const std::vector<double> v{3, 1, 3};
  const std::vector<double> w{2, 3, 1};
  EXPECT_EQ(ident::averageRanks(v, w), (std::vector<double>{5, 2, 5}));
  // Pearson of (1, 2, 3) with weights (1, 1, 2) is that of (1, 2, 3, 3).
  const std::vector<double> x{1, 2, 3};
  const std::vector<double> y{2, 1, 5};
  EXPECT_NEAR(ident::pearson(x, y, std::vector<double>{1, 1, 2}),
              ident::pearson(std::vector<double>{1, 2, 3, 3}, std::vector<double>{2, 1, 5, 5}), 1e-15);
}

TEST(CountRows, TheCorrelationTableIsTheExpandedLogs) {
  const auto& p = geaware_test::paperParams();
  const ident::PlatformLog log = countedLog(1);
  const auto w = ident::platformCorrelations(log, p);
  const auto e = ident::platformCorrelations(expanded(log), p);
  const auto plain = ident::platformCorrelations(withoutCounts(log), p);
  EXPECT_EQ(w.samples, e.samples);
  double largest_difference = 0.0;  // between the table without its counts and the expansion
  for (Eigen::Index i = 0; i < e.r.rows(); ++i) {
    for (Eigen::Index j = 0; j < e.r.cols(); ++j) {
      EXPECT_NEAR(w.r(i, j), e.r(i, j), 1e-12) << i << ", " << j;
      largest_difference = std::max(largest_difference, std::abs(plain.r(i, j) - e.r(i, j)));
    }
  }
  EXPECT_GT(largest_difference, 1e-3);
}

TEST(CountRows, TheLevelingFitsAreTheExpandedLogs) {
  const ident::PlatformLog log = countedLog(2);
  const ident::PlatformLog big = expanded(log);
  const ident::LevelingFitOptions o = plainOptions();
  {
    const auto w = ident::fitLeveling(log, truthInputs(), o);
    const auto e = ident::fitLeveling(big, truthInputs(), o);
    const auto plain = ident::fitLeveling(withoutCounts(log), truthInputs(), o);
    for (const auto& [a, b, c] : {std::tuple{w.g3_m, e.g3_m, plain.g3_m}, std::tuple{w.g4_m2, e.g4_m2, plain.g4_m2},
                                  std::tuple{w.scale_m4, e.scale_m4, plain.scale_m4}}) {
      // Both optimised to a small fraction of a standard error; without the counts, elsewhere.
      EXPECT_NEAR(a.value, b.value, 1e-4 * b.std_error);
      EXPECT_GT(std::abs(c.value - b.value), 1e-2 * b.std_error);
    }
  }
  {
    const auto w = ident::fitLevelingTable(log, truthInputs(), o);
    const auto e = ident::fitLevelingTable(big, truthInputs(), o);
    const auto plain = ident::fitLevelingTable(withoutCounts(log), truthInputs(), o);
    EXPECT_EQ(w.M_G.samples, e.M_G.samples);  // samples per knot, not rows
    ASSERT_EQ(w.M_G.values.size(), e.M_G.values.size());
    double largest_difference = 0.0;
    for (std::size_t j = 0; j < e.M_G.values.size(); ++j) {
      EXPECT_NEAR(w.M_G.values[j].value, e.M_G.values[j].value, 1e-9 * std::abs(e.M_G.values[j].value));
      largest_difference = std::max(largest_difference, std::abs(plain.M_G.values[j].value - e.M_G.values[j].value) /
                                                            e.M_G.values[j].std_error);
    }
    EXPECT_GT(largest_difference, 1e-2);
  }
}

}  // namespace
