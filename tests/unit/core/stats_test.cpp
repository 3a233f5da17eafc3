#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

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

TEST(Stats, SelectionWithoutACopyEqualsTheSortedValues) {
    // Values with repeats, both zeros, negatives, tiny and huge magnitudes, and non-finite ones
    // (left out): the k-th smallest is the k-th of the sorted finite values, and the percentile
    // equals percentile() of a copy, for every k and for many q.
    std::mt19937 rng(4);
    std::uniform_int_distribution<int> pick(0, 9);
    std::normal_distribution<double> g(0, 1);
    std::vector<double> v;
    for (int i = 0; i < 3000; ++i) {
        const int kind = pick(rng);
        v.push_back(kind == 0   ? 0.0
                    : kind == 1 ? -0.0
                    : kind == 2 ? 1.5
                    : kind == 3 ? g(rng) * 1e-300
                    : kind == 4 ? g(rng) * 1e300
                    : kind == 5 ? std::numeric_limits<double>::infinity()
                    : kind == 6 ? std::nan("")
                                : g(rng));
    }
    std::vector<double> finite;
    for (double x : v) {
        if (std::isfinite(x)) {
            finite.push_back(x);
        }
    }
    std::vector<double> sorted = finite;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t k = 0; k < sorted.size(); ++k) {
        ASSERT_EQ(kth_smallest_finite(v, k), sorted[k]) << "k " << k;
    }
    for (double q : {0.0, 0.5, 10.0, 33.3, 50.0, 90.0, 99.99, 100.0}) {
        std::vector<double> copy = finite;
        EXPECT_EQ(percentile_of_finite(v, q), percentile(copy, q)) << "q " << q;
    }
    EXPECT_TRUE(std::isnan(percentile_of_finite(
        std::vector<double>{std::nan(""), -std::numeric_limits<double>::infinity()}, 50)));
}

}  // namespace
}  // namespace pc
