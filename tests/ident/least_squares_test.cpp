// SPDX-License-Identifier: BSD-3-Clause
// The shared solvers: least-squares estimates with honest standard errors, and a robust scheme
// that ignores gross outliers.

#include "geaware/ident/least_squares.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "synthetic.hpp"

namespace {

using geaware::ident::fitLinear;
using geaware::ident::fitNonlinear;
using geaware::ident::LeastSquaresFit;
using geaware::ident::NonlinearProblem;
using geaware::ident::RobustLoss;
using geaware::ident::RobustOptions;

struct Line {
  std::vector<double> x, y;
};

Line line(std::size_t n, std::uint64_t seed, double outlier_fraction = 0.0) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Line l;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = 10.0 * unit(rng);
    double y = 2.0 + 0.5 * x + noise(rng);
    if (unit(rng) < outlier_fraction) y += 30.0 + 20.0 * unit(rng);  // one-sided: the worst case
    l.x.push_back(x);
    l.y.push_back(y);
  }
  return l;
}

LeastSquaresFit fitLine(const Line& l, const RobustOptions& o) {
  return fitLinear(l.x.size(), 2,
                   [&](std::size_t i, double* x, double& y, double& w) {
                     x[0] = 1.0;
                     x[1] = l.x[i];
                     y = l.y[i];
                     w = 1.0;
                     return true;
                   },
                   o);
}

// Over many seeds the z-scores of an honest estimator have unit variance. 200 seeds: the sample
// variance of z² lies in [0.75, 1.3] with probability > 99.9 %.
TEST(LeastSquares, LinearStandardErrorsAreHonestOverManySeeds) {
  double z2 = 0.0;
  constexpr int kSeeds = 200;
  for (int s = 0; s < kSeeds; ++s) {
    const auto fit = fitLine(line(200, static_cast<std::uint64_t>(s)), {});
    ASSERT_TRUE(fit.ok) << fit.message;
    const double z = (fit.x(1) - 0.5) / std::sqrt(fit.covariance(1, 1));
    z2 += z * z;
  }
  z2 /= kSeeds;
  EXPECT_GT(z2, 0.75);
  EXPECT_LT(z2, 1.3);
}

TEST(LeastSquares, StandardErrorShrinksAsOneOverRootN) {
  const auto a = fitLine(line(2000, 1), {});
  const auto b = fitLine(line(8000, 2), {});
  EXPECT_NEAR(std::sqrt(a.covariance(1, 1) / b.covariance(1, 1)), 2.0, 0.2);
}

TEST(LeastSquares, LinearRobustFitIgnoresFivePercentGrossOutliers) {
  const Line l = line(4000, 7, 0.05);
  const auto robust = fitLine(l, {});
  ASSERT_TRUE(robust.ok);
  EXPECT_TRUE(ident_test::withinSigmas(robust.estimate(0), 2.0));
  EXPECT_TRUE(ident_test::withinSigmas(robust.estimate(1), 0.5));
  EXPECT_NEAR(static_cast<double>(robust.stats.outliers), 0.05 * 4000, 0.015 * 4000);
  EXPECT_NEAR(robust.stats.residual_rms, 0.1, 0.01);
  // Plain least squares is pulled far off by the same data.
  const auto plain = fitLine(l, {RobustLoss::kNone, 1.0, 0.0});
  EXPECT_GT(std::abs(plain.x(0) - 2.0), 1.0);
}

TEST(LeastSquares, SingularProblemsAreReportedNotSolved) {
  const auto fit = fitLinear(100, 2, [](std::size_t, double* x, double& y, double& w) {
    x[0] = 1.0;
    x[1] = 2.0;  // collinear with x[0]
    y = 1.0;
    w = 1.0;
    return true;
  });
  EXPECT_FALSE(fit.ok);
  EXPECT_NE(fit.message.find("not identifiable"), std::string::npos) << fit.message;
  const auto few = fitLinear(2, 2, [](std::size_t i, double* x, double& y, double& w) {
    x[0] = 1.0;
    x[1] = static_cast<double>(i);
    y = 1.0;
    w = 1.0;
    return true;
  });
  EXPECT_FALSE(few.ok);
  EXPECT_NE(few.message.find("too few samples"), std::string::npos) << few.message;
}

// y = a·exp(−b·x) with Cauchy and Huber losses: both recover (a, b) despite 5 % outliers.
TEST(LeastSquares, NonlinearRobustFitWithEitherLoss) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> xs, ys;
  for (int i = 0; i < 5000; ++i) {
    const double x = 3.0 * unit(rng);
    double y = 1.5 * std::exp(-0.8 * x) + noise(rng);
    if (unit(rng) < 0.05) y -= 2.0 + unit(rng);
    xs.push_back(x);
    ys.push_back(y);
  }
  NonlinearProblem p;
  p.samples = xs.size();
  p.parameters = 2;
  p.residual = [&](std::size_t i, const double* x, double& r, double* g) {
    const double e = std::exp(-x[1] * xs[i]);
    r = ys[i] - x[0] * e;
    if (g != nullptr) {
      g[0] = -e;
      g[1] = x[0] * xs[i] * e;
    }
    return true;
  };
  p.scales = {1.0, 1.0};
  for (const auto loss : {RobustLoss::kHuber, RobustLoss::kCauchy}) {
    const auto fit = fitNonlinear(p, Eigen::Vector2d(1.0, 0.3), {loss, loss == RobustLoss::kHuber ? 1.345 : 2.385, 4.0});
    ASSERT_TRUE(fit.ok) << fit.message;
    EXPECT_TRUE(ident_test::withinSigmas(fit.estimate(0), 1.5));
    EXPECT_TRUE(ident_test::withinSigmas(fit.estimate(1), 0.8));
    EXPECT_NEAR(fit.stats.residual_rms, 0.02, 0.002);
  }
}

TEST(LeastSquares, RobustSigmaIsTheNormalConsistentMad) {
  EXPECT_NEAR(geaware::ident::robustSigma({1.0, 2.0, 3.0, 4.0, 100.0}), 1.482602218505602, 1e-12);
}

/// The oracle of the robust scale: the upper median and the MAD, each by a full std::nth_element.
double madByFullSelection(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  const double median = *mid;
  for (double& x : v) x = std::abs(x - median);
  std::nth_element(v.begin(), mid, v.end());
  return 1.482602218505602 * *mid;
}

TEST(LeastSquares, RobustSigmaIsExactlyTheMedianOfAbsoluteDeviations) {
  // The oracle: the upper median and the MAD by a full std::nth_element. robustSigma selects
  // from a window bracketed by a sample on large inputs; the value must be the same, exactly,
  // whatever the values' order and distribution (sorted, ties, outliers, a narrow window miss).
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_int_distribution<int> small(0, 3);
  for (const std::size_t n : {1u, 2u, 7u, 8191u, 8192u, 8193u, 100000u, 300001u}) {
    std::vector<std::vector<double>> cases(5, std::vector<double>(n));
    for (std::size_t i = 0; i < n; ++i) {
      cases[0][i] = normal(rng);
      cases[1][i] = static_cast<double>(i);                        // sorted
      cases[2][i] = small(rng);                                    // heavy ties
      cases[3][i] = i % 10 == 0 ? 1e6 * normal(rng) : normal(rng);  // outliers
      cases[4][i] = i < n / 2 ? 0.0 : 1.0 + static_cast<double>(i);  // half exact zeros
    }
    for (std::size_t c = 0; c < cases.size(); ++c) {
      EXPECT_EQ(geaware::ident::robustSigma(cases[c]), madByFullSelection(cases[c])) << "n " << n << ", case " << c;
    }
  }
}

// Values for the selection tests: normal draws with heavy ties, zeros of both signs and
// infinities mixed in (`kind` picks the mixture).
std::vector<double> selectionCase(std::size_t n, int kind, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_int_distribution<int> pick(0, 9);
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> v(n);
  const std::size_t stride = std::max<std::size_t>(1, n / 1024);
  for (std::size_t i = 0; i < n; ++i) {
    const int u = pick(rng);
    switch (kind) {
      case 0: v[i] = normal(rng); break;
      case 1: v[i] = static_cast<double>(u % 3); break;                             // 3 values
      case 2: v[i] = u < 3 ? 0.0 : u < 6 ? -0.0 : normal(rng); break;               // ±0
      case 3: v[i] = u == 0 ? inf : u == 1 ? -inf : u == 2 ? -0.0 : normal(rng); break;
      case 4: v[i] = static_cast<double>(n - i); break;                             // reversed
      // Every value the 1024-value sample sees is far below the others: its bracket misses
      // and the whole vector is selected from.
      default: v[i] = i % stride == 0 ? -1e9 - static_cast<double>(i) : static_cast<double>(i); break;
    }
  }
  return v;
}

TEST(LeastSquares, KthSmallestIsTheValueNthElementSelects) {
  // RobustScale::kthSmallest against std::nth_element on a copy: every size from 1 to 300 at
  // every k, and sizes around and above the 8192 values where the sampled window starts, at
  // the median, the ends and random ranks; one RobustScale reused throughout (its buffers keep
  // the previous, larger sizes). Compared with ==: −0 and +0 are the same order statistic.
  std::mt19937_64 rng(11);
  geaware::ident::RobustScale scale;
  const auto oracle = [](std::vector<double> v, std::size_t k) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
  };
  for (std::size_t n = 1; n <= 300; ++n) {
    for (int kind = 0; kind < 6; ++kind) {
      const auto v = selectionCase(n, kind, rng);
      for (std::size_t k = 0; k < n; ++k) {
        ASSERT_EQ(scale.kthSmallest(v, k), oracle(v, k)) << "n " << n << ", kind " << kind << ", k " << k;
      }
    }
  }
  for (const std::size_t n : {100000u, 8191u, 8192u, 8193u, 20000u, 65537u}) {
    std::uniform_int_distribution<std::size_t> rank(0, n - 1);
    for (int kind = 0; kind < 6; ++kind) {
      const auto v = selectionCase(n, kind, rng);
      for (const std::size_t k : {std::size_t{0}, n / 2, n - 1, n / 8, rank(rng), rank(rng)}) {
        EXPECT_EQ(scale.kthSmallest(v, k), oracle(v, k)) << "n " << n << ", kind " << kind << ", k " << k;
      }
    }
  }
}

TEST(LeastSquares, RobustScaleIsTheMadOfAFullSelectionBitForBit) {
  // One RobustScale over many vectors (as the iterations of a fit use it) gives the MAD of a
  // full std::nth_element on each, bit for bit, on the mixtures above (ties, ±0, infinities, a
  // sample whose bracket misses) and sizes below and above the sampled window's 8192. (The
  // deviations are |x − median|, never −0, so any exact selection gives the same bits.)
  std::mt19937_64 rng(12);
  geaware::ident::RobustScale scale;
  for (const std::size_t n : {1u, 2u, 3u, 10u, 8191u, 8192u, 50000u, 9000u, 7u, 300001u, 100000u, 65536u}) {
    for (int kind = 0; kind < 6; ++kind) {
      const auto v = selectionCase(n, kind, rng);
      const double expected = madByFullSelection(v);
      const double got = scale.sigma(v);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(got), std::bit_cast<std::uint64_t>(expected))
          << "n " << n << ", kind " << kind << ": " << got << " vs " << expected;
    }
  }
}

// robustSigma as it was before RobustScale (a sorted sample's bracket, a window copied with
// branches, std::nth_element on it or on all values): the oracle where values are NaN, which
// no order ranks, so that only the same steps give the same value.
double previousKth(std::vector<double>& v, std::size_t k, std::vector<double>& window) {
  constexpr std::size_t kSample = 1024;
  constexpr std::ptrdiff_t kMargin = 64;
  const std::size_t n = v.size();
  if (n >= 8 * kSample) {
    std::array<double, kSample> sample{};
    const std::size_t stride = n / kSample;
    for (std::size_t i = 0; i < kSample; ++i) sample[i] = v[i * stride];
    std::sort(sample.begin(), sample.end());
    const auto rank = static_cast<std::ptrdiff_t>(static_cast<double>(k) / static_cast<double>(n) * kSample);
    constexpr double kUnbounded = std::numeric_limits<double>::infinity();
    const double lo = rank - kMargin < 0 ? -kUnbounded : sample[static_cast<std::size_t>(rank - kMargin)];
    const double hi = rank + kMargin >= static_cast<std::ptrdiff_t>(kSample) ? kUnbounded
                                                                             : sample[static_cast<std::size_t>(rank + kMargin)];
    std::size_t below = 0;
    window.clear();
    for (const double x : v) {
      if (x < lo) {
        ++below;
      } else if (!(x > hi)) {
        window.push_back(x);
      }
    }
    if (below <= k && k < below + window.size()) {
      const auto at = window.begin() + static_cast<std::ptrdiff_t>(k - below);
      std::nth_element(window.begin(), at, window.end());
      return *at;
    }
  }
  const auto at = v.begin() + static_cast<std::ptrdiff_t>(k);
  std::nth_element(v.begin(), at, v.end());
  return *at;
}

double previousRobustSigma(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t mid = v.size() / 2;
  std::vector<double> window;
  const double median = previousKth(v, mid, window);
  for (double& x : v) x = std::abs(x - median);
  return 1.482602218505602 * previousKth(v, mid, window);
}

TEST(LeastSquares, RobustScaleWithNaNTakesThePreviousStepsBitForBit) {
  // Residuals with NaN (a few, many, all; in the sample or only outside it) and without: the
  // value of the previous implementation, bit for bit (NaN payload included).
  std::mt19937_64 rng(13);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  geaware::ident::RobustScale scale;
  for (const std::size_t n : {1u, 5u, 100u, 8192u, 20000u, 100000u, 300001u}) {
    for (const double fraction : {0.0, 0.001, 0.05, 0.5, 1.0}) {
      std::vector<double> v(n);
      for (double& x : v) x = unit(rng) < fraction ? nan : normal(rng);
      const double expected = previousRobustSigma(v);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(scale.sigma(v)), std::bit_cast<std::uint64_t>(expected))
          << "n " << n << ", NaN fraction " << fraction;
    }
    if (n >= 8192) {  // one NaN, off the sampled positions (n / 1024 apart)
      std::vector<double> v(n);
      for (double& x : v) x = normal(rng);
      v[n / 1024 + 1] = nan;
      EXPECT_EQ(std::bit_cast<std::uint64_t>(scale.sigma(v)),
                std::bit_cast<std::uint64_t>(previousRobustSigma(v))) << "n " << n << ", one NaN";
    }
  }
}

TEST(LeastSquares, ABlockResidualGivesTheSameFitAsTheSampleOne) {
  // A nonlinear problem solved with its per-sample residual and with the block form of the same
  // lambda: the same numbers, bit for bit (the block form only saves calls).
  std::mt19937_64 rng(9);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<double> x(20000), y(20000);
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = 0.1 + 2.0 * static_cast<double>(i) / static_cast<double>(x.size());
    y[i] = 1.5 * std::exp(-0.7 * x[i]) + noise(rng) + (i % 97 == 0 ? 3.0 : 0.0);
  }
  const auto residual = [&](std::size_t i, const double* p, double& r, double* g) {
    const double e = std::exp(-p[1] * x[i]);
    r = y[i] - p[0] * e;
    if (g != nullptr) {
      g[0] = -e;
      g[1] = p[0] * x[i] * e;
    }
    return true;
  };
  NonlinearProblem problem;
  problem.samples = x.size();
  problem.parameters = 2;
  problem.residual = residual;
  problem.scales = {1.0, 1.0};
  const Eigen::VectorXd x0 = Eigen::Vector2d(1.0, 1.0);
  const LeastSquaresFit plain = fitNonlinear(problem, x0);
  problem.block = geaware::ident::blockResidual(residual, 2);
  const LeastSquaresFit block = fitNonlinear(problem, x0);
  ASSERT_TRUE(plain.ok && block.ok);
  EXPECT_EQ(plain.x, block.x);
  EXPECT_EQ(plain.covariance, block.covariance);
  EXPECT_EQ(plain.stats.outliers, block.stats.outliers);
  EXPECT_GT(plain.stats.outliers, 100u);
}

}  // namespace
