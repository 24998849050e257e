// SPDX-License-Identifier: BSD-3-Clause
// Seeded noise and scheduling shared by the sensors: the normal generator's distribution, the
// seeding, the fixed-rate clock and the Gauss–Markov process.
#include "geaware/sim/sampling.hpp"

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace geaware::sim {
namespace {

TEST(Mt19937_64, IsBitForBitTheStandardEngine) {
  // Our engine replaces std::mt19937_64 for speed; every noise stream must stay the same.
  // 2,000 outputs cross six refills of the 312-word state.
  for (const std::uint64_t seed : {std::uint64_t{0}, std::uint64_t{1}, std::uint64_t{5489},
                                   ~std::uint64_t{0}, streamSeed(42, salt::kRanger)}) {
    Mt19937_64 ours(seed);
    std::mt19937_64 standard(seed);
    for (int k = 0; k < 2000; ++k) ASSERT_EQ(ours(), standard()) << "seed " << seed << ", k " << k;
  }
  // The standard's own check value: the 10,000th output of a default-constructed engine.
  Mt19937_64 fresh;
  for (int k = 1; k < 10000; ++k) (void)fresh();
  EXPECT_EQ(fresh(), 9981545732273789042ULL);
}

TEST(NoiseSource, UniformIsTheDocumentedMappingOfTheStandardEngine) {
  // uniform() = (top 53 bits + ½)·2⁻⁵³ of mt19937_64 seeded with streamSeed(seed, salt).
  NoiseSource noise(7, salt::kImu);
  std::mt19937_64 standard(streamSeed(7, salt::kImu));
  for (int k = 0; k < 1000; ++k) {
    const double expected = (static_cast<double>(standard() >> 11) + 0.5) * 0x1.0p-53;
    ASSERT_EQ(noise.uniform(), expected) << "k " << k;
  }
}

TEST(NoiseSource, SameSeedSameStreamOtherSeedOrSaltOther) {
  NoiseSource a(42, salt::kImu);
  NoiseSource b(42, salt::kImu);
  NoiseSource c(43, salt::kImu);
  NoiseSource d(42, salt::kMocap);
  int differ_c = 0;
  int differ_d = 0;
  for (int k = 0; k < 100; ++k) {
    const double x = a.normal();
    EXPECT_EQ(x, b.normal());
    differ_c += x != c.normal();
    differ_d += x != d.normal();
  }
  EXPECT_EQ(differ_c, 100);
  EXPECT_EQ(differ_d, 100);
}

TEST(NoiseSource, NormalHasTheStandardNormalDistribution) {
  // 10⁶ draws. Tolerances ≈ 5 standard errors: mean 1e-3, variance 1.4e-3, fourth moment 1e-2,
  // P(|x| > 3) 5e-5, P(x > 3.5) 1.5e-5 (beyond the ziggurat's tail start R = 3.44).
  NoiseSource n(7, 99);
  constexpr int kN = 1'000'000;
  double s1 = 0, s2 = 0, s4 = 0;
  int beyond3 = 0, above35 = 0, below05 = 0, below1 = 0, below2 = 0;
  for (int k = 0; k < kN; ++k) {
    const double x = n.normal();
    s1 += x;
    s2 += x * x;
    s4 += x * x * x * x;
    beyond3 += std::abs(x) > 3.0;
    above35 += x > 3.5;
    below05 += x < 0.5;
    below1 += x < 1.0;
    below2 += x < 2.0;
  }
  const double mean = s1 / kN;
  const double var = s2 / kN - mean * mean;
  EXPECT_NEAR(mean, 0.0, 5e-3);
  EXPECT_NEAR(var, 1.0, 7e-3);
  EXPECT_NEAR(s4 / kN, 3.0, 0.05);
  EXPECT_NEAR(beyond3 / double(kN), 2.6998e-3, 2.5e-4);
  EXPECT_NEAR(above35 / double(kN), 2.3263e-4, 7e-5);
  EXPECT_NEAR(below05 / double(kN), 0.691462, 2.5e-3);
  EXPECT_NEAR(below1 / double(kN), 0.841345, 2e-3);
  EXPECT_NEAR(below2 / double(kN), 0.977250, 8e-4);
}

TEST(NoiseSource, UniformIsOpenUnitIntervalAndGeometricHasMeanOneOverP) {
  NoiseSource n(1, 2);
  double s = 0;
  double lo = 1, hi = 0;
  for (int k = 0; k < 100'000; ++k) {
    const double u = n.uniform();
    s += u;
    lo = std::min(lo, u);
    hi = std::max(hi, u);
  }
  EXPECT_GT(lo, 0.0);
  EXPECT_LT(hi, 1.0);
  EXPECT_NEAR(s / 100'000, 0.5, 4e-3);
  double g = 0;
  for (int k = 0; k < 100'000; ++k) g += static_cast<double>(n.geometric(0.01));
  EXPECT_NEAR(g / 100'000 / 100.0, 1.0, 0.02);  // std error 0.3 %
  EXPECT_EQ(n.geometric(1.0), 1);
  EXPECT_GT(n.geometric(0.0), std::int64_t{1} << 60);
}

TEST(SampleClock, DueExactlyAtItsRateInAFasterLoop) {
  // 200 Hz inside a 1 kHz loop whose time accumulates (as the plant's does): every 5th step,
  // for a minute, without drift.
  SampleClock clock(200.0);
  double t = 0.0;
  int due = 0;
  for (int k = 0; k <= 60'000; ++k) {
    if (clock.due(t)) {
      EXPECT_EQ(k % 5, 0) << "step " << k;
      ++due;
    }
    t += 1e-3;
  }
  EXPECT_EQ(due, 12'001);
}

TEST(SampleClock, SlowCallerGetsNoBacklog) {
  SampleClock clock(100.0);
  EXPECT_TRUE(clock.due(0.0));
  EXPECT_FALSE(clock.due(0.005));
  EXPECT_TRUE(clock.due(0.137));  // 13 periods missed: one sample
  EXPECT_FALSE(clock.due(0.139));
  EXPECT_NEAR(clock.next_s(), 0.14, 1e-12);
  EXPECT_TRUE(clock.due(0.14));
}

TEST(GaussMarkov3, StationaryUnitVarianceAndExponentialCorrelation) {
  // τ = 0.05 s, dt = 1 ms, 400 s: ≈ 4000 correlation times per axis, std error of the variance
  // ≈ 2 %; the lag-τ autocorrelation must be e⁻¹.
  NoiseSource n(3, 4);
  constexpr double kTau = 0.05;
  constexpr double kDt = 1e-3;
  GaussMarkov3 x(kTau, n);
  constexpr int kSteps = 400'000;
  constexpr int kLag = 50;
  std::vector<double> v(kSteps);
  for (int k = 0; k < kSteps; ++k) v[k] = x.advance(kDt, n).x();
  double s2 = 0, c = 0;
  for (int k = 0; k < kSteps; ++k) s2 += v[k] * v[k];
  for (int k = 0; k + kLag < kSteps; ++k) c += v[k] * v[k + kLag];
  const double var = s2 / kSteps;
  EXPECT_NEAR(var, 1.0, 0.08);
  EXPECT_NEAR(c / (kSteps - kLag) / var, std::exp(-1.0), 0.05);
}

TEST(IsFinite, RejectsAnyNonFiniteField) {
  PlantState s;
  EXPECT_TRUE(isFinite(s));
  s.w_dot_B.y() = std::nan("");
  EXPECT_FALSE(isFinite(s));
  s = PlantState{};
  s.n_rpm[3] = INFINITY;
  EXPECT_FALSE(isFinite(s));
}

}  // namespace
}  // namespace geaware::sim
