#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/filters/colorize.h>
#include <pc/io/text.h>

namespace pc::filters {
namespace {

TEST(Colorize, ViridisEndsAndMiddleAreMatplotlibs) {
    // matplotlib's viridis(0), viridis(0.5), viridis(1) as 8-bit (68,1,84), (33,145,140),
    // (253,231,37); ours samples OpenCV's table of it: within one step.
    const auto near = [](Rgb8 a, Rgb8 b) {
        for (int c = 0; c < 3; ++c) {
            if (std::abs(a[c] - b[c]) > 1) {
                return false;
            }
        }
        return true;
    };
    EXPECT_TRUE(near(viridis(0), {68, 1, 84}));
    EXPECT_TRUE(near(viridis(0.5), {33, 145, 140}));
    EXPECT_TRUE(near(viridis(1), {253, 231, 37}));
    EXPECT_EQ(viridis(-3), viridis(0));  // clamped
    EXPECT_EQ(viridis(7), viridis(1));
    EXPECT_EQ(viridis(NAN), (Rgb8{160, 160, 160}));
    // Lightness rises along the map (what makes it readable in grey): green channel monotone.
    for (double t = 0; t < 0.99; t += 0.01) {
        EXPECT_LE(viridis(t)[1], viridis(t + 0.01)[1]) << t;
    }
}

TEST(Colorize, LabelsGetDistinctColoursAndNoiseGrey) {
    EXPECT_EQ(label_color(0), (Rgb8{160, 160, 160}));
    std::set<Rgb8> seen;
    for (std::uint32_t l = 1; l <= 50; ++l) {
        seen.insert(label_color(l));
    }
    EXPECT_EQ(seen.size(), 50u);
    // Neighbouring labels are far apart in colour (the golden-ratio step).
    for (std::uint32_t l = 1; l < 50; ++l) {
        const Rgb8 a = label_color(l), b = label_color(l + 1);
        EXPECT_GT(std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]), 60) << l;
    }
}

TEST(Colorize, AFieldThroughTheMapWithItsRangeAndPercentiles) {
    const io::Blob b =
        io::parse_text("x y z w label\n0 0 0 0 1\n1 0 0 5 2\n2 0 0 10 0\n3 0 0 nan 1\n").blob;
    const Colorized given = colorize(b, {.by = "w", .range = std::array<double, 2>{0, 10}});
    EXPECT_EQ(given.colors[0], viridis(0));
    EXPECT_EQ(given.colors[1], viridis(0.5));
    EXPECT_EQ(given.colors[2], viridis(1));
    EXPECT_EQ(given.colors[3], (Rgb8{160, 160, 160}));  // NaN
    // Default range: numpy.percentile([0, 5, 10], [2, 98]) = 0.2, 9.8.
    const Colorized auto_range = colorize(b, {.by = "w"});
    EXPECT_NEAR(auto_range.lo, 0.2, 1e-12);
    EXPECT_NEAR(auto_range.hi, 9.8, 1e-12);
    const Colorized by_x = colorize(b, {.by = "x", .range = std::array<double, 2>{0, 3}});
    EXPECT_EQ(by_x.colors[3], viridis(1));
    const Colorized labels = colorize(b, {.by = "label"});
    EXPECT_EQ(labels.colors[0], labels.colors[3]);  // same label, same colour
    EXPECT_EQ(labels.colors[2], label_color(0));
    EXPECT_EQ(packed({Rgb8{1, 2, 3}})[0], 0x010203u);
}

TEST(Colorize, RefusesWhatItCannotColourBy) {
    const io::Blob b = io::parse_text("x y z r g b\n0 0 0 1 2 3\n").blob;
    EXPECT_THROW((void)colorize(b, {.by = "opacity"}), IoError);
    EXPECT_THROW((void)colorize(b, {.by = "rgb"}), IoError);  // packed colour: not a number
    EXPECT_THROW((void)colorize(b, {.by = "x", .range = std::array<double, 2>{1, 1}}),
                 InvalidArgument);
}

}  // namespace
}  // namespace pc::filters
