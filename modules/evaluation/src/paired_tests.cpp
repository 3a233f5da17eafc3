#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include <pc/core/error.h>
#include <pc/evaluation/paired_tests.h>

namespace pc::evaluation {

namespace {

/// Continued fraction of the incomplete beta function (modified Lentz).
double beta_cf(double a, double b, double x) {
    constexpr double tiny = 1e-300;
    double c = 1, d = 1 - (a + b) * x / (a + 1);
    d = std::abs(d) < tiny ? tiny : d;
    d = 1 / d;
    double h = d;
    for (int m = 1; m <= 500; ++m) {
        const double m2 = 2.0 * m;
        double aa = m * (b - m) * x / ((a + m2 - 1) * (a + m2));
        d = 1 + aa * d;
        d = std::abs(d) < tiny ? tiny : d;
        c = 1 + aa / c;
        c = std::abs(c) < tiny ? tiny : c;
        d = 1 / d;
        h *= d * c;
        aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1));
        d = 1 + aa * d;
        d = std::abs(d) < tiny ? tiny : d;
        c = 1 + aa / c;
        c = std::abs(c) < tiny ? tiny : c;
        d = 1 / d;
        const double del = d * c;
        h *= del;
        if (std::abs(del - 1) < 1e-15) {
            break;
        }
    }
    return h;
}

/// The regularised incomplete beta function I_x(a, b).
double incomplete_beta(double a, double b, double x) {
    if (x <= 0) {
        return 0;
    }
    if (x >= 1) {
        return 1;
    }
    const double front = std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) +
                                  a * std::log(x) + b * std::log1p(-x));
    return x < (a + 1) / (a + b + 2) ? front * beta_cf(a, b, x) / a
                                     : 1 - front * beta_cf(b, a, 1 - x) / b;
}

/// Two-sided p of Student's t with `df` degrees of freedom.
double student_two_sided(double t, double df) {
    return incomplete_beta(0.5 * df, 0.5, df / (df + t * t));
}

/// Ranks 1..n of `v` with ties averaged (scipy.stats.rankdata).
std::vector<double> ranks(const std::vector<double>& v) {
    std::vector<std::size_t> idx(v.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::sort(idx.begin(), idx.end(), [&](std::size_t i, std::size_t j) { return v[i] < v[j]; });
    std::vector<double> r(v.size());
    for (std::size_t i = 0; i < idx.size();) {
        std::size_t j = i;
        while (j + 1 < idx.size() && v[idx[j + 1]] == v[idx[i]]) {
            ++j;
        }
        for (std::size_t k = i; k <= j; ++k) {
            r[idx[k]] = 0.5 * static_cast<double>(i + j) + 1;
        }
        i = j + 1;
    }
    return r;
}

}  // namespace

PairedTests paired_tests(std::span<const double> a, std::span<const double> b) {
    if (a.size() != b.size() || a.size() < 2) {
        throw InvalidArgument("paired_tests: two samples of the same length >= 2 are needed, got " +
                              std::to_string(a.size()) + " and " + std::to_string(b.size()));
    }
    std::vector<double> d(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (!std::isfinite(a[i]) || !std::isfinite(b[i])) {
            throw InvalidArgument("paired_tests: values must be finite");
        }
        d[i] = a[i] - b[i];
    }
    PairedTests r;
    const auto n = static_cast<double>(d.size());
    r.n = d.size();
    r.mean_difference = std::accumulate(d.begin(), d.end(), 0.0) / n;
    double ss = 0;
    for (double x : d) {
        ss += (x - r.mean_difference) * (x - r.mean_difference);
    }
    const double sd = std::sqrt(ss / (n - 1));
    if (sd > 0) {
        r.t = r.mean_difference / (sd / std::sqrt(n));
        r.t_p = student_two_sided(r.t, n - 1);
    } else if (r.mean_difference != 0) {
        r.t = std::copysign(std::numeric_limits<double>::infinity(), r.mean_difference);
        r.t_p = 0;
    }

    const bool zeros = std::any_of(d.begin(), d.end(), [](double x) { return x == 0; });
    if (std::all_of(d.begin(), d.end(), [](double x) { return x == 0; })) {
        return r;  // W = 0, p = 1
    }
    const bool exact = d.size() <= 50 && !zeros;
    if (!exact) {
        d.erase(std::remove(d.begin(), d.end(), 0.0), d.end());
    }
    std::vector<double> mag(d.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
        mag[i] = std::abs(d[i]);
    }
    const std::vector<double> rk = ranks(mag);
    double plus = 0, minus = 0;
    for (std::size_t i = 0; i < d.size(); ++i) {
        (d[i] > 0 ? plus : minus) += rk[i];
    }
    r.w = std::min(plus, minus);
    const auto m = static_cast<long>(d.size());
    if (exact) {
        // counts of subsets of 1..m by their rank sum: the distribution of W+ (scipy truncates
        // a tied W+ to an integer, and so do we)
        const long top = m * (m + 1) / 2;
        std::vector<double> count(static_cast<std::size_t>(top) + 1, 0.0);
        count[0] = 1;
        for (long k = 1; k <= m; ++k) {
            for (long s = top; s >= k; --s) {
                count[static_cast<std::size_t>(s)] += count[static_cast<std::size_t>(s - k)];
            }
        }
        const double total = std::ldexp(1.0, static_cast<int>(m));
        const auto wp = static_cast<long>(plus);
        if (wp == top / 2) {  // scipy: W+ at the middle of its range
            r.w_p = 1;
        } else {
            double less = 0, greater = 0;
            for (long s = 0; s <= top; ++s) {
                less += s <= wp ? count[static_cast<std::size_t>(s)] : 0;
                greater += s >= wp ? count[static_cast<std::size_t>(s)] : 0;
            }
            r.w_p = std::min(1.0, 2 * std::min(less, greater) / total);
        }
    } else {
        const double k = static_cast<double>(m);
        const double mean = k * (k + 1) * 0.25;
        double var = k * (k + 1) * (2 * k + 1);
        std::vector<double> sorted = rk;
        std::sort(sorted.begin(), sorted.end());
        for (std::size_t i = 0; i < sorted.size();) {
            std::size_t j = i;
            while (j < sorted.size() && sorted[j] == sorted[i]) {
                ++j;
            }
            const auto t = static_cast<double>(j - i);
            if (t > 1) {
                var -= 0.5 * t * (t * t - 1);
            }
            i = j;
        }
        const double z = (r.w - mean) / std::sqrt(var / 24);
        r.w_p = std::erfc(std::abs(z) / std::sqrt(2.0));
    }
    return r;
}

}  // namespace pc::evaluation
