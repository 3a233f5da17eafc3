#include <algorithm>
#include <set>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/segmentation/recursive_split.h>

#include "support/clouds.h"

namespace pc::segmentation {
namespace {

/// Clouds of `count` separate balls (one label each) plus one touching pair under one label.
struct Scene {
    Cloud cloud;
    std::vector<std::uint32_t> labels;
    std::uint32_t fruit = 0;
};

Scene singles_and_a_touching_pair(int singles) {
    Scene s;
    for (int b = 0; b < singles; ++b) {
        const Cloud ball = test::ball({static_cast<float>(b) * 5, 0, 0}, 1, 300, 100 + b);
        s.cloud += ball;
        s.labels.insert(s.labels.end(), ball.size(), static_cast<std::uint32_t>(b + 1));
        ++s.fruit;
    }
    // Two balls touching at one point: one DBSCAN cluster, two fruit.
    const Cloud pair =
        test::concat(test::ball({0, 10, 0}, 1, 300, 7), test::ball({2, 10, 0}, 1, 300, 8));
    s.cloud += pair;
    s.labels.insert(s.labels.end(), pair.size(), static_cast<std::uint32_t>(singles + 1));
    s.fruit += 2;
    return s;
}

TEST(RecursiveSplit, TouchingPairBecomesTwoAndSinglesStayWhole) {
    const Scene s = singles_and_a_touching_pair(6);
    for (SplitRule rule : {SplitRule::kPaper, SplitRule::kScript}) {
        const auto r = recursive_split(s.cloud, s.labels, {.rule = rule});
        EXPECT_EQ(r.cluster_count, s.fruit);
        EXPECT_EQ(r.splits, 1u);
        // The pair's halves follow the two balls exactly.
        const std::size_t start = s.cloud.size() - 600;
        std::set<std::uint32_t> first(r.labels.begin() + start, r.labels.begin() + start + 300);
        std::set<std::uint32_t> second(r.labels.begin() + start + 300, r.labels.end());
        EXPECT_EQ(first.size(), 1u);
        EXPECT_EQ(second.size(), 1u);
        EXPECT_NE(*first.begin(), *second.begin());
    }
}

TEST(RecursiveSplit, OneBallStaysOne) {
    const Cloud c = test::ball({0, 0, 0}, 1, 500, 3);
    const std::vector<std::uint32_t> labels(c.size(), 1);
    const auto r = recursive_split(c, labels, {});
    EXPECT_EQ(r.cluster_count, 1u);
    EXPECT_EQ(r.splits, 0u);  // a single cluster is its own median: never above 2x itself
}

TEST(RecursiveSplit, SparseFactorFiveKeepsThePair) {
    const Scene s = singles_and_a_touching_pair(6);
    // The pair's AABB is about 2x a single ball's: above 2x median, not above 5x.
    EXPECT_EQ(recursive_split(s.cloud, s.labels, {.volume_factor = 5.0}).cluster_count,
              s.fruit - 1);
}

TEST(RecursiveSplit, MinClusterSizeTurnsSmallClustersToNoise) {
    Scene s = singles_and_a_touching_pair(3);
    s.cloud.push_back({50, 50, 50});
    s.labels.push_back(99);
    const auto r = recursive_split(s.cloud, s.labels, {.min_cluster_size = 10});
    EXPECT_EQ(r.labels.back(), 0u);
    EXPECT_EQ(r.cluster_count, s.fruit);
}

TEST(RecursiveSplit, NoiseStaysNoiseAndNumberingIsBySize) {
    Scene s = singles_and_a_touching_pair(2);
    s.cloud.push_back(test::nan_point());
    s.labels.push_back(1);
    s.cloud.push_back({40, 40, 40});
    s.labels.push_back(0);
    const auto r = recursive_split(s.cloud, s.labels, {});
    EXPECT_EQ(r.labels[s.cloud.size() - 2], 0u);
    EXPECT_EQ(r.labels.back(), 0u);
    std::vector<std::size_t> sizes(r.cluster_count + 1, 0);
    for (auto l : r.labels) {
        ++sizes[l];
    }
    EXPECT_TRUE(std::is_sorted(sizes.begin() + 1, sizes.end(), std::greater<>()));
}

TEST(RecursiveSplit, RejectsNegativeFactors) {
    const Cloud c = test::ball({0, 0, 0}, 1, 10, 3);
    const std::vector<std::uint32_t> labels(c.size(), 1);
    EXPECT_THROW((void)recursive_split(c, labels, {.size_factor = -1}), InvalidArgument);
    EXPECT_THROW((void)parse_split_rule("median"), InvalidArgument);
}

}  // namespace
}  // namespace pc::segmentation
