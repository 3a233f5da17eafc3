// smooth_colors: the per-channel median of a point's own and its k nearest neighbours' colours
// against a brute-force reference; noise shrinks, a border between two colours stays sharp.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/core/random.h>
#include <pc/filters/color_smooth.h>

#include "support/clouds.h"

namespace pc::filters {
namespace {

/// The median of each channel over the point and its k nearest others (ties by index), by
/// sorting every distance.
std::vector<io::Rgb> brute(const Cloud& c, const std::vector<io::Rgb>& colors, std::size_t k) {
    std::vector<io::Rgb> out(c.size());
    for (std::size_t i = 0; i < c.size(); ++i) {
        std::vector<std::pair<double, std::size_t>> d;
        for (std::size_t j = 0; j < c.size(); ++j) {
            if (j != i) {
                d.push_back({test::dist2(c[i], c[j]), j});
            }
        }
        std::sort(d.begin(), d.end());
        std::vector<float> r{colors[i].r}, g{colors[i].g}, b{colors[i].b};
        for (std::size_t n = 0; n < k; ++n) {
            r.push_back(colors[d[n].second].r);
            g.push_back(colors[d[n].second].g);
            b.push_back(colors[d[n].second].b);
        }
        const auto median = [](std::vector<float> v) {
            std::sort(v.begin(), v.end());
            return v[v.size() / 2];
        };
        out[i] = {median(r), median(g), median(b)};
    }
    return out;
}

TEST(ColorSmooth, MedianOfEachChannelOverTheNearestNeighboursAsABruteForceReference) {
    Rng rng(3);
    Cloud c;
    std::vector<io::Rgb> colors;
    for (int i = 0; i < 400; ++i) {
        c.push_back({static_cast<float>(rng.uniform(0, 10)), static_cast<float>(rng.uniform(0, 10)),
                     static_cast<float>(rng.uniform(0, 2))});
        colors.push_back({static_cast<float>(rng.uniform()), static_cast<float>(rng.uniform()),
                          static_cast<float>(rng.uniform())});
    }
    for (std::uint32_t k : {1u, 4u, 8u}) {
        const std::vector<io::Rgb> got = smooth_colors(XyzView(c), colors, {.k = k}).colors;
        const std::vector<io::Rgb> want = brute(c, colors, k);
        ASSERT_EQ(got.size(), want.size());
        for (std::size_t i = 0; i < got.size(); ++i) {
            ASSERT_EQ(got[i].r, want[i].r) << k << " " << i;
            ASSERT_EQ(got[i].g, want[i].g);
            ASSERT_EQ(got[i].b, want[i].b);
        }
    }
}

TEST(ColorSmooth, NoiseShrinksAndABorderBetweenTwoColoursStaysSharp) {
    // A plane lattice, red where x < 30 and green beyond: on a border point 6 of the 9 colours
    // are its own side's (itself, the row behind, two along the border, two diagonals behind),
    // so the median keeps every point's colour where a mean would blend the border.
    Cloud c;
    std::vector<io::Rgb> clean, noisy;
    Rng rng(5);
    for (int x = 0; x < 60; ++x) {
        for (int y = 0; y < 60; ++y) {
            c.push_back({static_cast<float>(x), static_cast<float>(y), 0.0f});
            const io::Rgb base = x < 30 ? io::Rgb{0.7f, 0.2f, 0.2f} : io::Rgb{0.2f, 0.6f, 0.2f};
            clean.push_back(base);
            noisy.push_back({base.r + static_cast<float>(0.1 * rng.normal()), base.g, base.b});
        }
    }
    const std::vector<io::Rgb> kept = smooth_colors(XyzView(c), clean, {}).colors;
    for (std::size_t i = 0; i < c.size(); ++i) {
        ASSERT_EQ(kept[i].r, clean[i].r) << i;
        ASSERT_EQ(kept[i].g, clean[i].g) << i;
    }
    const std::vector<io::Rgb> smooth = smooth_colors(XyzView(c), noisy, {}).colors;
    double before = 0, after = 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
        if (c[i].x >= 2 && c[i].x < 28) {  // inside the red half
            before += std::pow(noisy[i].r - 0.7, 2);
            after += std::pow(smooth[i].r - 0.7, 2);
            ++n;
        }
    }
    EXPECT_NEAR(std::sqrt(before / n), 0.1, 0.01);
    EXPECT_LT(std::sqrt(after / n), 0.05);  // the median of 9: about 0.1 / 2.4
}

TEST(ColorSmooth, TheNoiseReadIsTheSigmaAddedAndCleanColoursAreLeftAlone) {
    // A plane lattice of one colour plus N(0, sigma) a channel: a point's distance to its 8
    // neighbours' median is about N(0, sigma * sqrt(1 + pi / 16)) (the median of 8 has a variance
    // of about pi sigma^2 / 16), whose median absolute value over 0.6745 reads sigma * 1.09.
    Cloud c;
    for (int x = 0; x < 150; ++x) {
        for (int y = 0; y < 150; ++y) {
            c.push_back({static_cast<float>(x), static_cast<float>(y), 0.0f});
        }
    }
    for (const double sigma : {0.0, 0.02, 0.05, 0.1}) {
        Rng rng(11);
        std::vector<io::Rgb> colors;
        for (std::size_t i = 0; i < c.size(); ++i) {
            const auto noisy = [&](double v) {
                return static_cast<float>(v + sigma * rng.normal());
            };
            colors.push_back({noisy(0.6), noisy(0.3), noisy(0.2)});
        }
        const ColorSmoothParams p{.min_noise = kNoisyColours};
        const SmoothedColors s = smooth_colors(XyzView(c), colors, p);
        EXPECT_NEAR(s.noise, 1.09 * sigma, 0.1 * sigma + 1e-6) << sigma;
        // smoothed where the noise reaches min_noise (10 of 255 = 0.039), else left alone
        EXPECT_EQ(s.colors.empty(), s.noise < kNoisyColours) << sigma;
        EXPECT_EQ(s.colors.empty(), sigma < 0.04) << sigma;
    }
}

TEST(ColorSmooth, BadParametersAreRefused) {
    Cloud c;
    c.push_back({0, 0, 0});
    c.push_back({1, 0, 0});
    const std::vector<io::Rgb> one(1);
    EXPECT_THROW((void)smooth_colors(XyzView(c), one, {}), InvalidArgument);
    const std::vector<io::Rgb> two(2);
    EXPECT_THROW((void)smooth_colors(XyzView(c), two, {.k = 0}), InvalidArgument);
    EXPECT_THROW((void)smooth_colors(XyzView(c), two, {.k = 65}), InvalidArgument);
    EXPECT_THROW((void)smooth_colors(XyzView(c), two, {.min_noise = -0.1}), InvalidArgument);
    EXPECT_THROW((void)smooth_colors(XyzView(c), two, {.min_noise = 1.5}), InvalidArgument);
    EXPECT_EQ(smooth_colors(XyzView(c), two, {}).colors.size(), 2u);
}

}  // namespace
}  // namespace pc::filters
