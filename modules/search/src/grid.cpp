#include <pc/search/grid.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <pc/core/error.h>
#include <pc/core/stats.h>

namespace pc::search {

namespace {

constexpr std::int64_t kAxisCells = std::int64_t{1} << 21;  // 21 bits per axis in a 63-bit key

/// LSD radix sort of (key, index) pairs, 11 bits per pass, skipping passes where all digits agree.
void radix_sort(std::vector<std::uint64_t>& keys, std::vector<std::uint32_t>& idx) {
    const std::size_t n = keys.size();
    std::vector<std::uint64_t> k2(n);
    std::vector<std::uint32_t> i2(n);
    std::uint64_t all_or = 0, all_and = ~std::uint64_t{0};
    for (auto k : keys) {
        all_or |= k;
        all_and &= k;
    }
    const std::uint64_t varying = all_or ^ all_and;
    for (int shift = 0; shift < 64; shift += 11) {
        if (((varying >> shift) & 0x7ff) == 0) {
            continue;
        }
        std::size_t count[2049] = {};
        for (auto k : keys) {
            ++count[((k >> shift) & 0x7ff) + 1];
        }
        for (int b = 0; b < 2048; ++b) {
            count[b + 1] += count[b];
        }
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t at = count[(keys[i] >> shift) & 0x7ff]++;
            k2[at] = keys[i];
            i2[at] = idx[i];
        }
        keys.swap(k2);
        idx.swap(i2);
    }
}

struct Bounds {
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    std::size_t n = 0;
};

Bounds finite_bounds(const Cloud& cloud) {
    Bounds b;
    for (int a = 0; a < 3; ++a) {
        b.lo[a] = std::numeric_limits<double>::infinity();
        b.hi[a] = -b.lo[a];
    }
    for (const auto& p : cloud.points) {
        if (!is_finite(p)) {
            continue;
        }
        ++b.n;
        const double v[3] = {p.x, p.y, p.z};
        for (int a = 0; a < 3; ++a) {
            b.lo[a] = std::min(b.lo[a], v[a]);
            b.hi[a] = std::max(b.hi[a], v[a]);
        }
    }
    return b;
}

/// Mean points per occupied cell of side `cell` over every `stride`-th finite point.
double occupancy(const Cloud& cloud, const Bounds& b, double cell, std::size_t stride) {
    std::vector<std::uint64_t> keys;
    std::size_t seen = 0;
    for (const auto& p : cloud.points) {
        if (!is_finite(p) || (seen++ % stride) != 0) {
            continue;
        }
        const double v[3] = {p.x, p.y, p.z};
        std::uint64_t key = 0;
        for (int a = 0; a < 3; ++a) {
            const auto c = static_cast<std::uint64_t>(
                std::min<double>(std::floor((v[a] - b.lo[a]) / cell), kAxisCells - 1));
            key = (key << 21) | c;
        }
        keys.push_back(key);
    }
    std::sort(keys.begin(), keys.end());
    const auto unique = static_cast<double>(std::unique(keys.begin(), keys.end()) - keys.begin());
    return unique > 0 ? static_cast<double>(keys.size()) / unique : 1.0;
}

/// Inserts (dd, i) into the ascending (d², index) list of at most k entries.
inline void insert_candidate(std::uint32_t i, double dd, std::size_t k,
                             std::vector<std::uint32_t>& idx, std::vector<double>& d2) {
    if (idx.size() == k && (dd > d2.back() || (dd == d2.back() && i > idx.back()))) {
        return;
    }
    std::size_t at = idx.size() == k ? k - 1 : idx.size();
    if (idx.size() < k) {
        idx.push_back(0);
        d2.push_back(0);
    }
    while (at > 0 && (d2[at - 1] > dd || (d2[at - 1] == dd && idx[at - 1] > i))) {
        idx[at] = idx[at - 1];
        d2[at] = d2[at - 1];
        --at;
    }
    idx[at] = i;
    d2[at] = dd;
}

constexpr std::int64_t kMaxRing = 2;       // rings searched before falling back to the tree
constexpr std::uint32_t kLeafSize = 16;

}  // namespace

double Grid::suggest_cell(const Cloud& cloud) {
    constexpr double kTarget = 4.0;  // points per occupied cell in the full cloud
    const Bounds b = finite_bounds(cloud);
    if (b.n < 2) {
        return 1.0;
    }
    double extent = 0;
    for (int a = 0; a < 3; ++a) {
        extent = std::max(extent, b.hi[a] - b.lo[a]);
    }
    if (!(extent > 0)) {
        return 1.0;  // all points coincide
    }
    const std::size_t stride = std::max<std::size_t>(1, b.n / 200000);
    const double s = static_cast<double>(stride);
    // Cells small enough that every axis fits, then measure how occupancy grows with the cell
    // side (2^d for a d-dimensional point set) and solve for the target occupancy.
    double cell = std::max(extent / static_cast<double>(kAxisCells - 2),
                           extent / std::cbrt(static_cast<double>(b.n)));
    for (int iter = 0; iter < 3; ++iter) {
        const double a1 = occupancy(cloud, b, cell, stride) * s;
        const double a2 = occupancy(cloud, b, 2 * cell, stride) * s;
        const double d = std::clamp(std::log2(std::max(a2 / a1, 1.0)), 1.0, 3.0);
        const double next = cell * std::pow(kTarget / a1, 1.0 / d);
        const double floor_cell = extent / static_cast<double>(kAxisCells - 2);
        cell = std::max(next, floor_cell);
        if (a1 > kTarget / 2 && a1 < kTarget * 2) {
            break;
        }
    }
    return cell;
}

Grid::Grid(const Cloud& cloud, double cell) : cell_(cell), cloud_(&cloud) {
    if (!(cell > 0) || !std::isfinite(cell)) {
        throw InvalidArgument("grid: cell must be > 0, got " + format_number(cell));
    }
    const Bounds b = finite_bounds(cloud);
    for (int a = 0; a < 3; ++a) {
        origin_[a] = b.n ? b.lo[a] : 0.0;
        // Keep every axis within 21 bits of cells: a larger cell is still exact, only slower.
        if (b.n) {
            cell_ = std::max(cell_, (b.hi[a] - b.lo[a]) / static_cast<double>(kAxisCells - 4));
        }
    }
    std::vector<std::uint64_t> keys;
    keys.reserve(b.n);
    order_.reserve(b.n);
    for (std::uint32_t i = 0; i < cloud.size(); ++i) {
        const auto& p = cloud[i];
        if (!is_finite(p)) {
            continue;
        }
        keys.push_back(pack(coord(p.x, 0), coord(p.y, 1), coord(p.z, 2)));
        order_.push_back(i);
    }
    radix_sort(keys, order_);
    xyz_.resize(3 * order_.size());
    for (std::size_t s = 0; s < order_.size(); ++s) {
        const auto& p = cloud[order_[s]];
        xyz_[3 * s] = p.x;
        xyz_[3 * s + 1] = p.y;
        xyz_[3 * s + 2] = p.z;
        if (s == 0 || keys[s] != keys[s - 1]) {
            cells_.push_back({keys[s], static_cast<std::uint32_t>(s), 0});
        }
        cells_.back().end = static_cast<std::uint32_t>(s + 1);
    }
    std::size_t cap = 16;
    int bits = 4;
    while (cap < 2 * cells_.size()) {
        cap *= 2;
        ++bits;
    }
    table_.assign(cap, 0);
    mask_ = cap - 1;
    shift_ = 64 - bits;
    for (std::uint32_t c = 0; c < cells_.size(); ++c) {
        std::uint64_t h = slot(cells_[c].key);
        while (table_[h & mask_] != 0) {
            ++h;
        }
        table_[h & mask_] = c + 1;
    }
}

std::int64_t Grid::coord(float v, int axis) const {
    // Clamped so that far query points (not in the grid) cannot overflow the conversion.
    const double c = std::floor((double{v} - origin_[axis]) / cell_);
    return static_cast<std::int64_t>(std::clamp(c, -1e12, 1e12));
}

std::uint64_t Grid::pack(std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint64_t>(x) << 42) | (static_cast<std::uint64_t>(y) << 21) |
           static_cast<std::uint64_t>(z);
}

const Grid::Cell* Grid::find(std::int64_t x, std::int64_t y, std::int64_t z) const {
    if (x < 0 || y < 0 || z < 0 || x >= kAxisCells || y >= kAxisCells || z >= kAxisCells) {
        return nullptr;
    }
    const std::uint64_t key = pack(x, y, z);
    for (std::uint64_t h = slot(key);; ++h) {
        const std::uint32_t slot = table_[h & mask_];
        if (slot == 0) {
            return nullptr;
        }
        if (cells_[slot - 1].key == key) {
            return &cells_[slot - 1];
        }
    }
}

void Grid::knn(std::uint32_t self,
               std::size_t k,
               std::vector<std::uint32_t>& idx,
               std::vector<double>& d2) const {
    search(cloud_->points[self], self, k, idx, d2);
}

void Grid::knn_point(const pcl::PointXYZ& q, std::size_t k, std::vector<std::uint32_t>& idx,
                     std::vector<double>& d2) const {
    search(q, std::numeric_limits<std::uint32_t>::max(), k, idx, d2);
}

void Grid::search(const pcl::PointXYZ& q,
                  std::uint32_t self,
                  std::size_t k,
                  std::vector<std::uint32_t>& idx,
                  std::vector<double>& d2) const {
    idx.clear();
    d2.clear();
    if (k == 0 || order_.empty() || !is_finite(q)) {
        return;  // a non-finite query has no neighbours
    }
    const std::int64_t c[3] = {coord(q.x, 0), coord(q.y, 1), coord(q.z, 2)};
    // A query outside the grid's range (pc_compare's other cloud) goes to the tree at once.
    bool outside = false;
    for (int a = 0; a < 3; ++a) {
        outside = outside || c[a] < -1 || c[a] > kAxisCells;
    }
    // Distance from q to the nearest face of its own cell: points in ring r+1 are at least
    // r * cell + margin away.
    double margin = std::numeric_limits<double>::infinity();
    const double v[3] = {q.x, q.y, q.z};
    for (int a = 0; a < 3; ++a) {
        const double lo = origin_[a] + static_cast<double>(c[a]) * cell_;
        margin = std::min({margin, v[a] - lo, lo + cell_ - v[a]});
    }
    margin = std::max(margin, 0.0);
    const auto consider = [&](const Cell& cell) {
        for (std::uint32_t s = cell.begin; s < cell.end; ++s) {
            const std::uint32_t i = order_[s];
            if (i == self) {
                continue;
            }
            const double ex = double{xyz_[3 * s]} - q.x;
            const double ey = double{xyz_[3 * s + 1]} - q.y;
            const double ez = double{xyz_[3 * s + 2]} - q.z;
            insert_candidate(i, ex * ex + ey * ey + ez * ez, k, idx, d2);
        }
    };
    const bool indexed = self < cloud_->size() && is_finite((*cloud_)[self]);
    const std::size_t others = order_.size() - (indexed ? 1 : 0);
    for (std::int64_t r = 0;; ++r) {
        for (std::int64_t dz = -r; dz <= r; ++dz) {
            for (std::int64_t dy = -r; dy <= r; ++dy) {
                const bool inner = std::abs(dz) < r && std::abs(dy) < r;
                for (std::int64_t dx = -r; dx <= r; dx += (inner ? 2 * r : 1)) {
                    if (const Cell* cell = find(c[0] + dx, c[1] + dy, c[2] + dz)) {
                        consider(*cell);
                    }
                    if (r == 0) {
                        break;
                    }
                }
            }
        }
        // Unvisited points are at least `reach` away; strict so that index tie-breaks are exact.
        const double reach = static_cast<double>(r) * cell_ + margin;
        if (idx.size() == k && d2.back() < reach * reach) {
            return;
        }
        if (idx.size() == others) {
            return;  // fewer than k other points, all seen
        }
        if (r == kMaxRing || outside) {
            tree_knn(q, self, k, idx, d2);  // an isolated point: let the tree bound the work
            return;
        }
    }
}

void Grid::build_tree() const {
    std::call_once(tree_once_, [this] {
        const auto n = static_cast<std::uint32_t>(order_.size());
        tree_perm_.resize(n);
        for (std::uint32_t s = 0; s < n; ++s) {
            tree_perm_[s] = s;
        }
        nodes_.reserve(4 * (n / kLeafSize + 1));
        nodes_.push_back({0, n});
        // Level by level: the nodes of one level own disjoint ranges of tree_perm_, so their
        // median splits run in parallel; children are appended afterwards, in order.
        for (std::size_t level_begin = 0; level_begin < nodes_.size();) {
            const std::size_t level_end = nodes_.size();
#pragma omp parallel for schedule(dynamic, 1)
            for (std::int64_t at = static_cast<std::int64_t>(level_begin);
                 at < static_cast<std::int64_t>(level_end); ++at) {
                Node& node = nodes_[static_cast<std::size_t>(at)];
                const std::uint32_t b = node.begin, e = node.end;
                if (e - b <= kLeafSize) {
                    continue;
                }
                float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
                for (std::uint32_t p = b; p < e; ++p) {
                    for (int a = 0; a < 3; ++a) {
                        lo[a] = std::min(lo[a], xyz_[3 * tree_perm_[p] + a]);
                        hi[a] = std::max(hi[a], xyz_[3 * tree_perm_[p] + a]);
                    }
                }
                int axis = 0;
                for (int a = 1; a < 3; ++a) {
                    if (hi[a] - lo[a] > hi[axis] - lo[axis]) {
                        axis = a;
                    }
                }
                const std::uint32_t mid = b + (e - b) / 2;
                std::nth_element(tree_perm_.begin() + b, tree_perm_.begin() + mid,
                                 tree_perm_.begin() + e, [&](std::uint32_t u, std::uint32_t v) {
                                     return xyz_[3 * u + axis] < xyz_[3 * v + axis];
                                 });
                node.axis = static_cast<std::uint8_t>(axis);
                node.split = xyz_[3 * tree_perm_[mid] + axis];
            }
            for (std::size_t at = level_begin; at < level_end; ++at) {
                const std::uint32_t b = nodes_[at].begin, e = nodes_[at].end;
                if (e - b <= kLeafSize) {
                    continue;
                }
                const std::uint32_t mid = b + (e - b) / 2;
                nodes_[at].left = static_cast<std::int32_t>(nodes_.size());
                nodes_.push_back({b, mid});
                nodes_[at].right = static_cast<std::int32_t>(nodes_.size());
                nodes_.push_back({mid, e});
            }
            level_begin = level_end;
        }
    });
}

void Grid::tree_knn(const pcl::PointXYZ& q, std::uint32_t self, std::size_t k,
                    std::vector<std::uint32_t>& idx, std::vector<double>& d2) const {
    build_tree();
    idx.clear();
    d2.clear();
    const double v[3] = {q.x, q.y, q.z};
    // Depth-first, near side first; a far side is skipped only when its half-space is strictly
    // farther than the current k-th distance (so index tie-breaks stay exact).
    thread_local std::vector<std::pair<std::int32_t, double>> stack;
    stack.assign(1, {0, 0.0});
    while (!stack.empty()) {
        const auto [at, bound] = stack.back();
        stack.pop_back();
        if (idx.size() == k && bound > d2.back()) {
            continue;
        }
        const Node& node = nodes_[at];
        if (node.left < 0) {
            for (std::uint32_t p = node.begin; p < node.end; ++p) {
                const std::uint32_t s = tree_perm_[p];
                const std::uint32_t i = order_[s];
                if (i == self) {
                    continue;
                }
                const double ex = double{xyz_[3 * s]} - v[0];
                const double ey = double{xyz_[3 * s + 1]} - v[1];
                const double ez = double{xyz_[3 * s + 2]} - v[2];
                insert_candidate(i, ex * ex + ey * ey + ez * ez, k, idx, d2);
            }
            continue;
        }
        const double diff = v[node.axis] - double{node.split};
        const std::int32_t near = diff < 0 ? node.left : node.right;
        const std::int32_t far = diff < 0 ? node.right : node.left;
        stack.push_back({far, std::max(bound, diff * diff)});
        stack.push_back({near, bound});
    }
}

void Grid::neighbour_cells(std::size_t c, std::vector<std::uint32_t>& out) const {
    out.clear();
    const std::uint64_t key = cells_[c].key;
    const auto x = static_cast<std::int64_t>(key >> 42);
    const auto y = static_cast<std::int64_t>((key >> 21) & (kAxisCells - 1));
    const auto z = static_cast<std::int64_t>(key & (kAxisCells - 1));
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
            for (std::int64_t dz = -1; dz <= 1; ++dz) {
                if (const Cell* n = find(x + dx, y + dy, z + dz)) {
                    out.push_back(static_cast<std::uint32_t>(n - cells_.data()));
                }
            }
        }
    }
    std::sort(out.begin(), out.end());
}

void Grid::sweep_cells(
    const std::function<void(std::uint32_t, const std::vector<std::uint32_t>&)>& f) const {
    const auto cells = static_cast<std::int64_t>(cells_.size());
#pragma omp parallel
    {
        std::vector<std::uint32_t> nb;
#pragma omp for schedule(dynamic, 64)
        for (std::int64_t c = 0; c < cells; ++c) {
            neighbour_cells(static_cast<std::size_t>(c), nb);
            f(static_cast<std::uint32_t>(c), nb);
        }
    }
}

void Grid::all_knn(std::size_t k,
                   const std::function<void(std::uint32_t, const std::vector<std::uint32_t>&,
                                            const std::vector<double>&)>& f) const {
    const std::size_t others = order_.empty() ? 0 : order_.size() - 1;
    build_tree();  // here, not lazily inside the parallel sweep, so that its build is parallel too
    sweep_cells([&](std::uint32_t c, const std::vector<std::uint32_t>& nb) {
        thread_local std::vector<std::uint32_t> idx;
        thread_local std::vector<double> d2;
        const std::uint64_t key = cells_[c].key;
        const double lo[3] = {origin_[0] + static_cast<double>(key >> 42) * cell_,
                              origin_[1] + static_cast<double>((key >> 21) & (kAxisCells - 1)) * cell_,
                              origin_[2] + static_cast<double>(key & (kAxisCells - 1)) * cell_};
        for (std::uint32_t s = cells_[c].begin; s < cells_[c].end; ++s) {
            idx.clear();
            d2.clear();
            for (std::uint32_t nc : nb) {
                for (std::uint32_t t = cells_[nc].begin; t < cells_[nc].end; ++t) {
                    if (t != s) {
                        insert_candidate(order_[t], dist2(s, t), k, idx, d2);
                    }
                }
            }
            // The 3x3x3 block covers every point closer than one cell plus the distance to the
            // nearest face of the point's own cell.
            double margin = cell_;
            for (int a = 0; a < 3; ++a) {
                const double v = xyz_[3 * s + a];
                margin = std::min({margin, v - lo[a], lo[a] + cell_ - v});
            }
            const double reach = cell_ + std::max(margin, 0.0);
            const bool done = (idx.size() == k && d2.back() < reach * reach) ||
                              (idx.size() == others && others < k);
            if (!done) {
                tree_knn((*cloud_)[order_[s]], order_[s], k, idx, d2);  // sparse: skip more rings
            }
            f(order_[s], idx, d2);
        }
    });
}

double median_spacing(const Cloud& cloud, std::size_t samples) {
    const Grid grid(cloud, Grid::suggest_cell(cloud));
    if (grid.finite_count() < 2) {
        return 0;
    }
    const std::size_t stride = std::max<std::size_t>(1, grid.finite_count() / std::max<std::size_t>(1, samples));
    std::vector<double> d;
    std::vector<std::uint32_t> idx;
    std::vector<double> d2;
    for (std::size_t s = 0; s < grid.finite_count(); s += stride) {
        grid.knn(grid.index_of(static_cast<std::uint32_t>(s)), 1, idx, d2);
        if (!d2.empty() && d2[0] > 0) {
            d.push_back(std::sqrt(d2[0]));
        }
    }
    return d.empty() ? 0 : median(d);
}

}  // namespace pc::search
