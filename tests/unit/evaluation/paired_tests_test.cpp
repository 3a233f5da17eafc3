// paired_tests: values from scipy 1.10 (stats.ttest_rel, stats.wilcoxon with its defaults) for
// the exact path, ties, zeros and the normal approximation, and the degenerate cases.
#include <vector>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/evaluation/paired_tests.h>

namespace pc::evaluation {
namespace {

TEST(PairedTests, ExactPathMatchesScipy) {
    const std::vector<double> a{0.81, 0.75, 0.92, 0.66, 0.88, 0.79, 0.71, 0.95};
    const std::vector<double> b{0.78, 0.74, 0.85, 0.69, 0.80, 0.77, 0.70, 0.90};
    const PairedTests r = paired_tests(a, b);
    EXPECT_EQ(r.n, 8u);
    EXPECT_NEAR(r.t, 2.366431913239849, 1e-12);
    EXPECT_NEAR(r.t_p, 0.049867230568884965, 1e-12);
    EXPECT_EQ(r.w, 4.0);
    EXPECT_NEAR(r.w_p, 0.0546875, 1e-15);  // 14 of 256 sign patterns, twice
}

TEST(PairedTests, TiedRanksWithoutZerosStayExactAsInScipy) {
    // d = 1 2 -1 2 2 -1: W+ = 17.5 truncated to 17 by scipy's exact path
    const PairedTests r =
        paired_tests(std::vector<double>{1, 2, 3, 4, 5, 6}, std::vector<double>{0, 0, 4, 2, 3, 7});
    EXPECT_NEAR(r.t, 1.3867504905630728, 1e-12);
    EXPECT_NEAR(r.t_p, 0.2241632761229063, 1e-12);
    EXPECT_EQ(r.w, 4.0);
    EXPECT_NEAR(r.w_p, 0.21875, 1e-15);
}

TEST(PairedTests, ZerosSwitchToTheNormalApproximationWithTieCorrection) {
    const std::vector<double> a{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    const std::vector<double> b{1, 1, 4, 2, 5, 9, 6, 8, 7, 7, 15, 10};
    const PairedTests r = paired_tests(a, b);
    EXPECT_NEAR(r.t, 0.4135026674140679, 1e-12);
    EXPECT_NEAR(r.t_p, 0.6871851699928556, 1e-12);
    EXPECT_EQ(r.w, 18.5);
    EXPECT_NEAR(r.w_p, 0.6328885544300881, 1e-12);
}

TEST(PairedTests, MoreThanFiftyPairsUseTheNormalApproximation) {
    const std::vector<double> x{
        0.904, 0.444, 0.742, 0.643, 0.655, 0.678, 0.498, 0.677, 0.613, 1.032, 0.723, 0.665,
        0.672, 0.633, 0.594, 0.661, 0.748, 0.676, 0.796, 0.68,  0.702, 0.855, 0.755, 0.649,
        0.682, 0.754, 0.894, 0.673, 0.676, 0.8,   0.611, 0.671, 0.788, 0.758, 0.709, 0.767,
        0.417, 0.802, 0.604, 0.533, 0.728, 0.77,  0.656, 0.592, 0.703, 0.695, 0.841, 0.775,
        0.719, 0.811, 0.679, 0.607, 0.758, 0.758, 0.679, 0.622, 0.723, 0.451, 0.769, 0.749};
    const std::vector<double> y{
        0.966, 0.421, 0.77,  0.585, 0.737, 0.704, 0.443, 0.599, 0.701, 1.037, 0.687, 0.675,
        0.572, 0.673, 0.556, 0.693, 0.658, 0.657, 0.795, 0.746, 0.598, 0.797, 0.697, 0.572,
        0.645, 0.766, 0.914, 0.693, 0.587, 0.853, 0.621, 0.667, 0.757, 0.709, 0.751, 0.834,
        0.397, 0.721, 0.546, 0.502, 0.724, 0.735, 0.648, 0.531, 0.723, 0.668, 0.827, 0.728,
        0.688, 0.663, 0.584, 0.512, 0.84,  0.755, 0.689, 0.575, 0.817, 0.372, 0.696, 0.794};
    const PairedTests r = paired_tests(x, y);
    EXPECT_EQ(r.n, 60u);
    EXPECT_NEAR(r.t, 2.4409807207714254, 1e-11);
    EXPECT_NEAR(r.t_p, 0.01766729762468344, 1e-11);
    EXPECT_EQ(r.w, 607.0);
    EXPECT_NEAR(r.w_p, 0.023362249213775797, 1e-11);
}

TEST(PairedTests, DegenerateSamples) {
    const std::vector<double> a{0.5, 0.6, 0.7};
    const PairedTests same = paired_tests(a, a);
    EXPECT_EQ(same.t, 0);
    EXPECT_EQ(same.t_p, 1);
    EXPECT_EQ(same.w_p, 1);
    const PairedTests shifted = paired_tests(a, std::vector<double>{0.4, 0.5, 0.6});
    EXPECT_GT(shifted.t, 1e300);  // the same difference everywhere
    EXPECT_EQ(shifted.t_p, 0);
    EXPECT_THROW((void)paired_tests(a, std::vector<double>{1, 2}), InvalidArgument);
    EXPECT_THROW((void)paired_tests(std::vector<double>{1}, std::vector<double>{2}),
                 InvalidArgument);
}

}  // namespace
}  // namespace pc::evaluation
