#include <pc/segmentation/dbscan.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include <pc/core/error.h>
#include <pc/search/grid.h>

namespace pc::segmentation {

namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

/// Lock-free union-find (links the larger root under the smaller with CAS, path halving).
struct ConcurrentForest {
    std::vector<std::atomic<std::uint32_t>> parent;
    explicit ConcurrentForest(std::size_t n) : parent(n) {
        for (std::size_t i = 0; i < n; ++i) {
            parent[i].store(static_cast<std::uint32_t>(i), std::memory_order_relaxed);
        }
    }
    std::uint32_t find(std::uint32_t x) {
        while (true) {
            std::uint32_t p = parent[x].load(std::memory_order_relaxed);
            if (p == x) {
                return x;
            }
            const std::uint32_t gp = parent[p].load(std::memory_order_relaxed);
            if (gp != p) {
                parent[x].compare_exchange_weak(p, gp, std::memory_order_relaxed);
            }
            x = gp;
        }
    }
    void unite(std::uint32_t a, std::uint32_t b) {
        while (true) {
            a = find(a);
            b = find(b);
            if (a == b) {
                return;
            }
            if (a < b) {
                std::swap(a, b);
            }
            std::uint32_t expected = a;
            if (parent[a].compare_exchange_strong(expected, b, std::memory_order_acq_rel)) {
                return;
            }
        }
    }
};

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
    const double eps2 = params.eps * params.eps;
    const std::size_t m = grid.finite_count();  // work in the grid's sorted positions
    std::vector<std::uint8_t> core(m, 0);

    // 1. Core points: at least min_points neighbours within eps, itself included (stop counting
    //    once there are enough).
    grid.sweep_cells([&](std::uint32_t c, const std::vector<std::uint32_t>& nb) {
        for (std::uint32_t s = grid.cell_begin(c); s < grid.cell_end(c); ++s) {
            std::uint32_t found = 0;
            for (std::size_t k = 0; k < nb.size() && found < params.min_points; ++k) {
                for (std::uint32_t t = grid.cell_begin(nb[k]); t < grid.cell_end(nb[k]); ++t) {
                    found += grid.dist2(s, t) <= eps2;
                }
            }
            core[s] = found >= params.min_points;
        }
    });

    // 2. Connected components of core points. Each pair is seen once: t > s lies in this cell
    //    or in a neighbour cell with a larger index.
    ConcurrentForest forest(m);
    grid.sweep_cells([&](std::uint32_t c, const std::vector<std::uint32_t>& nb) {
        for (std::uint32_t s = grid.cell_begin(c); s < grid.cell_end(c); ++s) {
            if (!core[s]) {
                continue;
            }
            for (std::uint32_t nc : nb) {
                if (nc < c) {
                    continue;
                }
                for (std::uint32_t t = std::max(grid.cell_begin(nc), s + 1); t < grid.cell_end(nc); ++t) {
                    if (core[t] && grid.dist2(s, t) <= eps2) {
                        forest.unite(s, t);
                    }
                }
            }
        }
    });

    // 3. Each core point's component; border points take their nearest core point's (ties: the
    //    smallest original index).
    std::vector<std::uint32_t> root(m, kNone);
    grid.sweep_cells([&](std::uint32_t c, const std::vector<std::uint32_t>& nb) {
        for (std::uint32_t s = grid.cell_begin(c); s < grid.cell_end(c); ++s) {
            if (core[s]) {
                root[s] = forest.find(s);
                continue;
            }
            double best = std::numeric_limits<double>::infinity();
            std::uint32_t best_t = kNone;
            for (std::uint32_t nc : nb) {
                for (std::uint32_t t = grid.cell_begin(nc); t < grid.cell_end(nc); ++t) {
                    if (!core[t]) {
                        continue;
                    }
                    const double d2 = grid.dist2(s, t);
                    // d2 == best implies best is finite, so best_t is a real position.
                    if (d2 <= eps2 && (d2 < best || (d2 == best && grid.index_of(t) < grid.index_of(best_t)))) {
                        best = d2;
                        best_t = t;
                    }
                }
            }
            if (best_t != kNone) {
                root[s] = forest.find(best_t);
            }
        }
    });

    // 4. Number clusters by decreasing size, ties by smallest original member index.
    std::vector<std::uint32_t> size(m, 0), first(m, kNone);
    for (std::uint32_t s = 0; s < m; ++s) {
        if (root[s] != kNone) {
            ++size[root[s]];
            first[root[s]] = std::min(first[root[s]], grid.index_of(s));
        }
    }
    std::vector<std::uint32_t> roots;
    for (std::uint32_t s = 0; s < m; ++s) {
        if (size[s] > 0) {
            roots.push_back(s);
        }
    }
    std::sort(roots.begin(), roots.end(), [&](std::uint32_t a, std::uint32_t b) {
        return size[a] != size[b] ? size[a] > size[b] : first[a] < first[b];
    });
    std::vector<std::uint32_t> label_of_root(m, kNoise);
    for (std::uint32_t k = 0; k < roots.size(); ++k) {
        label_of_root[roots[k]] = k + 1;
    }
    for (std::uint32_t s = 0; s < m; ++s) {
        const std::uint32_t i = grid.index_of(s);
        r.core[i] = core[s];
        if (root[s] != kNone) {
            r.labels[i] = label_of_root[root[s]];
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
