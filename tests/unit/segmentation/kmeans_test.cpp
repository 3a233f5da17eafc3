#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/segmentation/kmeans.h>

#include "support/clouds.h"

namespace pc::segmentation {
namespace {

TEST(KMeans, TwoSeparatedBallsAreTheTwoClusters) {
    const Cloud c =
        test::concat(test::ball({0, 0, 0}, 1, 200, 1), test::ball({5, 0, 0}, 1, 300, 2));
    const KMeansResult r = kmeans(c.points, {.k = 2, .seed = 7});
    for (std::size_t i = 1; i < 200; ++i) {
        EXPECT_EQ(r.assignment[i], r.assignment[0]);
    }
    for (std::size_t i = 200; i < 500; ++i) {
        EXPECT_NE(r.assignment[i], r.assignment[0]);
    }
}

TEST(KMeans, SameSeedSameResult) {
    const Cloud c = test::uniform(400, 1.0f, 3);
    EXPECT_EQ(kmeans(c.points, {.seed = 5}).assignment, kmeans(c.points, {.seed = 5}).assignment);
}

TEST(KMeans, IdenticalPointsLeaveOneSideEmpty) {
    Cloud c;
    for (int i = 0; i < 10; ++i) {
        c.push_back({1, 2, 3});
    }
    const KMeansResult r = kmeans(c.points, {.k = 2});
    EXPECT_EQ(r.inertia, 0.0);
    for (auto a : r.assignment) {
        EXPECT_EQ(a, r.assignment[0]);
    }
}

TEST(KMeans, RejectsZeroK) {
    EXPECT_THROW((void)kmeans(test::uniform(5, 1, 1).points, {.k = 0}), InvalidArgument);
}

}  // namespace
}  // namespace pc::segmentation
