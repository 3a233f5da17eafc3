#include <cmath>

#include <gtest/gtest.h>

#include <pc/core/stats.h>

namespace pc {
namespace {

TEST(Stats, PercentileIsNumpysLinearInterpolation) {
    // numpy.percentile([1, 2, 3, 4], 90) = 3.7; ([5], 50) = 5; ([1, 2], 25) = 1.25
    std::vector<double> a = {4, 1, 3, 2}, b = {5}, c = {2, 1};
    EXPECT_DOUBLE_EQ(percentile(a, 90), 3.7);
    EXPECT_DOUBLE_EQ(percentile(b, 50), 5);
    EXPECT_DOUBLE_EQ(percentile(c, 25), 1.25);
}

TEST(Stats, MedianIsTheUsualOne) {
    std::vector<double> odd = {3, 1, 2}, even = {4, 1, 3, 2}, none;
    EXPECT_EQ(median(odd), 2);
    EXPECT_EQ(median(even), 2.5);
    EXPECT_TRUE(std::isnan(median(none)));
}

}  // namespace
}  // namespace pc
