#include <cmath>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/filters/range_filter.h>
#include <pc/io/text.h>

namespace pc::filters {
namespace {

/// Five points: x 0..4; opacity 0.05, 0.1, 0.5, nan, 0.9; label 0 1 2 0 3 (U 4).
io::Blob cloud() {
    return io::parse_text(
               "x y z opacity label\n0 0 0 0.05 0\n1 0 0 0.1 1\n2 0 0 0.5 2\n"
               "3 0 0 nan 0\n4 0 0 0.9 3\n")
        .blob;
}

std::vector<std::uint32_t> keep(const std::string& limits) {
    return range_filter(cloud(), {.ranges = parse_ranges(limits)});
}

using Ids = std::vector<std::uint32_t>;

TEST(RangeFilter, BoundsIncludedWithSquareBracketsExcludedWithRound) {
    EXPECT_EQ(keep("opacity[0.1:]"), (Ids{1, 2, 4}));  // 0.1 included; NaN outside
    EXPECT_EQ(keep("opacity(0.1:]"), (Ids{2, 4}));     // 0.1 excluded
    EXPECT_EQ(keep("opacity[:0.5)"), (Ids{0, 1}));
    EXPECT_EQ(keep("x[1:3]"), (Ids{1, 2, 3}));
    EXPECT_EQ(keep("x[:]"), (Ids{0, 1, 2, 3, 4}));
}

TEST(RangeFilter, NegationKeepsWhatLiesOutsideNonFiniteIncluded) {
    EXPECT_EQ(keep("label![0:0]"), (Ids{1, 2, 4}));
    EXPECT_EQ(keep("opacity![0.1:]"), (Ids{0, 3}));  // NaN is outside [0.1, inf)
}

TEST(RangeFilter, OneFieldIsOrAcrossFieldsAndAsPdal) {
    EXPECT_EQ(keep("label[1:1],label[3:3]"), (Ids{1, 4}));
    EXPECT_EQ(keep("label[1:3],opacity[0.5:]"), (Ids{2, 4}));
    // A brute-force check of the rule over every pair of ranges on two fields.
    const io::Blob b = cloud();
    for (double cut : {0.0, 0.1, 0.5, 0.9}) {
        const Ids got = keep("label[1:2],label[3:3],opacity[" + std::to_string(cut) + ":]");
        Ids want;
        const double opacity[] = {0.05, 0.1, 0.5, NAN, 0.9};
        const int label[] = {0, 1, 2, 0, 3};
        for (std::uint32_t i = 0; i < 5; ++i) {
            const bool l = (label[i] >= 1 && label[i] <= 2) || label[i] == 3;
            // opacity is F 4: values and bounds compare as floats
            const bool o = std::isfinite(opacity[i]) &&
                           static_cast<float>(opacity[i]) >= static_cast<float>(cut);
            if (l && o) {
                want.push_back(i);
            }
        }
        EXPECT_EQ(got, want) << cut;
    }
}

TEST(RangeFilter, BadLimitsSayWhatWasExpected) {
    for (const char* bad :
         {"opacity", "opacity[0.1]", "[0:1]", "x[a:1]", "x[2:1]", "x[0:1", "x[0:1:2]", ""}) {
        EXPECT_THROW((void)parse_ranges(bad), InvalidArgument) << bad;
    }
    EXPECT_THROW((void)keep("missing[0:1]"), IoError);
}

}  // namespace
}  // namespace pc::filters
