#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

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

TEST(VoxelDownsample, IdsEqualABruteForceWhateverTheKeyWidth) {
    // A unit cube with repeated voxels, plus far points: voxel keys and point indices in one
    // word (the usual case), a 64-bit key with (x, y, z) beside the index (far in x: 67 bits
    // together), and keys wider than 64 bits (far in every axis). Oracle: voxel index tuples
    // numbered in order of first occurrence.
    const double leaf = 1e-3;
    for (const pcl::PointXYZ far :
         {pcl::PointXYZ(0.5f, 0.5f, 0.5f), pcl::PointXYZ(1e9f, 0.5f, 0.5f),
          pcl::PointXYZ(1e9f, 1e9f, 1e9f)}) {
        Cloud c = test::uniform(300, 0.01f, 5);  // about 10 points a voxel row: repeats
        c.push_back(far);
        c.push_back(test::nan_point());
        c.push_back(c[7]);
        double lo[3] = {1e300, 1e300, 1e300};
        for (const auto& p : c) {
            if (is_finite(p)) {
                lo[0] = std::min(lo[0], double{p.x});
                lo[1] = std::min(lo[1], double{p.y});
                lo[2] = std::min(lo[2], double{p.z});
            }
        }
        std::map<std::tuple<std::int64_t, std::int64_t, std::int64_t>, std::uint32_t> id;
        std::vector<std::uint32_t> expected;
        for (const auto& p : c) {
            if (!is_finite(p)) {
                expected.push_back(io::kNoGroup);
                continue;
            }
            const auto at = [&](double v, int a) {
                return static_cast<std::int64_t>(std::floor((v - (lo[a] - leaf / 2)) / leaf));
            };
            const auto key = std::make_tuple(at(p.x, 0), at(p.y, 1), at(p.z, 2));
            const auto [it, added] = id.emplace(key, static_cast<std::uint32_t>(id.size()));
            expected.push_back(it->second);
        }
        const auto r = voxel_downsample(c, {.leaf = leaf});
        EXPECT_EQ(r.count, id.size()) << "far point " << far.x;
        EXPECT_EQ(r.voxel, expected) << "far point " << far.x;
    }
}

TEST(VoxelDownsample, RejectsNonPositiveLeaf) {
    EXPECT_THROW((void)voxel_downsample(test::grid({0, 0, 0}, 2, 1.0f), {.leaf = 0}),
                 InvalidArgument);
}

}  // namespace
}  // namespace pc::filters
