#include <gtest/gtest.h>

#include <pc/segmentation/cluster_summary.h>

#include "support/clouds.h"

namespace pc::segmentation {
namespace {

TEST(ClusterSummary, CentroidAndBoxOfALattice) {
    const Cloud c = test::grid({1, 2, 3}, 3, 0.5f);  // 1..2, 2..3, 3..4
    const std::vector<std::uint32_t> labels(c.size(), 4);
    const auto s = summarize_clusters(c, labels);
    ASSERT_EQ(s.clusters.size(), 1u);
    EXPECT_EQ(s.clusters[0].id, 4u);
    EXPECT_EQ(s.clusters[0].points, 27u);
    EXPECT_DOUBLE_EQ(s.clusters[0].centroid[0], 1.5);
    EXPECT_DOUBLE_EQ(s.clusters[0].centroid[2], 3.5);
    EXPECT_EQ(s.clusters[0].max[1], 3.0);
}

TEST(ClusterSummary, SmallClustersAndNanCountAsNoise) {
    Cloud c = test::grid({0, 0, 0}, 2, 1.0f);
    c.push_back(test::nan_point());
    std::vector<std::uint32_t> labels = {1, 1, 1, 1, 1, 1, 2, 0, 1};
    const auto s = summarize_clusters(c, labels, 2);
    EXPECT_EQ(s.clusters.size(), 1u);
    EXPECT_EQ(s.small_clusters, 1u);
    EXPECT_EQ(s.noise_points, 3u);  // label 0, the NaN point, the 1-point cluster
}

}  // namespace
}  // namespace pc::segmentation
