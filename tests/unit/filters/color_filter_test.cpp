#include <cmath>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/filters/color_filter.h>

namespace pc::filters {
namespace {

// Crafted colours: their hue, saturation, value and mean are known exactly.
const std::vector<io::Rgb> kColours = {
    {1, 0, 0},           // 0: red, hue 0, mean 1/3
    {0, 1, 0},           // 1: green, hue 120
    {0, 0, 1},           // 2: blue, hue 240
    {1, 0, 1},           // 3: magenta, hue 300
    {0.5f, 0.5f, 0.5f},  // 4: grey, no hue, mean 0.5 exactly
    {1, 1, 1},           // 5: white, mean 1
    {0.1f, 0.1f, 0.1f},  // 6: dark
    {1, 0.25f, 0},       // 7: orange, hue 15
    {NAN, 1, 1},         // 8: broken colour
};

Indices run(const ColorFilterParams& p) { return color_filter(kColours, p).kept; }

TEST(ColorFilter, MinMeanIsStrict) {
    // magenta 2/3 and white 1 pass; grey's mean is exactly 0.5, which is not > 0.5
    EXPECT_EQ(run({.min_mean = 0.5}), (Indices{3, 5}));
    EXPECT_EQ(run({.min_mean = 0.3}), (Indices{0, 1, 2, 3, 4, 5, 7}));
}

TEST(ColorFilter, MinValueUsesTheBrightestChannel) {
    EXPECT_EQ(run({.min_value = 0.5}), (Indices{0, 1, 2, 3, 5, 7}));
}

TEST(ColorFilter, HueRangeWrapsThroughZero) {
    EXPECT_EQ(run({.hue_deg = Interval{300, 30}}), (Indices{0, 3, 7}));
    EXPECT_EQ(run({.hue_deg = Interval{100, 250}}), (Indices{1, 2}));
    EXPECT_EQ(run({.hue_deg = Interval{0, 360}}), (Indices{0, 1, 2, 3, 7}));  // grey never matches
}

TEST(ColorFilter, SaturationAndValueIntervalsIncludeTheirEnds) {
    EXPECT_EQ(run({.saturation = Interval{0, 0}}), (Indices{4, 5, 6}));
    EXPECT_EQ(run({.value = Interval{0.1, 0.5}}), (Indices{4, 6}));
}

TEST(ColorFilter, InvertKeepsTheComplement) {
    const Indices kept = run({.min_mean = 0.3});
    const Indices rest = run({.min_mean = 0.3, .invert = true});
    EXPECT_EQ(kept.size() + rest.size(), kColours.size());
    for (auto i : kept) {
        EXPECT_EQ(std::count(rest.begin(), rest.end(), i), 0);
    }
}

TEST(ColorFilter, RejectsBadIntervals) {
    EXPECT_THROW((void)run({.saturation = Interval{0.5, 2}}), InvalidArgument);
    EXPECT_THROW((void)run({.hue_deg = Interval{-10, 30}}), InvalidArgument);
    EXPECT_THROW((void)parse_interval("hue", "10-20"), InvalidArgument);
    EXPECT_EQ(parse_interval("hue", "300:30").lo, 300);
}

}  // namespace
}  // namespace pc::filters
