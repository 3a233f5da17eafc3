#include <charconv>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include <pc/core/error.h>

namespace pc {
namespace {

TEST(Format, NumberReadsBackToTheSameDouble) {
    EXPECT_EQ(format_number(0.05), "0.05");
    EXPECT_EQ(format_number(92.28739930133324), "92.28739930133324");
    EXPECT_EQ(format_number(-3), "-3");
}

TEST(Format, RoundedKeepsThreeSignificantDigitsAndWholeNumbersWhole) {
    EXPECT_EQ(format_rounded(92.28739930133324), "92.3");
    EXPECT_EQ(format_rounded(0.006724499740953404), "0.00672");
    EXPECT_EQ(format_rounded(0.035), "0.035");
    EXPECT_EQ(format_rounded(16.5), "16.5");
    EXPECT_EQ(format_rounded(1234.5), "1235");  // not "1.23e+03"
    EXPECT_EQ(format_rounded(-1234.4), "-1234");
    EXPECT_EQ(format_rounded(0), "0");
    EXPECT_EQ(format_rounded(0.123456, 5), "0.12346");
}

TEST(Format, RoundedIsWithinHalfAUnitOfTheLastDigit) {
    // Invariant: three digits read back to within 0.5 % of the value, over ten magnitudes.
    for (double v = 1.234567e-4; v < 1e6; v *= 3.7) {
        const std::string text = format_rounded(v);
        double back = 0;
        std::from_chars(text.data(), text.data() + text.size(), back);
        EXPECT_LE(std::abs(back - v), 0.5e-2 * v) << text;
    }
}

}  // namespace
}  // namespace pc
