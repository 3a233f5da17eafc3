#include <algorithm>
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/filters/knn_outlier.h>

#include "support/clouds.h"

namespace pc::filters {
namespace {

std::vector<double> brute_scores(const Cloud& c, std::size_t k) {
    std::vector<double> out(c.size(), INFINITY);
    for (std::size_t i = 0; i < c.size(); ++i) {
        if (!is_finite(c[i])) {
            continue;
        }
        std::vector<double> d;
        for (std::size_t j = 0; j < c.size(); ++j) {
            if (j != i && is_finite(c[j])) {
                d.push_back(std::sqrt(test::dist2(c[i], c[j])));
            }
        }
        std::sort(d.begin(), d.end());
        d.resize(std::min(k, d.size()));
        double s = 0;
        for (double v : d) {
            s += v;
        }
        out[i] = d.empty() ? INFINITY : s / static_cast<double>(d.size());
    }
    return out;
}

TEST(KnnOutlier, ScoresMatchBruteForce) {
    Cloud c = test::concat(test::uniform(800, 1.0f, 11), test::grid({2, 2, 2}, 4, 0.05f));
    c.push_back(test::nan_point());
    const auto r = knn_outlier(c, {.k = 5});
    const auto ref = brute_scores(c, 5);
    for (std::size_t i = 0; i < c.size(); ++i) {
        if (std::isfinite(ref[i])) {
            EXPECT_NEAR(r.mean_distance[i], ref[i], 1e-12) << i;
        } else {
            EXPECT_FALSE(std::isfinite(r.mean_distance[i]));
            EXPECT_EQ(r.outlier[i], 1);
        }
    }
}

TEST(KnnOutlier, RichRecordsGiveTheScoresOfThinOnesAndAreLeftInPlace) {
    // Records of 12 bytes are sorted in place, of 24 bytes copied (search::grid_over): the
    // scores are the same, and both come back byte for byte.
    Cloud c = test::concat(test::uniform(800, 1.0f, 12), test::grid({2, 2, 2}, 4, 0.05f));
    c.push_back(test::nan_point());
    const auto ref = brute_scores(c, 5);
    for (const std::size_t stride : {12u, 24u}) {
        std::vector<std::uint8_t> bytes = test::records_of(c, stride);
        const std::vector<std::uint8_t> original = bytes;
        XyzRecords records{bytes.data(), stride, c.size(), 0};
        const auto r = knn_outlier(records, {.k = 5});
        EXPECT_EQ(bytes, original) << "stride " << stride;
        for (std::size_t i = 0; i < c.size(); ++i) {
            if (std::isfinite(ref[i])) {
                EXPECT_NEAR(r.mean_distance[i], ref[i], 1e-12) << i;
            } else {
                EXPECT_FALSE(std::isfinite(r.mean_distance[i])) << i;
            }
        }
        EXPECT_EQ(r.outlier, knn_outlier(c, {.k = 5}).outlier);
    }
}

TEST(KnnOutlier, DropsTheTopTenPercentAtOrAboveTheCut) {
    const Cloud c = test::uniform(1000, 1.0f, 12);
    const auto r = knn_outlier(c, {.k = 5, .drop_percentile = 10});
    std::size_t dropped = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
        dropped += r.outlier[i];
        EXPECT_EQ(r.outlier[i] == 1, r.mean_distance[i] >= r.threshold);
    }
    EXPECT_EQ(dropped, 100u);  // distinct scores: exactly the points at or above P90
}

TEST(KnnOutlier, FarPointsAreTheOutliers) {
    Cloud c = test::grid({0, 0, 0}, 10, 0.01f);
    c.push_back({5, 5, 5});
    c.push_back({-5, 5, 5});
    const auto r = knn_outlier(c, {.k = 4, .std_mul = 1.0});
    EXPECT_EQ(r.outlier[c.size() - 1], 1);
    EXPECT_EQ(r.outlier[c.size() - 2], 1);
    EXPECT_EQ(std::count(r.outlier.begin(), r.outlier.end(), 1), 2);
}

TEST(KnnOutlier, ZeroPercentDropsNothingFinite) {
    const auto r = knn_outlier(test::uniform(100, 1.0f, 2), {.k = 3, .drop_percentile = 0});
    EXPECT_EQ(std::count(r.outlier.begin(), r.outlier.end(), 1), 0);
}

TEST(KnnOutlier, RejectsBadParameters) {
    EXPECT_THROW((void)knn_outlier(test::uniform(10, 1, 1), {.k = 0}), InvalidArgument);
    EXPECT_THROW((void)knn_outlier(test::uniform(10, 1, 1), {.drop_percentile = 100}),
                 InvalidArgument);
}

}  // namespace
}  // namespace pc::filters
