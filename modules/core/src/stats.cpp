#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include <pc/core/stats.h>

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

namespace {

/// The bits of v as an unsigned number in the order of the values (negatives flipped).
std::uint64_t ordered_bits(double v) {
    const auto u = std::bit_cast<std::uint64_t>(v);
    return (u >> 63) != 0 ? ~u : u | (std::uint64_t{1} << 63);
}

}  // namespace

double kth_smallest_finite(std::span<const double> values, std::size_t k) {
    // 16 bits a pass, most significant first: each pass counts the values that share the
    // prefix found so far, by their next 16 bits, and keeps the digit holding the k-th.
    std::vector<std::size_t> count(std::size_t{1} << 16);
    std::uint64_t prefix = 0;
    for (int shift = 48; shift >= 0; shift -= 16) {
        std::fill(count.begin(), count.end(), 0);
        const int known = 48 - shift;  // bits of the prefix already fixed
        for (const double v : values) {
            if (!std::isfinite(v)) {
                continue;
            }
            const std::uint64_t b = ordered_bits(v);
            if (known == 0 || (b >> (64 - known)) == (prefix >> (64 - known))) {
                ++count[(b >> shift) & 0xffff];
            }
        }
        std::size_t digit = 0;
        while (k >= count[digit]) {
            k -= count[digit];
            ++digit;
        }
        prefix |= static_cast<std::uint64_t>(digit) << shift;
    }
    const std::uint64_t u = (prefix >> 63) != 0 ? prefix & ~(std::uint64_t{1} << 63) : ~prefix;
    return std::bit_cast<double>(u);
}

double percentile_of_finite(std::span<const double> values, double q) {
    std::size_t n = 0;
    for (const double v : values) {
        n += std::isfinite(v) ? 1 : 0;
    }
    if (n == 0) {
        return std::nan("");
    }
    const double pos = q / 100.0 * static_cast<double>(n - 1);
    const auto lo = static_cast<std::size_t>(std::floor(pos));
    const double frac = pos - static_cast<double>(lo);
    const double a = kth_smallest_finite(values, lo);
    if (frac == 0 || lo + 1 >= n) {
        return a;
    }
    // The next order statistic: a again when more than lo + 1 values are at most a, else the
    // smallest value above a.
    std::size_t at_most = 0;
    double above = std::numeric_limits<double>::infinity();
    for (const double v : values) {
        if (std::isfinite(v)) {
            at_most += v <= a ? 1 : 0;
            if (v > a) {
                above = std::min(above, v);
            }
        }
    }
    const double b = at_most > lo + 1 ? a : above;
    return a + frac * (b - a);  // as percentile()
}

}  // namespace pc
