#include <pc/core/stats.h>

#include <algorithm>
#include <cmath>

namespace pc {

double percentile(std::vector<double>& values, double q) {
    if (values.empty()) {
        return std::nan("");
    }
    const double pos = q / 100.0 * static_cast<double>(values.size() - 1);
    const auto lo = static_cast<std::size_t>(std::floor(pos));
    const double frac = pos - static_cast<double>(lo);
    const auto at = values.begin() + static_cast<std::ptrdiff_t>(lo);
    std::nth_element(values.begin(), at, values.end());
    const double a = *at;
    if (frac == 0 || lo + 1 >= values.size()) {
        return a;
    }
    const double b = *std::min_element(at + 1, values.end());
    return a + frac * (b - a);  // numpy's "linear" method
}

double median(std::vector<double>& v) { return percentile(v, 50.0); }

}  // namespace pc
