// SPDX-License-Identifier: BSD-3-Clause
// The shared parameter checks: which values each check admits (bounds, NaN, infinity) and the
// exact text it reports, since loaders, the CLI and other layers' tests quote that text.
#include "geaware/model/field_check.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geaware/model/vehicle_model.hpp"

namespace {

using geaware::model::FieldChecker;
using geaware::model::FieldError;
using geaware::model::formatValue;
using enum geaware::model::LowerBound;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

void expectError(const FieldError& e, const std::string& field, const std::string& value,
                 const std::string& expected) {
  EXPECT_EQ(e.field, field);
  EXPECT_EQ(e.value, value);
  EXPECT_EQ(e.expected, expected);
}

TEST(FormatValue, NineSignificantDigitsByDefault) {
  EXPECT_EQ(formatValue(0.25), "0.25");
  EXPECT_EQ(formatValue(1000.0), "1000");
  EXPECT_EQ(formatValue(1e-6), "1e-06");
  EXPECT_EQ(formatValue(1e12), "1e+12");
  EXPECT_EQ(formatValue(1.0 / 3.0), "0.333333333");
  EXPECT_EQ(formatValue(1.0 / 3.0, 6), "0.333333");
  EXPECT_EQ(formatValue(-2.5), "-2.5");
  EXPECT_EQ(formatValue(kNaN), "nan");
  EXPECT_EQ(formatValue(kInf), "inf");
  EXPECT_EQ(formatValue(-kInf), "-inf");
}

TEST(FieldChecker, RangeAdmitsItsBoundsAsTold) {
  std::vector<FieldError> out;
  FieldChecker c(out);
  EXPECT_TRUE(c.range("a", 0.0, 0.0, 1.0, kInclusive));
  EXPECT_TRUE(c.range("a", 1.0, 0.0, 1.0, kInclusive));
  EXPECT_TRUE(c.range("a", 1.0, 0.0, 1.0, kExclusive));
  EXPECT_TRUE(out.empty());

  EXPECT_FALSE(c.range("mass_kg", 0.0, 0.0, 1000.0, kExclusive, "kg"));
  EXPECT_FALSE(c.range("b", 1.5, 0.0, 1.0, kInclusive, "m"));
  EXPECT_FALSE(c.range("c", kNaN, 0.0, 1.0, kInclusive));
  EXPECT_FALSE(c.range("d", kInf, -kInf, kInf, kInclusive));
  ASSERT_EQ(out.size(), 4u);
  expectError(out[0], "mass_kg", "0", "a finite number in (0, 1000] kg");
  expectError(out[1], "b", "1.5", "a finite number in [0, 1] m");
  // No unit: nothing after the interval.
  expectError(out[2], "c", "nan", "a finite number in [0, 1]");
  expectError(out[3], "d", "inf", "a finite number in [-inf, inf]");
}

TEST(FieldChecker, SignChecks) {
  std::vector<FieldError> out;
  FieldChecker c(out);
  EXPECT_TRUE(c.positive("a", 1e-300));
  EXPECT_TRUE(c.nonNegative("a", 0.0));
  EXPECT_TRUE(c.finite("a", -1e300));
  EXPECT_FALSE(c.positive("rate_hz", 0.0));
  EXPECT_FALSE(c.positive("gain", kInf, "1/s"));
  EXPECT_FALSE(c.nonNegative("noise_m", -0.5, "m"));
  EXPECT_FALSE(c.nonNegative("noise", kNaN));
  EXPECT_FALSE(c.finite("mean", kNaN));
  ASSERT_EQ(out.size(), 5u);
  expectError(out[0], "rate_hz", "0", "a finite number > 0");
  expectError(out[1], "gain", "inf", "a finite number > 0 1/s");
  expectError(out[2], "noise_m", "-0.5", "a finite number ≥ 0 m");
  expectError(out[3], "noise", "nan", "a finite number ≥ 0");
  expectError(out[4], "mean", "nan", "a finite number");
}

TEST(FieldChecker, VectorChecksPrintAllThreeComponents) {
  std::vector<FieldError> out;
  FieldChecker c(out);
  EXPECT_TRUE(c.finite("v", Eigen::Vector3d(1.0, -2.0, 3.0), "m"));
  EXPECT_TRUE(c.nonNegative("v", Eigen::Vector3d(0.0, 2.0, 3.0), "N"));
  EXPECT_FALSE(c.finite("mount_B", Eigen::Vector3d(1.0, kNaN, 3.0), "m"));
  EXPECT_FALSE(c.nonNegative("force_std_N", Eigen::Vector3d(0.5, -1.0, 0.0), "N"));
  ASSERT_EQ(out.size(), 2u);
  expectError(out[0], "mount_B", "(1, nan, 3)", "three finite numbers m");
  expectError(out[1], "force_std_N", "(0.5, -1, 0)", "three finite numbers ≥ 0 N");
}

TEST(FieldChecker, ComponentsWithinReportsEachAxis) {
  std::vector<FieldError> out;
  FieldChecker c(out);
  EXPECT_TRUE(c.componentsWithin("p", Eigen::Vector3d(-1.0, 0.0, 1.0), 1.0, "m"));
  EXPECT_FALSE(c.componentsWithin("p", Eigen::Vector3d(2.0, 0.0, kNaN), 1.0, "m"));
  ASSERT_EQ(out.size(), 2u);
  expectError(out[0], "p.x", "2", "a finite number in [-1, 1] m");
  expectError(out[1], "p.z", "nan", "a finite number in [-1, 1] m");
}

TEST(FieldChecker, IntegerChecks) {
  std::vector<FieldError> out;
  FieldChecker c(out);
  EXPECT_TRUE(c.integerRange("n", 1, 1, 10));
  EXPECT_TRUE(c.integerRange("n", 10, 1, 10));
  EXPECT_TRUE(c.integerAtLeast("n", 3, 3));
  EXPECT_FALSE(c.integerRange("samples", 0, 1, 1'000'000));
  EXPECT_FALSE(c.integerAtLeast("min_inliers", 2, 3));
  ASSERT_EQ(out.size(), 2u);
  expectError(out[0], "samples", "0", "an integer in [1, 1000000]");
  expectError(out[1], "min_inliers", "2", "an integer ≥ 3");
}

TEST(FieldChecker, FailAppendsAsGivenInCallOrder) {
  std::vector<FieldError> out{{"earlier", "1", "kept"}};
  FieldChecker c(out);
  c.positive("first", -1.0);
  c.fail("second", "c1=1, c2=2", "n² strictly increasing");
  c.nonNegative("third", -1.0);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[0].field, "earlier");
  EXPECT_EQ(out[1].field, "first");
  expectError(out[2], "second", "c1=1, c2=2", "n² strictly increasing");
  EXPECT_EQ(out[3].field, "third");
}

TEST(FieldChecker, DigitsApplyToValuesAndBounds) {
  std::vector<FieldError> out;
  FieldChecker c(out, 6);
  EXPECT_EQ(c.format(0.123456789), "0.123457");
  c.range("x", 0.123456789, 0.0, 0.1, kInclusive, "s");
  ASSERT_EQ(out.size(), 1u);
  expectError(out[0], "x", "0.123457", "a finite number in [0, 0.1] s");
}

TEST(DescribeErrors, OneLinePerError) {
  const std::vector<FieldError> errors{{"a", "1", "b"}, {"c.d", "nan", "a finite number"}};
  EXPECT_EQ(geaware::model::describeErrors("invalid things:", errors),
            "invalid things:\n  a = 1: expected b\n  c.d = nan: expected a finite number");
  EXPECT_EQ(geaware::model::describeErrors("none:", {}), "none:");
}

/// A parameter set of one field, for model::validated().
struct Gain {
  double k = 1.0;
  [[nodiscard]] std::vector<FieldError> validate() const {
    std::vector<FieldError> out;
    FieldChecker(out).positive("k", k);
    return out;
  }
};

TEST(Validated, ReturnsTheParamsOrThrowsWithEveryError) {
  const Gain good;
  EXPECT_EQ(&geaware::model::validated(good), &good);
  const Gain bad{-2.0};
  try {
    (void)geaware::model::validated(bad);
    FAIL() << "no exception";
  } catch (const geaware::model::InvalidParameters& e) {
    ASSERT_EQ(e.errors().size(), 1u);
    expectError(e.errors()[0], "k", "-2", "a finite number > 0");
    EXPECT_STREQ(e.what(), "invalid vehicle parameters:\n  k = -2: expected a finite number > 0");
  }
}

}  // namespace
