#include <cmath>
#include <limits>
#include <random>
#include <string>

#include <pc/core/error.h>
#include <pc/segmentation/kmeans.h>

namespace pc::segmentation {

namespace {

using Centre = std::array<double, 3>;

double dist2(const pcl::PointXYZ& p, const Centre& c) {
    const double dx = p.x - c[0], dy = p.y - c[1], dz = p.z - c[2];
    return dx * dx + dy * dy + dz * dz;
}

/// Uniform double in [0, 1) from the engine's bits (portable, unlike std distributions).
double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

std::vector<Centre> seed_plus_plus(std::span<const pcl::PointXYZ> pts,
                                   std::uint32_t k,
                                   std::mt19937_64& rng) {
    std::vector<Centre> c;
    const std::size_t n = pts.size();
    const auto& first = pts[static_cast<std::size_t>(unit(rng) * static_cast<double>(n))];
    c.push_back({first.x, first.y, first.z});
    std::vector<double> d(n);
    for (std::size_t i = 0; i < n; ++i) {
        d[i] = dist2(pts[i], c[0]);
    }
    while (c.size() < k) {
        double total = 0;
        for (double v : d) {
            total += v;
        }
        std::size_t pick = 0;
        if (total > 0) {
            double target = unit(rng) * total;
            for (pick = 0; pick + 1 < n && (target -= d[pick]) >= 0; ++pick) {
            }
        }
        c.push_back({pts[pick].x, pts[pick].y, pts[pick].z});
        for (std::size_t i = 0; i < n; ++i) {
            d[i] = std::min(d[i], dist2(pts[i], c.back()));
        }
    }
    return c;
}

KMeansResult lloyd(std::span<const pcl::PointXYZ> pts,
                   std::vector<Centre> centres,
                   std::uint32_t max_iterations) {
    const std::size_t n = pts.size();
    const std::size_t k = centres.size();
    KMeansResult r;
    r.assignment.assign(n, 0);
    for (std::uint32_t it = 0; it <= max_iterations; ++it) {
        bool changed = it == 0;
        r.inertia = 0;
        for (std::size_t i = 0; i < n; ++i) {
            std::uint32_t best = 0;
            double bd = dist2(pts[i], centres[0]);
            for (std::uint32_t c = 1; c < k; ++c) {
                const double d = dist2(pts[i], centres[c]);
                if (d < bd) {
                    bd = d;
                    best = c;
                }
            }
            changed |= best != r.assignment[i];
            r.assignment[i] = best;
            r.inertia += bd;
        }
        if (!changed || it == max_iterations) {
            break;
        }
        std::vector<Centre> sum(k, {0, 0, 0});
        std::vector<std::size_t> cnt(k, 0);
        for (std::size_t i = 0; i < n; ++i) {
            auto& s = sum[r.assignment[i]];
            s[0] += pts[i].x;
            s[1] += pts[i].y;
            s[2] += pts[i].z;
            ++cnt[r.assignment[i]];
        }
        for (std::size_t c = 0; c < k; ++c) {
            if (cnt[c] > 0) {
                for (int a = 0; a < 3; ++a) {
                    centres[c][a] = sum[c][a] / static_cast<double>(cnt[c]);
                }
            }
        }
    }
    r.centres = std::move(centres);
    return r;
}

}  // namespace

void KMeansParams::validate() const {
    if (k < 1) {
        throw InvalidArgument("kmeans: k must be >= 1, got " + std::to_string(k));
    }
    if (restarts < 1) {
        throw InvalidArgument("kmeans: restarts must be >= 1, got " + std::to_string(restarts));
    }
}

KMeansResult kmeans(std::span<const pcl::PointXYZ> points, const KMeansParams& params) {
    params.validate();
    KMeansResult best;
    best.inertia = std::numeric_limits<double>::infinity();
    if (points.empty()) {
        best.inertia = 0;
        best.centres.assign(params.k, {0, 0, 0});
        return best;
    }
    std::mt19937_64 rng(params.seed);
    for (std::uint32_t r = 0; r < params.restarts; ++r) {
        KMeansResult run =
            lloyd(points, seed_plus_plus(points, params.k, rng), params.max_iterations);
        if (run.inertia < best.inertia) {
            best = std::move(run);
        }
    }
    return best;
}

}  // namespace pc::segmentation
