#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/filters/voxel_downsample.h>
#include <pc/io/points.h>

#include "support/clouds.h"

namespace pc::filters {
namespace {

TEST(VoxelDownsample, LatticePointsFallIntoOneVoxelEach) {
    // Spacing 1, leaf 1: the grid starts half a leaf below the minimum, so every lattice point
    // sits in the middle of its own voxel.
    const Cloud c = test::grid({0, 0, 0}, 4, 1.0f);
    const auto r = voxel_downsample(c, {.leaf = 1.0});
    EXPECT_EQ(r.count, 64u);
}

TEST(VoxelDownsample, ClustersCollapseAndIdsFollowFirstOccurrence) {
    Cloud c;
    c.push_back({10, 10, 10});
    c.push_back({0, 0, 0});
    c.push_back({10.1f, 10, 10});
    c.push_back(test::nan_point());
    c.push_back({0.2f, 0.1f, 0});
    const auto r = voxel_downsample(c, {.leaf = 1.0});
    EXPECT_EQ(r.count, 2u);
    EXPECT_EQ(r.voxel, (std::vector<std::uint32_t>{0, 1, 0, io::kNoGroup, 1}));
}

TEST(VoxelDownsample, RejectsNonPositiveLeaf) {
    EXPECT_THROW((void)voxel_downsample(test::grid({0, 0, 0}, 2, 1.0f), {.leaf = 0}), InvalidArgument);
}

}  // namespace
}  // namespace pc::filters
