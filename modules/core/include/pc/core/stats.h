#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace pc {

/// numpy.percentile(values, q) with linear interpolation (q in [0, 100]); reorders `values`.
/// NaN when empty.
[[nodiscard]] double percentile(std::vector<double>& values, double q);

/// The median (mean of the two middle values for an even count); reorders `v`. NaN when empty.
[[nodiscard]] double median(std::vector<double>& v);

/// The k-th smallest (0-based) of the finite values among `values`, which are neither copied nor
/// reordered (radix selection on the bit patterns: four counting passes). k must be below the
/// number of finite values.
[[nodiscard]] double kth_smallest_finite(std::span<const double> values, std::size_t k);

/// percentile() of the finite values among `values`, without copying or reordering them (for a
/// per-point array as large as the cloud). NaN when none is finite.
[[nodiscard]] double percentile_of_finite(std::span<const double> values, double q);

}  // namespace pc
