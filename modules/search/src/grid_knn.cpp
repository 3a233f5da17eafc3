// Grid's k-nearest-neighbour queries: a ring search over the cells around the query, the k-d
// tree over cells (grid_tree.cpp) for points far from everything else, and all_knn() swept cell
// by cell.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <vector>

#include <omp.h>

#include <pc/search/grid.h>

#include "knn_candidates.h"

namespace pc::search {

using detail::insert_candidate;
using detail::kMaxRing;

void Grid::knn(std::uint32_t self,
               std::size_t k,
               std::vector<std::uint32_t>& idx,
               std::vector<double>& d2) const {
    if (!has_points_) {
        throw std::logic_error(
            "grid: knn(i) needs a grid that copied the points and was not renumbered");
    }
    search(points_[self], self, k, idx, d2);
}

void Grid::knn_point(const pcl::PointXYZ& q,
                     std::size_t k,
                     std::vector<std::uint32_t>& idx,
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
    if (k == 0 || finite_ == 0 || !is_finite(q)) {
        return;  // a non-finite query has no neighbours
    }
    const std::int64_t c[3] = {coord(q.x, 0), coord(q.y, 1), coord(q.z, 2)};
    // A query outside the grid's range (pc_compare's other cloud) goes to the tree at once.
    bool outside = false;
    for (int a = 0; a < 3; ++a) {
        outside = outside || c[a] < -1 || c[a] > dims_[a];
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
        for (std::uint32_t s = cell.begin; s < cell.end(); ++s) {
            const std::uint32_t i = index_of(s);
            if (i == self) {
                continue;
            }
            const float* p = point(s);
            const double ex = double{p[0]} - q.x;
            const double ey = double{p[1]} - q.y;
            const double ez = double{p[2]} - q.z;
            insert_candidate(i, ex * ex + ey * ey + ez * ez, k, idx, d2);
        }
    };
    const bool indexed = has_points_ && self < points_.size && is_finite(points_[self]);
    const std::size_t others = finite_ - (indexed ? 1 : 0);
    for (std::int64_t r = 0;; ++r) {
        // Ring r by rows: rows on the square's edge give all of z - r .. z + r, inner rows only
        // their two ends.
        for (std::int64_t dx = -r; dx <= r; ++dx) {
            for (std::int64_t dy = -r; dy <= r; ++dy) {
                const bool edge = std::abs(dx) == r || std::abs(dy) == r;
                for (const std::int64_t z_lo : {c[2] - r, c[2] + r}) {
                    const std::int64_t z_hi = edge ? c[2] + r : z_lo;
                    const auto [first, last] = row_span(c[0] + dx, c[1] + dy, z_lo, z_hi);
                    for (const Cell* cell = first; cell < last; ++cell) {
                        consider(*cell);
                    }
                    if (edge || r == 0) {
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

namespace {

/// A cell near a query's cell: its index, its offset (-2..2 per axis), |offset|_1.
struct Segment {
    std::uint32_t cell;
    std::int8_t d[3];
    std::uint8_t rank;
};

/// Per-thread scratch of all_knn (one thread_local look-up per cell, not per access).
struct KnnScratch {
    std::vector<std::uint32_t> idx, far;
    std::vector<double> d2;
    std::vector<Segment> block, ring2;  // the 3x3x3 block; the cells at Chebyshev distance 2
};

/// The segment of `cell` at cell coordinates `at` seen from the cell at `centre`.
Segment make_segment(std::uint32_t cell, const std::int64_t at[3], const std::int64_t centre[3]) {
    Segment seg{
        cell,
        {static_cast<std::int8_t>(at[0] - centre[0]), static_cast<std::int8_t>(at[1] - centre[1]),
         static_cast<std::int8_t>(at[2] - centre[2])},
        0};
    seg.rank =
        static_cast<std::uint8_t>(std::abs(seg.d[0]) + std::abs(seg.d[1]) + std::abs(seg.d[2]));
    return seg;
}

/// For point p in the cell whose lower corner is `lo`: gap[a][d + 2], the squared distance from p
/// to the cells at offset d along axis a (faces moved `slack` closer: a point's cell is found
/// with rounding); returns the distance to the nearest face of its own cell.
double point_gaps(const float* p, const double lo[3], double cell, double slack, double gap[3][5]) {
    double margin = cell;
    for (int a = 0; a < 3; ++a) {
        const double below = std::max(0.0, double{p[a]} - lo[a] - slack);
        const double above = std::max(0.0, lo[a] + cell - p[a] - slack);
        gap[a][0] = (below + cell) * (below + cell);
        gap[a][1] = below * below;
        gap[a][2] = 0;
        gap[a][3] = above * above;
        gap[a][4] = (above + cell) * (above + cell);
        margin = std::min({margin, below, above});
    }
    return margin;
}

/// Offers the points of `cells` to sorted position s's k nearest (w.idx, w.d2), skipping cells
/// that lie wholly farther than the current k-th.
void scan_cells(const Grid& g,
                std::uint32_t s,
                const std::vector<Segment>& cells,
                const double gap[3][5],
                std::size_t k,
                KnnScratch& w) {
    const double px = g.point(s)[0], py = g.point(s)[1], pz = g.point(s)[2];
    const std::size_t stride = g.point_stride();
    double worst = w.idx.size() == k ? w.d2.back() : std::numeric_limits<double>::infinity();
    for (const Segment& seg : cells) {
        if (gap[0][seg.d[0] + 2] + gap[1][seg.d[1] + 2] + gap[2][seg.d[2] + 2] > worst) {
            continue;  // every point of that cell is farther than the k-th
        }
        const float* q = g.point(g.cell_begin(seg.cell));
        for (std::uint32_t t = g.cell_begin(seg.cell); t < g.cell_end(seg.cell); ++t, q += stride) {
            const double ex = px - q[0], ey = py - q[1], ez = pz - q[2];
            const double dd = ex * ex + ey * ey + ez * ez;
            if (dd <= worst && t != s) {
                insert_candidate(g.index_of(t), dd, k, w.idx, w.d2);
                if (w.idx.size() == k) {
                    worst = w.d2.back();
                }
            }
        }
    }
}

}  // namespace

void Grid::all_knn(
    std::size_t k,
    const std::function<void(
        std::uint32_t, const std::vector<std::uint32_t>&, const std::vector<double>&)>& f) const {
    const std::size_t others = finite_ == 0 ? 0 : finite_ - 1;
    // A point's cell is found with rounding, so a point may sit a hair across its cell's face:
    // face distances are reduced by `slack`, keeping every bound below the true distance.
    const double slack = 1e-6 * cell_;
    std::vector<std::uint32_t> far_points;  // left for the k-d tree
    std::mutex far_mutex;
    sweep_cells([&](std::uint32_t c, const std::vector<std::uint32_t>& nb) {
        thread_local KnnScratch scratch;
        KnnScratch& w = scratch;
        w.far.clear();
        std::int64_t xyz[3];
        unpack(cells_[c].key(), xyz);
        const double lo[3] = {origin_[0] + static_cast<double>(xyz[0]) * cell_,
                              origin_[1] + static_cast<double>(xyz[1]) * cell_,
                              origin_[2] + static_cast<double>(xyz[2]) * cell_};
        // The 3x3x3 block's cells, nearest first (own cell, faces, edges, corners), so that a
        // point can skip cells farther than its current k-th distance.
        w.block.clear();
        for (std::uint32_t nc : nb) {
            std::int64_t at[3];
            unpack(cells_[nc].key(), at);
            w.block.push_back(make_segment(nc, at, xyz));
        }
        std::stable_sort(w.block.begin(), w.block.end(),
                         [](const Segment& a, const Segment& b) { return a.rank < b.rank; });
        bool ring2_ready = false;
        for (std::uint32_t s = cells_[c].begin; s < cells_[c].end(); ++s) {
            w.idx.clear();
            w.d2.clear();
            double gap[3][5];
            const double margin = point_gaps(point(s), lo, cell_, slack, gap);
            const auto scan = [&](const std::vector<Segment>& cells) {
                scan_cells(*this, s, cells, gap, k, w);
            };
            // The 3x3x3 block covers every point closer than one cell plus the distance to the
            // nearest face of the point's own cell; the 5x5x5 block one cell more.
            const auto done = [&](double reach) {
                return (w.idx.size() == k && w.d2.back() < reach * reach) ||
                       (w.idx.size() == others && others < k);
            };
            scan(w.block);
            if (!done(cell_ + margin)) {
                if (!ring2_ready) {  // gathered once per cell, for its points that need it
                    w.ring2.clear();
                    for (std::int64_t dx = -2; dx <= 2; ++dx) {
                        for (std::int64_t dy = -2; dy <= 2; ++dy) {
                            const bool inner_row = std::abs(dx) <= 1 && std::abs(dy) <= 1;
                            const auto [first, last] =
                                row_span(xyz[0] + dx, xyz[1] + dy, xyz[2] - 2, xyz[2] + 2);
                            for (const Cell* cell = first; cell < last; ++cell) {
                                std::int64_t at[3];
                                unpack(cell->key(), at);
                                if (!inner_row ||
                                    std::abs(at[2] - xyz[2]) == 2) {  // not in the block
                                    w.ring2.push_back(make_segment(
                                        static_cast<std::uint32_t>(cell - cells_.data()), at, xyz));
                                }
                            }
                        }
                    }
                    ring2_ready = true;
                }
                scan(w.ring2);
                if (!done(2 * cell_ + margin)) {
                    w.far.push_back(s);  // sparse: the tree bounds the work
                    continue;
                }
            }
            f(index_of(s), w.idx, w.d2);
        }
        if (!w.far.empty()) {
            const std::lock_guard<std::mutex> lock(far_mutex);
            far_points.insert(far_points.end(), w.far.begin(), w.far.end());
        }
    });
    if (far_points.empty()) {
        return;
    }
    build_tree();  // here, outside the sweep, so that its build is parallel too
#pragma omp parallel
    {
        std::vector<std::uint32_t> idx;
        std::vector<double> d2;
#pragma omp for schedule(dynamic, 256)
        for (std::int64_t at = 0; at < static_cast<std::int64_t>(far_points.size()); ++at) {
            const std::uint32_t s = far_points[static_cast<std::size_t>(at)];
            const float* p = point(s);
            tree_knn(pcl::PointXYZ(p[0], p[1], p[2]), index_of(s), k, idx, d2);
            f(index_of(s), idx, d2);
        }
    }
}

}  // namespace pc::search
