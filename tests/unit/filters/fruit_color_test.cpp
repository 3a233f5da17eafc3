// choose_fruit_color: the rule read from the colours of a cloud, and the words.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/filters/fruit_color.h>

namespace pc::filters {
namespace {

std::vector<io::Rgb> repeat(std::vector<std::pair<io::Rgb, int>> parts) {
    std::vector<io::Rgb> out;
    for (const auto& [c, n] : parts) {
        out.insert(out.end(), static_cast<std::size_t>(n), c);
    }
    return out;
}

std::size_t kept(const std::vector<io::Rgb>& c, const FruitColorChoice& choice) {
    return choice.rule ? color_filter(c, *choice.rule).kept.size() : c.size();
}

TEST(FruitColor, TwoTonedGreyIsAMaskAndKeepsThePapersRule) {
    const auto c = repeat({{{0.98f, 0.98f, 0.98f}, 300}, {{0.02f, 0.02f, 0.02f}, 700}});
    const FruitColorChoice r = choose_fruit_color(c, {});
    ASSERT_TRUE(r.rule);
    EXPECT_EQ(r.rule->min_mean, 0.5);
    EXPECT_TRUE(r.warnings.empty());
    EXPECT_EQ(kept(c, r), 300u);
}

TEST(FruitColor, EvenGreysCarryNoFruitInformation) {
    std::vector<io::Rgb> c;
    for (int i = 0; i < 1000; ++i) {
        const float v = static_cast<float>(i) / 999;
        c.push_back({v, v, v});
    }
    const FruitColorChoice r = choose_fruit_color(c, {});
    EXPECT_FALSE(r.rule);
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find("cannot tell fruit"), std::string::npos);
}

TEST(FruitColor, GreysInTwoGroupsAreOfferedForTheShapeTest) {
    // Ivory fruit (245, 240, 225: saturation 0.08) beside silver bark (175, 170, 160): both grey,
    // and no two-toned mask (the bark's value 0.69 is a mid grey): no rule, and the warning, but
    // the two groups (value 0.96 and 0.69) are offered, each keeping one of them.
    const io::Rgb ivory{245.0f / 255, 240.0f / 255, 225.0f / 255},
        silver{175.0f / 255, 170.0f / 255, 160.0f / 255};
    const auto c = repeat({{ivory, 400}, {silver, 600}});
    const FruitColorChoice r = choose_fruit_color(c, {});
    EXPECT_FALSE(r.rule);
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find("cannot tell fruit"), std::string::npos);
    ASSERT_EQ(r.classes.size(), 2u) << r.reason;
    std::array<std::size_t, 2> n{color_filter(c, r.classes[0].rule).kept.size(),
                                 color_filter(c, r.classes[1].rule).kept.size()};
    std::sort(n.begin(), n.end());
    EXPECT_EQ(n, (std::array<std::size_t, 2>{400, 600})) << r.classes[0].reason;
}

TEST(FruitColor, NaturalColoursKeepSaturatedNonFoliageOfAnyBrightness) {
    // Dark red (hue 0), shaded purple (hue 313), orange; green leaves (hue 109), grey ground.
    const auto c = repeat({{{0.47f, 0.08f, 0.08f}, 100},
                           {{0.12f, 0.05f, 0.10f}, 100},
                           {{0.92f, 0.55f, 0.18f}, 100},
                           {{0.24f, 0.49f, 0.18f}, 300},
                           {{0.20f, 0.19f, 0.21f}, 200}});
    const FruitColorChoice r = choose_fruit_color(c, {});
    ASSERT_TRUE(r.rule);
    EXPECT_TRUE(r.warnings.empty());
    EXPECT_EQ(kept(c, r), 300u);  // the three fruit colours; the paper's rule keeps 100
    EXPECT_EQ(color_filter(c, {.min_mean = 0.5}).kept.size(), 100u);
}

TEST(FruitColor, AllGreenKeepsEverySaturatedPointAndSaysLeavesStay) {
    const auto c = repeat({{{0.49f, 0.69f, 0.24f}, 100},    // green fruit
                           {{0.24f, 0.49f, 0.18f}, 300},    // leaves
                           {{0.20f, 0.19f, 0.21f}, 100}});  // ground
    const FruitColorChoice r = choose_fruit_color(c, {});
    ASSERT_TRUE(r.rule);
    EXPECT_EQ(kept(c, r), 400u);
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find("leaves were kept"), std::string::npos);
    // The greens are two hues (86 and 109 degrees): each is offered as a class, for the chain to
    // tell fruit from leaves by shape; the classes part the saturated points.
    ASSERT_EQ(r.classes.size(), 2u);
    EXPECT_EQ(color_filter(c, r.classes[0].rule).kept.size(), 100u);
    EXPECT_EQ(color_filter(c, r.classes[1].rule).kept.size(), 300u);
}

/// A fully saturated colour of hue `h` degrees at value 0.6.
io::Rgb hue(double h) {
    const double x = 1 - std::abs(std::fmod(h / 60, 2.0) - 1);
    const int k = static_cast<int>(h / 60) % 6;
    const double r[6] = {1, x, 0, 0, x, 1}, g[6] = {x, 1, 1, x, 0, 0}, b[6] = {0, 0, x, 1, 1, x};
    return {static_cast<float>(0.6 * r[k]), static_cast<float>(0.6 * g[k]),
            static_cast<float>(0.6 * b[k])};
}

TEST(FruitColor, DarkGreenFruitAmongLighterLeavesAreOfferedByValue) {
    // Near-black green fruit (hue 90, value 0.25) among leaves (hue 109, value 0.49): hue is
    // foliage for both, value parts them. A dark colour's hue is noisy: some fruit points stray
    // out of the foliage band (hue 60 here). With 6 % of the saturated points outside the band
    // the rule stays "not foliage" but competes with the two groups of value; with 1 %, nearly
    // every point is green and the groups are offered against keeping every saturated point.
    const io::Rgb fruit{0.1875f, 0.25f, 0.125f}, stray{0.25f, 0.25f, 0.125f},
        leaf{0.235f, 0.49f, 0.176f};
    for (const auto& [strays, competes] : {std::pair{100, true}, std::pair{15, false}}) {
        const auto c = repeat({{fruit, 500}, {stray, strays}, {leaf, 1000}});
        const FruitColorChoice r = choose_fruit_color(c, {});
        ASSERT_EQ(r.classes.size(), 2u) << r.reason;
        EXPECT_EQ(r.rule_competes, competes) << r.reason;
        EXPECT_NE(r.reason.find("values split"), std::string::npos) << r.reason;
        EXPECT_EQ(color_filter(c, r.classes[0].rule).kept.size(), 500u + strays);
        EXPECT_EQ(color_filter(c, r.classes[1].rule).kept.size(), 1000u);
    }
}

TEST(FruitColor, GreenGroupsBesideBarkAreTriedAfterTheRule) {
    // The same dark fruit and leaves beside brown bark (hue 30, saturation 0.5): with a tenth or
    // more of the saturated points outside foliage hue the rule is tried first (it keeps the
    // bark, where the fruit may be), the groups only when its centres claim too few points.
    const io::Rgb fruit{0.1875f, 0.25f, 0.125f}, bark{0.39f, 0.29f, 0.196f},
        leaf{0.235f, 0.49f, 0.176f};
    for (const auto& [barks, first] : {std::pair{600, true}, std::pair{100, false}}) {
        const auto c = repeat({{fruit, 500}, {bark, barks}, {leaf, 1000}});
        const FruitColorChoice r = choose_fruit_color(c, {});
        ASSERT_EQ(r.classes.size(), 2u) << r.reason;
        EXPECT_TRUE(r.rule_competes) << r.reason;
        EXPECT_EQ(r.rule_first, first) << r.reason;
        EXPECT_EQ(color_filter(c, *r.rule).kept.size(), static_cast<std::size_t>(barks));
    }
}

TEST(FruitColor, TheRulesPointsInTwoGroupsAreOfferedForTheShapeTest) {
    // Dark red fruit (hue 357, saturation 0.8) beside brown bark (hue 30, saturation 0.5) and
    // leaves: both pass "saturated and not foliage"; their saturations lie far apart, so the
    // rule's points are offered as two groups, each exactly one of them. One fruit colour alone
    // offers none.
    const io::Rgb fruit{0.39f, 0.078f, 0.098f}, bark{0.39f, 0.29f, 0.196f},
        leaf{0.235f, 0.49f, 0.176f};
    const auto c = repeat({{fruit, 400}, {bark, 600}, {leaf, 1000}});
    const FruitColorChoice r = choose_fruit_color(c, {});
    ASSERT_EQ(r.rule_classes.size(), 2u) << r.reason;
    std::array<std::size_t, 2> n{color_filter(c, r.rule_classes[0].rule).kept.size(),
                                 color_filter(c, r.rule_classes[1].rule).kept.size()};
    std::sort(n.begin(), n.end());
    EXPECT_EQ(n[0], 400u);
    EXPECT_EQ(n[1], 600u);
    EXPECT_TRUE(choose_fruit_color(repeat({{fruit, 400}, {leaf, 1000}}), {}).rule_classes.empty());
}

TEST(FruitColor, EachGroupOfTheRulesPointsOffersItsOwnGroups) {
    // Pink fruit (hue 342, value 0.6) beside bark (hue 30, value 0.45) whose shaded points (value
    // 0.16) have hues near red: hue parts the bark from the fruit with the dark points, and that
    // group's own groups (value) part the fruit from the dark points.
    const io::Rgb fruit{0.6f, 0.33f, 0.411f}, bark{0.45f, 0.348f, 0.2475f},
        dark{0.16f, 0.088f, 0.094f}, leaf{0.235f, 0.49f, 0.176f};
    const auto c = repeat({{fruit, 400}, {bark, 600}, {dark, 300}, {leaf, 1000}});
    const FruitColorChoice r = choose_fruit_color(c, {});
    ASSERT_EQ(r.rule_classes.size(), 2u) << r.reason;
    const auto n = [&](const ColourClass& k) { return color_filter(c, k.rule).kept.size(); };
    const std::size_t with_fruit = n(r.rule_classes[0]) == 700u ? 0 : 1;
    EXPECT_EQ(n(r.rule_classes[with_fruit]), 700u) << r.rule_classes[with_fruit].reason;
    EXPECT_EQ(n(r.rule_classes[1 - with_fruit]), 600u) << r.rule_classes[1 - with_fruit].reason;
    const std::vector<ColourClass>& sub = r.rule_classes[with_fruit].groups;
    ASSERT_EQ(sub.size(), 2u) << r.rule_classes[with_fruit].reason;
    std::array<std::size_t, 2> parts{n(sub[0]), n(sub[1])};
    std::sort(parts.begin(), parts.end());
    EXPECT_EQ(parts[0], 300u) << sub[0].reason;
    EXPECT_EQ(parts[1], 400u) << sub[1].reason;
    EXPECT_TRUE(r.rule_classes[1 - with_fruit].groups.empty());
}

TEST(FruitColor, OneGroupOfGreensIsNotCutInTwo) {
    // Green hues spread as a bell (normal, sigma 8 degrees, by its quantiles) or evenly over 60
    // degrees: Otsu's threshold separates 64 % and 75 % of their variance, under 80 %: one group.
    // Two groups 4 sigma apart separate 80 %: offered.
    const auto greens = [](auto hue_at) {
        std::vector<io::Rgb> c;
        for (int i = 0; i < 2000; ++i) {
            c.push_back(hue(hue_at((i + 0.5) / 2000)));
        }
        return c;
    };
    const auto bell = [](double q, double mean) {
        // the normal quantile by bisection on erfc
        double lo = -6, hi = 6;
        for (int k = 0; k < 60; ++k) {
            const double mid = (lo + hi) / 2;
            (0.5 * std::erfc(-mid / std::sqrt(2.0)) < q ? lo : hi) = mid;
        }
        return mean + 8 * lo;
    };
    EXPECT_TRUE(
        choose_fruit_color(greens([&](double q) { return bell(q, 110); }), {}).classes.empty());
    EXPECT_TRUE(
        choose_fruit_color(greens([](double q) { return 80 + 60 * q; }), {}).classes.empty());
    const FruitColorChoice two = choose_fruit_color(
        greens([&](double q) { return q < 0.5 ? bell(2 * q, 95) : bell(2 * q - 1, 137); }), {});
    EXPECT_EQ(two.classes.size(), 2u);
}

/// `n` colours around `base` (0..255): brightness × 0.85..1.1, each channel ± 8, as pc_synth
/// paints.
std::vector<io::Rgb> around(std::array<double, 3> base, int n, std::mt19937& rng) {
    std::uniform_real_distribution<double> tone(0.85, 1.1), jitter(-8, 8);
    std::vector<io::Rgb> out;
    for (int i = 0; i < n; ++i) {
        const double t = tone(rng);
        const auto ch = [&](double v) {
            return static_cast<float>(std::clamp(v * t + jitter(rng), 0.0, 255.0) / 255);
        };
        out.push_back({ch(base[0]), ch(base[1]), ch(base[2])});
    }
    return out;
}

TEST(FruitColor, PaleFruitAreKeptWhereTheColoursHaveTheirOwnGap) {
    // Cream fruit (225, 215, 170: saturation 0.24, so about half its points under 0.25) among
    // leaves, over dark grey ground (saturation 0.03-0.2): the non-foliage saturations part
    // between the two, and the fruit is kept whole.
    std::mt19937 rng(7);
    auto c = around({225, 215, 170}, 900, rng);
    const auto leaves = around({60, 125, 45}, 600, rng);
    std::vector<io::Rgb> ground;  // greys 10..70 of 255, a channel 1 above and 1 below
    for (int i = 0; i < 100; ++i) {
        const float v = static_cast<float>(10 + 0.6 * i);
        ground.push_back({(v + 1) / 255, v / 255, (v - 1) / 255});
    }
    c.insert(c.end(), leaves.begin(), leaves.end());
    c.insert(c.end(), ground.begin(), ground.end());
    const FruitColorChoice r = choose_fruit_color(c, {});
    ASSERT_TRUE(r.rule);
    const auto kept = color_filter(c, *r.rule).kept;
    const auto fruit = std::count_if(kept.begin(), kept.end(), [](auto i) { return i < 900; });
    EXPECT_GE(fruit, 890) << r.reason;
    EXPECT_LE(kept.size() - static_cast<std::size_t>(fruit), 10u) << r.reason;  // near-black
    EXPECT_NE(r.reason.find("the colours' own gap"), std::string::npos) << r.reason;
    // Without the ground nothing but the fruit is outside foliage: one group, the floor stays
    // 0.25 (about half the fruit's points go: the cloud gives no gap to go by).
    c.resize(1500);
    const FruitColorChoice alone = choose_fruit_color(c, {});
    EXPECT_EQ(alone.rule->saturation->lo, 0.25) << alone.reason;
    // Saturated red fruit over the same ground: 0.25 cuts nothing of the fruit's group, the floor
    // stays.
    auto red = around({200, 40, 40}, 900, rng);
    red.insert(red.end(), ground.begin(), ground.end());
    EXPECT_EQ(choose_fruit_color(red, {}).rule->saturation->lo, 0.25);
}

TEST(FruitColor, PaleFruitUnderBrownBarkAreOfferedAsThePalePoints) {
    // Cream fruit (235, 225, 195: saturation 0.17) among leaves beside brown bark (100, 75, 50:
    // 0.5): the fruit are the lower of the two saturation groups, so the rule keeps the bark; the
    // points under the split of the two are offered (`pale`), the fruit's whole and no bark.
    std::mt19937 rng(11);
    auto c = around({235, 225, 195}, 900, rng);
    const auto leaves = around({60, 125, 45}, 600, rng);
    const auto bark = around({100, 75, 50}, 300, rng);
    c.insert(c.end(), leaves.begin(), leaves.end());
    c.insert(c.end(), bark.begin(), bark.end());
    const FruitColorChoice r = choose_fruit_color(c, {});
    ASSERT_TRUE(r.rule);
    ASSERT_TRUE(r.pale) << r.reason;
    const auto kept = color_filter(c, r.pale->rule).kept;
    const auto fruit = std::count_if(kept.begin(), kept.end(), [](auto i) { return i < 900; });
    EXPECT_GE(fruit, 890) << r.pale->reason;
    EXPECT_EQ(kept.size(), static_cast<std::size_t>(fruit)) << r.pale->reason;
    // the line or the split of the two groups, whichever is higher; under the bark's
    EXPECT_GE(r.pale->rule.saturation->hi, 0.25);
    EXPECT_LT(r.pale->rule.saturation->hi, 0.45);
    // the rule keeps the bark and hardly any fruit
    const auto by_rule = color_filter(c, *r.rule).kept;
    EXPECT_LT(std::count_if(by_rule.begin(), by_rule.end(), [](auto i) { return i < 900; }), 50);
    // Saturated fruit and leaves only: no pale points, none offered.
    auto red = around({200, 40, 40}, 900, rng);
    red.insert(red.end(), leaves.begin(), leaves.end());
    EXPECT_FALSE(choose_fruit_color(red, {}).pale);
}

TEST(FruitColor, PaleFruitBesideBarkAsPaleAsThemAreAGroupOfThePalePoints) {
    // Cream fruit (235, 225, 195: saturation 0.17) beside grey-brown bark (110, 100, 90: 0.18)
    // and bluish-grey ground (150, 160, 175), all three pale points. The ground's values lie
    // between the fruit's and the bark's, so their hues part first, the ground from the rest;
    // within the warm hues the values part the lit fruit from the dark bark: a group of a group
    // holds the fruit whole and no bark.
    std::mt19937 rng(13);
    auto c = around({235, 225, 195}, 900, rng);
    const auto leaves = around({60, 125, 45}, 600, rng);
    const auto bark = around({110, 100, 90}, 1200, rng);
    const auto ground = around({150, 160, 175}, 900, rng);
    for (const auto& part : {leaves, bark, ground}) {
        c.insert(c.end(), part.begin(), part.end());
    }
    const FruitColorChoice r = choose_fruit_color(c, {});
    ASSERT_TRUE(r.pale) << r.reason;
    const auto fruit_alone = [&](const ColourClass& k) {
        const auto kept = color_filter(c, k.rule).kept;
        return kept.size() >= 890 &&
               std::all_of(kept.begin(), kept.end(), [](auto i) { return i < 900; });
    };
    EXPECT_FALSE(fruit_alone(*r.pale));
    bool found = false;
    for (const ColourClass& group : r.pale->groups) {
        EXPECT_FALSE(fruit_alone(group)) << group.reason;
        for (const ColourClass& sub : group.groups) {
            found = found || fruit_alone(sub);
        }
    }
    EXPECT_TRUE(found) << r.pale->reason;
}

TEST(FruitColor, EachWordKeepsItsHueAndDropsDistantOnes) {
    // Bands (degrees): red 320..35, orange 10..55, yellow 35..80, green 55..170, purple 240..350.
    // Neighbouring bands overlap on purpose (an orange-red apple is both).
    const struct {
        FruitColor word;
        double keep;
        std::vector<double> drop;
    } cases[] = {{FruitColor::kRed, 0, {57, 112, 200, 295}},
                 {FruitColor::kOrange, 32, {112, 200, 295, 330}},
                 {FruitColor::kYellow, 57, {0, 200, 295}},
                 {FruitColor::kGreen, 112, {0, 32, 200, 295}},
                 {FruitColor::kPurple, 295, {0, 32, 57, 112, 200}}};
    for (const auto& c : cases) {
        const FruitColorChoice r = choose_fruit_color({}, {.color = c.word});
        ASSERT_TRUE(r.rule) << fruit_color_name(c.word);
        EXPECT_EQ(color_filter(std::vector<io::Rgb>{hue(c.keep)}, *r.rule).kept.size(), 1u)
            << fruit_color_name(c.word) << " keeps " << c.keep;
        for (double d : c.drop) {
            EXPECT_EQ(color_filter(std::vector<io::Rgb>{hue(d)}, *r.rule).kept.size(), 0u)
                << fruit_color_name(c.word) << " drops " << d;
        }
    }
    EXPECT_FALSE(choose_fruit_color({}, {.color = FruitColor::kAny}).rule);
    EXPECT_EQ(choose_fruit_color({}, {.color = FruitColor::kMask}).rule->min_mean, 0.5);
}

TEST(FruitColor, WordsReadBackAndBadInputIsRefused) {
    for (FruitColor w :
         {FruitColor::kAuto, FruitColor::kMask, FruitColor::kRed, FruitColor::kOrange,
          FruitColor::kYellow, FruitColor::kGreen, FruitColor::kPurple, FruitColor::kAny}) {
        EXPECT_EQ(parse_fruit_color(fruit_color_name(w)), w);
    }
    EXPECT_THROW((void)parse_fruit_color("blue"), InvalidArgument);
    EXPECT_THROW((void)choose_fruit_color({}, {.min_saturation = 1}), InvalidArgument);
    // No colours at all, or only NaN: nothing to look at, no rule.
    EXPECT_FALSE(choose_fruit_color({}, {}).rule);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(choose_fruit_color(repeat({{{nan, nan, nan}, 5}}), {}).rule);
}

}  // namespace
}  // namespace pc::filters
