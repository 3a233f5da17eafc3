// renumber_by_size: labels written by hand, their numbering read off them.
#include <vector>

#include <gtest/gtest.h>

#include <pc/core/labels.h>

namespace pc {
namespace {

TEST(RenumberBySize, LargestFirstTiesBySmallestPointAndNoiseKept) {
    // cluster 7: 3 points; 4: 2 points from index 1; 9: 2 points from index 0; 0 stays noise
    std::vector<std::uint32_t> labels = {9, 4, 7, 0, 7, 4, 9, 7};
    EXPECT_EQ(renumber_by_size(labels), 3u);
    EXPECT_EQ(labels, (std::vector<std::uint32_t>{2, 3, 1, 0, 1, 3, 2, 1}));
}

TEST(RenumberBySize, ClustersBelowTheLeastSizeBecomeNoise) {
    std::vector<std::uint32_t> labels = {5, 5, 5, 2, 2, 8};
    EXPECT_EQ(renumber_by_size(labels, 2), 2u);
    EXPECT_EQ(labels, (std::vector<std::uint32_t>{1, 1, 1, 2, 2, 0}));
    std::vector<std::uint32_t> none;
    EXPECT_EQ(renumber_by_size(none), 0u);
}

}  // namespace
}  // namespace pc
