#pragma once

#include <vector>

namespace pc {

/// numpy.percentile(values, q) with linear interpolation (q in [0, 100]); reorders `values`.
/// NaN when empty.
[[nodiscard]] double percentile(std::vector<double>& values, double q);

/// The median (mean of the two middle values for an even count); reorders `v`. NaN when empty.
[[nodiscard]] double median(std::vector<double>& v);

}  // namespace pc
