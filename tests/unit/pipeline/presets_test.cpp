// The presets against ../shared/METHOD.md's table, column by column.
#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/pipeline/presets.h>

namespace pc::pipeline {
namespace {

TEST(Presets, PaperDenseIsPermissive) {
    const ChainParams p = preset("paper-dense");
    EXPECT_EQ(p.dbscan.eps, 0.015);
    EXPECT_EQ(p.knn->drop_percentile, 10);
    EXPECT_EQ(p.split->rule, segmentation::SplitRule::kPaper);
    EXPECT_EQ(p.split->min_cluster_size, 0u);
    EXPECT_EQ(p.count_min_points, 1u);
    EXPECT_FALSE(p.crop);
    EXPECT_FALSE(p.voxel);
}

TEST(Presets, PaperSparseWidensEpsAndSplitsOnlyAboveFiveTimesTheMedian) {
    const ChainParams p = preset("paper-sparse");
    EXPECT_EQ(p.dbscan.eps, 0.030);
    EXPECT_EQ(p.split->volume_factor, 5.0);
}

TEST(Presets, InvnerfsegIsTheAuthorScript) {
    const ChainParams p = preset("invnerfseg");
    EXPECT_EQ(p.color->min_mean, 0.5);
    EXPECT_EQ(p.crop->min, (std::array<double, 3>{-0.5, -0.5, -0.7}));
    EXPECT_EQ(p.crop->max, (std::array<double, 3>{0.5, 0.5, 0.2}));
    EXPECT_EQ(p.voxel->leaf, 0.001);
    EXPECT_EQ(p.knn->k, 5u);
    EXPECT_EQ(p.knn->drop_percentile, 10);
    EXPECT_EQ(p.dbscan.eps, 0.0065);
    EXPECT_EQ(p.dbscan.min_points, 3u);
    EXPECT_EQ(p.split->rule, segmentation::SplitRule::kScript);
    EXPECT_EQ(p.split->size_factor, 1.0);
    EXPECT_EQ(p.split->volume_factor, 2.0);
    EXPECT_EQ(p.split->median_min_points, 20u);
    EXPECT_EQ(p.split->size_band, 0.2);
    EXPECT_EQ(p.split->restarts, 6u);
    EXPECT_EQ(p.count_min_points, 40u);
}

TEST(Presets, UnknownNameIsAnError) { EXPECT_THROW((void)preset("paper"), InvalidArgument); }

}  // namespace
}  // namespace pc::pipeline
