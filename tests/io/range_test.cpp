// SPDX-License-Identifier: BSD-3-Clause
// "FROM:TO:STEP" ranges from the command line (io/range): the values include TO despite
// floating-point steps, and every malformed text is rejected with a message naming the option.

#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "geaware/io/range.hpp"

namespace {

namespace io = geaware::io;

// Rounding of from + i·step over a handful of steps stays within a few ulps of 1; 1e-12 is
// far above that and far below any step a user would give.
constexpr double kRoundingTolerance = 1e-12;

TEST(Range, DecimalStepReachesTo) {
  // 0.1 is not representable: (0.5 − 0.1)/0.1 is 3.9999999999999996, which must still give
  // five values and not four.
  const io::Range r = io::parseRange("0.1:0.5:0.1", "--heights");
  EXPECT_DOUBLE_EQ(r.from, 0.1);
  EXPECT_DOUBLE_EQ(r.to, 0.5);
  EXPECT_DOUBLE_EQ(r.step, 0.1);
  const std::vector<double> v = r.values();
  ASSERT_EQ(v.size(), 5u);
  for (std::size_t i = 0; i < v.size(); ++i) {
    EXPECT_NEAR(v[i], 0.1 + 0.1 * static_cast<double>(i), kRoundingTolerance) << i;
  }
  EXPECT_NEAR(v.back(), 0.5, kRoundingTolerance);
}

TEST(Range, OtherDecimalSteps) {
  EXPECT_EQ(io::parseRange("0:0.3:0.1", "--heights").values().size(), 4u);
  EXPECT_NEAR(io::parseRange("0:0.3:0.1", "--heights").values().back(), 0.3, kRoundingTolerance);
  const auto v = io::parseRange("0.072:2.0:0.05", "--heights").values();
  ASSERT_EQ(v.size(), 39u);  // 0.072 … 1.972; 2.022 would pass TO
  EXPECT_NEAR(v.back(), 1.972, kRoundingTolerance);
}

TEST(Range, StepThatDoesNotDivideStopsBeforeTo) {
  const auto v = io::parseRange("0:1:0.3", "--heights").values();
  ASSERT_EQ(v.size(), 4u);
  EXPECT_NEAR(v.back(), 0.9, kRoundingTolerance);
}

TEST(Range, SingleNumberIsOneValue) {
  const io::Range r = io::parseRange("0.25", "--heights");
  EXPECT_EQ(r.values(), std::vector<double>{0.25});
  EXPECT_EQ(io::parseRange("-3", "--tilt").values(), std::vector<double>{-3.0});
}

TEST(Range, EqualEndsAreOneValue) {
  EXPECT_EQ(io::parseRange("0.3:0.3:0.1", "--heights").values(), std::vector<double>{0.3});
}

TEST(Range, ExponentNotationIsAccepted) {
  const auto v = io::parseRange("1e-1:2e-1:5e-2", "--heights").values();
  ASSERT_EQ(v.size(), 3u);
  EXPECT_NEAR(v.back(), 0.2, kRoundingTolerance);
}

/// The message of the std::invalid_argument that parsing `text` throws ("" when none).
std::string rejectionMessage(const std::string& text, const std::string& option,
                             std::size_t max_values = 1'000'000) {
  try {
    (void)io::parseRange(text, option, max_values);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

TEST(Range, MalformedTextsAreRejectedNamingTheOption) {
  for (const char* text : {"1:2", "a:b:c", "1:2:0", "2:1:1", "1:2:-1", "nan:1:1", "1:2:3:4", "",
                           "1::1", "1:2:", " 1:2:1", "1:inf:1", "0x1:2:1", "1:2:1 ", "abc"}) {
    const std::string message = rejectionMessage(text, "--heights");
    ASSERT_FALSE(message.empty()) << "'" << text << "' was accepted";
    EXPECT_NE(message.find("--heights"), std::string::npos) << message;
    EXPECT_NE(message.find(std::string("'") + text + "'"), std::string::npos)
        << "the message should quote the text: " << message;
  }
}

TEST(Range, MessagesSayWhatIsWrong) {
  EXPECT_NE(rejectionMessage("1:2:0", "--tilt").find("STEP must be > 0"), std::string::npos);
  EXPECT_NE(rejectionMessage("2:1:1", "--tilt").find("TO must be"), std::string::npos);
  EXPECT_NE(rejectionMessage("a:2:1", "--tilt").find("FROM 'a'"), std::string::npos);
  EXPECT_NE(rejectionMessage("1:2:3:4", "--tilt").find("FROM:TO:STEP"), std::string::npos);
}

TEST(Range, HugeRangesAreRejected) {
  EXPECT_FALSE(rejectionMessage("0:1e9:1", "--heights").empty());
  // A tiny step overflows any count; it must be rejected, not wrapped into a small size_t.
  EXPECT_FALSE(rejectionMessage("0:1:1e-300", "--heights").empty());
  EXPECT_FALSE(rejectionMessage("-1e308:1e308:1e-308", "--heights").empty());
  EXPECT_NE(rejectionMessage("0:1e9:1", "--heights").find("more than 1000000 values"),
            std::string::npos);
}

TEST(Range, MaxValuesIsInclusive) {
  EXPECT_EQ(io::parseRange("0:4:1", "--speeds", 5).values().size(), 5u);
  EXPECT_FALSE(rejectionMessage("0:5:1", "--speeds", 5).empty());
}

}  // namespace
