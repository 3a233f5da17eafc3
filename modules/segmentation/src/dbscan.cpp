#include <pc/segmentation/dbscan.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <pc/core/error.h>
#include <pc/search/grid.h>

namespace pc::segmentation {

namespace {

std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t x) {
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

}  // namespace

void DbscanParams::validate() const {
    if (!(eps > 0) || !std::isfinite(eps)) {
        throw InvalidArgument("dbscan: eps must be > 0, got " + format_number(eps));
    }
    if (min_points < 1) {
        throw InvalidArgument("dbscan: min_points must be >= 1, got " + std::to_string(min_points));
    }
}

DbscanResult dbscan(const Cloud& cloud, const DbscanParams& params) {
    params.validate();
    const std::size_t n = cloud.size();
    DbscanResult r;
    r.labels.assign(n, kNoise);
    r.core.assign(n, 0);
    const search::Grid grid(cloud, params.eps);
    const auto count = static_cast<std::int64_t>(n);

    // 1. Core points: at least min_points neighbours within eps, itself included.
#pragma omp parallel for schedule(dynamic, 4096)
    for (std::int64_t i = 0; i < count; ++i) {
        if (!is_finite(cloud[i])) {
            continue;
        }
        std::uint32_t found = 0;
        grid.for_each_within(cloud[i], params.eps, [&](std::uint32_t, double) { ++found; });
        r.core[i] = found >= params.min_points;
    }

    // 2. Connected components of core points (union-find).
    std::vector<std::uint32_t> parent(n);
    std::iota(parent.begin(), parent.end(), 0u);
    for (std::int64_t i = 0; i < count; ++i) {
        if (!r.core[i]) {
            continue;
        }
        grid.for_each_within(cloud[i], params.eps, [&](std::uint32_t j, double) {
            if (r.core[j] && j > i) {
                const std::uint32_t a = find_root(parent, static_cast<std::uint32_t>(i));
                const std::uint32_t b = find_root(parent, j);
                if (a != b) {
                    parent[std::max(a, b)] = std::min(a, b);
                }
            }
        });
    }
    std::vector<std::uint32_t> root(n, std::numeric_limits<std::uint32_t>::max());
    for (std::int64_t i = 0; i < count; ++i) {
        if (r.core[i]) {
            root[i] = find_root(parent, static_cast<std::uint32_t>(i));
        }
    }

    // 3. Border points join the component of their nearest core point (ties: smallest index).
#pragma omp parallel for schedule(dynamic, 4096)
    for (std::int64_t i = 0; i < count; ++i) {
        if (r.core[i] || !is_finite(cloud[i])) {
            continue;
        }
        double best = std::numeric_limits<double>::infinity();
        std::uint32_t best_j = std::numeric_limits<std::uint32_t>::max();
        grid.for_each_within(cloud[i], params.eps, [&](std::uint32_t j, double d2) {
            if (r.core[j] && (d2 < best || (d2 == best && j < best_j))) {
                best = d2;
                best_j = j;
            }
        });
        if (best_j != std::numeric_limits<std::uint32_t>::max()) {
            root[i] = root[best_j];
        }
    }

    // 4. Number clusters by decreasing size, ties by smallest member index. A component's root is
    //    its smallest core index, not always its smallest member, so track the minimum.
    std::vector<std::uint32_t> size(n, 0), first(n, std::numeric_limits<std::uint32_t>::max());
    for (std::uint32_t i = 0; i < n; ++i) {
        if (root[i] != std::numeric_limits<std::uint32_t>::max()) {
            ++size[root[i]];
            first[root[i]] = std::min(first[root[i]], i);
        }
    }
    std::vector<std::uint32_t> roots;
    for (std::uint32_t i = 0; i < n; ++i) {
        if (size[i] > 0) {
            roots.push_back(i);
        }
    }
    std::sort(roots.begin(), roots.end(), [&](std::uint32_t a, std::uint32_t b) {
        return size[a] != size[b] ? size[a] > size[b] : first[a] < first[b];
    });
    std::vector<std::uint32_t> label_of_root(n, kNoise);
    for (std::uint32_t k = 0; k < roots.size(); ++k) {
        label_of_root[roots[k]] = k + 1;
    }
    for (std::uint32_t i = 0; i < n; ++i) {
        if (root[i] != std::numeric_limits<std::uint32_t>::max()) {
            r.labels[i] = label_of_root[root[i]];
        }
    }
    r.cluster_count = static_cast<std::uint32_t>(roots.size());
    return r;
}

double estimate_eps(const Cloud& cloud, std::uint32_t min_points) {
    if (min_points < 2) {
        throw InvalidArgument("dbscan: eps auto needs min_points >= 2, got " +
                              std::to_string(min_points));
    }
    const search::Grid grid(cloud, search::Grid::suggest_cell(cloud));
    if (grid.finite_count() < min_points) {
        throw InvalidArgument("dbscan: eps auto needs at least min_points (" +
                              std::to_string(min_points) + ") finite points, got " +
                              std::to_string(grid.finite_count()));
    }
    // At most 200k evenly strided query points: the curve's shape, not every point, matters.
    const std::size_t n = cloud.size();
    const std::size_t stride = std::max<std::size_t>(1, n / 200000);
    std::vector<double> kdist;
#pragma omp parallel
    {
        std::vector<std::uint32_t> idx;
        std::vector<double> d2;
        std::vector<double> local;
#pragma omp for schedule(static) nowait
        for (std::int64_t i = 0; i < static_cast<std::int64_t>(n); i += static_cast<std::int64_t>(stride)) {
            grid.knn(static_cast<std::uint32_t>(i), min_points - 1, idx, d2);
            if (d2.size() == min_points - 1) {
                local.push_back(std::sqrt(d2.back()));
            }
        }
#pragma omp critical
        kdist.insert(kdist.end(), local.begin(), local.end());
    }
    std::sort(kdist.begin(), kdist.end());
    if (kdist.size() < 3) {
        throw InvalidArgument("dbscan: eps auto needs more points");
    }
    const std::size_t m = std::max<std::size_t>(3, static_cast<std::size_t>(0.995 * static_cast<double>(kdist.size())));
    const double y0 = kdist.front(), y1 = kdist[m - 1];
    if (!(y1 > y0)) {
        return y1 > 0 ? y1 : 1.0;  // a perfectly regular cloud: its spacing
    }
    std::size_t knee = 0;
    double best = -1;
    for (std::size_t i = 0; i < m; ++i) {
        const double x = static_cast<double>(i) / static_cast<double>(m - 1);
        const double y = (kdist[i] - y0) / (y1 - y0);
        if (x - y > best) {
            best = x - y;
            knee = i;
        }
    }
    return kdist[knee];
}

}  // namespace pc::segmentation
