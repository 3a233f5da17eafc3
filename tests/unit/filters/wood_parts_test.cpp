#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/filters/wood_parts.h>

namespace pc::filters {
namespace {

// Colours of the tests (sRGB in [0, 1]): tan fruit, dark brown bark, white.
constexpr io::Rgb kTan{0.62f, 0.50f, 0.36f};
constexpr io::Rgb kBark{0.25f, 0.17f, 0.12f};
constexpr io::Rgb kWhite{1, 1, 1};

/// A count to clean: parts appended with their points' colour.
struct Count {
    std::vector<io::Rgb> colours;
    std::vector<std::uint32_t> labels;
    /// Appends `points` points of label `label`, coloured `c` (each channel moved by `jitter`).
    void add(std::uint32_t label, int points, io::Rgb c, float jitter = 0) {
        for (int i = 0; i < points; ++i) {
            colours.push_back({c.r + jitter, c.g + jitter, c.b - jitter});
            labels.push_back(label);
        }
    }
};

/// Every point of `c` kept by `r` exactly where its part is one of the fruit, 1..`fruit`.
void expect_fruit_kept(const WoodPartsResult& r, const Count& c, std::uint32_t fruit) {
    for (std::size_t i = 0; i < c.labels.size(); ++i) {
        const bool fruit_point = c.labels[i] >= 1 && c.labels[i] <= fruit;
        EXPECT_EQ(r.labels[i] != 0, fruit_point) << "point " << i << " of part " << c.labels[i];
    }
}

/// 40 tan fruit of 100 points, their colours a little apart (parts 1..40), and noise (label 0).
Count fruit() {
    Count c;
    for (std::uint32_t l = 1; l <= 40; ++l) {
        c.add(l, 100, kTan, 0.002f * static_cast<float>(l % 5));
    }
    c.add(0, 50, kBark);
    return c;
}

TEST(WoodParts, CielabOfKnownColours) {
    // References: CIE 1976 L*a*b* of sRGB white, black and primaries (D65)
    const auto near = [](std::array<double, 3> got, std::array<double, 3> want) {
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(got[k], want[k], 0.05) << "channel " << k;
        }
    };
    near(cielab({1, 1, 1}), {100, 0, 0});
    near(cielab({0, 0, 0}), {0, 0, 0});
    near(cielab({1, 0, 0}), {53.24, 80.09, 67.20});
    near(cielab({0, 1, 0}), {87.73, -86.18, 83.18});
    near(cielab({0, 0, 1}), {32.30, 79.19, -107.86});
}

TEST(WoodParts, TheWoodAndThePartsColouredLikeItAreDropped) {
    // The trunk: one part of 5000 points (50 times the median part, 100), bark brown; 6 bark
    // pieces of 100 points beside the 40 fruit.
    Count c = fruit();
    c.add(41, 5001, kBark);
    for (std::uint32_t l = 42; l < 48; ++l) {
        c.add(l, 100, kBark, 0.01f);
    }
    const WoodPartsResult r = wood_parts(c.colours, c.labels);
    EXPECT_EQ(r.giants, 1u);
    EXPECT_EQ(r.dropped, 6u);
    EXPECT_EQ(r.count, 40u);
    EXPECT_GT(r.fruit_colour_spread, 0);
    expect_fruit_kept(r, c, 40);
}

TEST(WoodParts, BarkPiecesOutnumberingTheFruitAreDropped) {
    // 20 fruit and 30 bark pieces of 100 points (the median part a bark piece), a trunk of 5001:
    // the fruit's colour is found from the parts far from the trunk's, not the median part's.
    Count c;
    for (std::uint32_t l = 1; l <= 20; ++l) {
        c.add(l, 100, kTan, 0.003f * static_cast<float>(l % 4));
    }
    for (std::uint32_t l = 21; l <= 50; ++l) {
        c.add(l, 100, kBark, 0.004f * static_cast<float>(l % 3));
    }
    c.add(51, 5001, kBark);
    const WoodPartsResult r = wood_parts(c.colours, c.labels);
    EXPECT_EQ(r.giants, 1u);
    EXPECT_EQ(r.dropped, 30u);
    EXPECT_EQ(r.count, 20u);
    expect_fruit_kept(r, c, 20);
}

TEST(WoodParts, WithoutAPartOfTheWoodsSizeNothingIsDropped) {
    // The same bark pieces, but the trunk holds 4999 points: under 50 times the median part
    // (and the bark, coloured apart, holds most points: no pieces)
    Count c = fruit();
    c.add(41, 4999, kBark);
    for (std::uint32_t l = 42; l < 48; ++l) {
        c.add(l, 100, kBark);
    }
    const WoodPartsResult r = wood_parts(c.colours, c.labels);
    EXPECT_EQ(r.giants, 0u);
    EXPECT_EQ(r.dropped, 0u);
    EXPECT_EQ(r.count, 47u);
    EXPECT_EQ(r.fruit_colour_spread, 0);
}

TEST(WoodParts, AGiantHoldingFewOfThePointsIsNoWood) {
    // 400 parts of 100 points beside one of 5001 (over 50 times the median part, but 11 % of
    // the points: a merged mass of leaves, not a tree's wood), 100 of them coloured as it is
    Count c;
    for (std::uint32_t l = 1; l <= 400; ++l) {
        c.add(l, 100, l <= 300 ? kTan : kBark);
    }
    c.add(401, 5001, kBark);
    const WoodPartsResult r = wood_parts(c.colours, c.labels, {.stray_share = 0});
    EXPECT_EQ(r.giants, 0u);
    EXPECT_EQ(r.dropped, 0u);
    EXPECT_EQ(r.count, 401u);
    // ... unless the share asked for is lower
    EXPECT_EQ(wood_parts(c.colours, c.labels, {.share = 0.1, .stray_share = 0}).count, 300u);
}

TEST(WoodParts, WithoutAGiantSmallPartsColouredApartFromMostAreDropped) {
    // Thin wood cut into pieces by fruit centres: 40 tan fruit of 100 points, 12 bark pieces of
    // 40 (no part of the wood's size). The bark pieces lie far more than 4 times the parts'
    // spread from their median colour, hold 11 % of the points and are smaller: they go.
    Count c = fruit();
    for (std::uint32_t l = 41; l <= 52; ++l) {
        c.add(l, 40, kBark, 0.005f * static_cast<float>(l % 3));
    }
    const WoodPartsResult r = wood_parts(c.colours, c.labels);
    EXPECT_EQ(r.giants, 0u);
    EXPECT_EQ(r.dropped, 12u);
    EXPECT_EQ(r.count, 40u);
    expect_fruit_kept(r, c, 40);
    // Off (stray_share 0), every part stays.
    EXPECT_EQ(wood_parts(c.colours, c.labels, {.stray_share = 0}).count, 52u);
}

TEST(WoodParts, WithoutAGiantPartsColouredApartStayWhereTheyAreNoSmallerOrHoldMost) {
    // Fruit of a second colour (as large as the others: ripe and unripe fruit, or green fruit
    // outnumbered by the leaves kept beside them) stay ...
    Count c = fruit();
    for (std::uint32_t l = 41; l <= 52; ++l) {
        c.add(l, 100, kBark);
    }
    EXPECT_EQ(wood_parts(c.colours, c.labels).count, 52u);
    // ... and so do small parts coloured apart that hold half the points or more.
    Count d;
    for (std::uint32_t l = 1; l <= 30; ++l) {
        d.add(l, 100, kTan);
    }
    for (std::uint32_t l = 31; l <= 40; ++l) {
        d.add(l, 99, kBark);
    }
    for (std::uint32_t l = 41; l <= 45; ++l) {
        d.add(l, 500, kBark);
    }
    const WoodPartsResult r = wood_parts(d.colours, d.labels);
    EXPECT_EQ(r.dropped, 0u);
    EXPECT_EQ(r.count, 45u);
}

TEST(WoodParts, AGiantColouredAsTheFruitAreIsKept) {
    // Mask colours (fruit, leaked wood and a merged bunch all white): no colour to tell by.
    Count c;
    for (std::uint32_t l = 1; l <= 40; ++l) {
        c.add(l, 100, kWhite);
    }
    c.add(41, 8000, kWhite);
    const WoodPartsResult r = wood_parts(c.colours, c.labels);
    EXPECT_EQ(r.giants, 0u);
    EXPECT_EQ(r.count, 41u);
    for (std::size_t i = 0; i < c.labels.size(); ++i) {
        ASSERT_NE(r.labels[i], 0u) << "point " << i << " of part " << c.labels[i] << " dropped";
    }
}

TEST(WoodParts, PartsNearerTheFruitsColourStay) {
    // A fruit part halfway-and-a-bit towards the bark's colour stays; one past halfway goes.
    Count c = fruit();
    c.add(41, 6000, kBark);
    const auto mix = [](float t) {
        return io::Rgb{kTan.r + t * (kBark.r - kTan.r), kTan.g + t * (kBark.g - kTan.g),
                       kTan.b + t * (kBark.b - kTan.b)};
    };
    c.add(42, 100, mix(0.35f));
    c.add(43, 100, mix(0.75f));
    const WoodPartsResult r = wood_parts(c.colours, c.labels);
    EXPECT_EQ(r.giants, 1u);
    EXPECT_EQ(r.dropped, 1u);
    EXPECT_EQ(r.count, 41u);
    EXPECT_NE(r.labels[c.labels.size() - 101], 0u);  // the part at 0.35 kept
    EXPECT_EQ(r.labels.back(), 0u);                  // the part at 0.75 dropped
}

TEST(WoodParts, BlushedFruitPastTheBarksSpreadStay) {
    // Yellow-green fruit blushed red (parts 1..40, each part's colour the mix of its blush, most
    // of them little blushed: (k / 39)³, k = 0..39) beside reddish-brown bark (the giant, 6000
    // points) and 6 bark pieces spread about its colour (up to 6 ΔE). The 9 most blushed
    // fruit lie nearer the bark's colour than the fruit's median colour does (26-39 ΔE from
    // the bark's; the median colour about 60), past a gap from the bark pieces: they stay.
    constexpr io::Rgb kYellowGreen{160 / 255.0f, 185 / 255.0f, 70 / 255.0f};
    constexpr io::Rgb kRed{185 / 255.0f, 40 / 255.0f, 45 / 255.0f};
    constexpr io::Rgb kRedBark{120 / 255.0f, 65 / 255.0f, 55 / 255.0f};
    Count c;
    for (std::uint32_t l = 1; l <= 40; ++l) {
        const float t = std::pow(static_cast<float>(l - 1) / 39, 3.0f);
        c.add(l, 100,
              {kYellowGreen.r + t * (kRed.r - kYellowGreen.r),
               kYellowGreen.g + t * (kRed.g - kYellowGreen.g),
               kYellowGreen.b + t * (kRed.b - kYellowGreen.b)});
    }
    c.add(41, 6000, kRedBark);
    for (std::uint32_t l = 42; l < 48; ++l) {
        c.add(l, 100, kRedBark, 0.004f * static_cast<float>(l - 42));
    }
    const WoodPartsResult r = wood_parts(c.colours, c.labels);
    EXPECT_EQ(r.giants, 1u);
    EXPECT_EQ(r.dropped, 6u);
    EXPECT_EQ(r.count, 40u);
    expect_fruit_kept(r, c, 40);
    // Every part nearer the bark's colour than the fruit's going (no gap), the reddest go too.
    const WoodPartsResult nearest = wood_parts(c.colours, c.labels, {.gap = 0});
    EXPECT_EQ(nearest.giants, 1u);
    EXPECT_LT(nearest.count, 35u);
}

TEST(WoodParts, PointsWithoutAColourAreLeftOutOfTheMeans) {
    Count c = fruit();
    c.add(41, 6000, kBark);
    c.add(42, 100, kBark);
    c.add(42, 100, {NAN, 0, 0});  // half of a bark piece without colour: still bark
    const WoodPartsResult r = wood_parts(c.colours, c.labels);
    EXPECT_EQ(r.giants, 1u);
    EXPECT_EQ(r.dropped, 1u);
    EXPECT_EQ(r.count, 40u);
}

TEST(WoodParts, RefusesMismatchedSizesAndBadParameters) {
    Count c = fruit();
    c.colours.pop_back();
    EXPECT_THROW((void)wood_parts(c.colours, c.labels), InvalidArgument);
    const Count d = fruit();
    EXPECT_THROW((void)wood_parts(d.colours, d.labels, {.giant = 1}), InvalidArgument);
    EXPECT_THROW((void)wood_parts(d.colours, d.labels, {.share = 1.5}), InvalidArgument);
    EXPECT_THROW((void)wood_parts(d.colours, d.labels, {.apart = 0}), InvalidArgument);
    EXPECT_THROW((void)wood_parts(d.colours, d.labels, {.apart = NAN}), InvalidArgument);
    EXPECT_THROW((void)wood_parts(d.colours, d.labels, {.gap = 0.5}), InvalidArgument);
    EXPECT_THROW((void)wood_parts(d.colours, d.labels, {.gap = INFINITY}), InvalidArgument);
    EXPECT_THROW((void)wood_parts(d.colours, d.labels, {.stray_share = -0.1}), InvalidArgument);
    EXPECT_THROW((void)wood_parts(d.colours, d.labels, {.stray_share = NAN}), InvalidArgument);
}

}  // namespace
}  // namespace pc::filters
