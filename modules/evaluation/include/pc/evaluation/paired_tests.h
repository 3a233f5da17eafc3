#pragma once

#include <cstddef>
#include <span>

namespace pc::evaluation {

/// Two methods scored on the same views: is the difference real?
struct PairedTests {
    std::size_t n = 0;           ///< pairs
    double mean_difference = 0;  ///< mean of a − b
    /// Paired t-test (scipy.stats.ttest_rel): t = mean(d) / (sd(d) / √n), sd with n − 1, and the
    /// two-sided p from Student's t with n − 1 degrees of freedom. All differences equal: t = 0,
    /// p = 1 when they are 0, else t = ±∞, p = 0.
    double t = 0, t_p = 1;
    /// Wilcoxon signed-rank test with scipy 1.10's defaults (scipy.stats.wilcoxon): W = min(W+,
    /// W−) of the ranks of |d| (ties averaged); the exact two-sided p for n <= 50 without zero
    /// differences, else zero differences dropped and the normal approximation with the ties'
    /// correction and no continuity correction. All differences 0: W = 0, p = 1.
    double w = 0, w_p = 1;
};

/// Both tests on the pairs (a[i], b[i]). Throws pc::InvalidArgument unless a and b have the same
/// length >= 2 and every value is finite.
[[nodiscard]] PairedTests paired_tests(std::span<const double> a, std::span<const double> b);

}  // namespace pc::evaluation
