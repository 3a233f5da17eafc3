// Grid's k-d tree over its occupied cells, built on first need: queries the ring search leaves
// (points more than two rings of cells from their k-th neighbour) are answered here.
#include <algorithm>
#include <climits>
#include <cmath>
#include <mutex>
#include <utility>
#include <vector>

#include <pc/search/grid.h>

#include "knn_candidates.h"

namespace pc::search {

using detail::insert_candidate;
using detail::kLeafCells;

void Grid::build_tree() const {
    std::call_once(tree_once_, [this] {
        // A k-d tree over the occupied cells (a few points each), split on cell coordinates:
        // cheaper to build than one over the points, and a cell's points are contiguous.
        const auto n = static_cast<std::uint32_t>(cell_count());
        tree_perm_.resize(n);
        for (std::uint32_t c = 0; c < n; ++c) {
            tree_perm_[c] = c;
        }
        const auto at_axis = [&](std::uint32_t c, int axis) {
            std::int64_t v[3];
            unpack(cells_[c].key(), v);
            return static_cast<std::int32_t>(v[axis]);
        };
        // Median splits leave at least kLeafCells / 2 cells in a leaf, so about n / 2 nodes; skewed
        // splits (many cells on one plane) may grow the vector past that, which is rare. (2 n, the
        // bound, held 48 bytes a cell: 6.9 MB at 1M points, part of it resident in huge pages.)
        nodes_.reserve(2 * (std::size_t{n} / (kLeafCells / 2) + 1));
        nodes_.push_back({0, n});
        std::vector<std::uint32_t>
            mid;  // per node of a level: where its range splits (end = a leaf)
        // Level by level: the nodes of one level own disjoint ranges of tree_perm_, so they are
        // split in parallel; children are appended afterwards, in order.
        for (std::size_t level_begin = 0; level_begin < nodes_.size();) {
            const std::size_t level_end = nodes_.size();
            mid.assign(level_end - level_begin, 0);
#pragma omp parallel for schedule(dynamic, 1)
            for (std::int64_t at = static_cast<std::int64_t>(level_begin);
                 at < static_cast<std::int64_t>(level_end); ++at) {
                Node& node = nodes_[static_cast<std::size_t>(at)];
                const std::uint32_t b = node.begin, e = node.end;
                std::uint32_t& split_at = mid[static_cast<std::size_t>(at) - level_begin];
                split_at = e;  // a leaf unless split below
                if (e - b <= kLeafCells) {
                    continue;
                }
                std::int32_t lo[3] = {INT32_MAX, INT32_MAX, INT32_MAX},
                             hi[3] = {INT32_MIN, INT32_MIN, INT32_MIN};
                for (std::uint32_t p = b; p < e; ++p) {
                    for (int a = 0; a < 3; ++a) {
                        lo[a] = std::min(lo[a], at_axis(tree_perm_[p], a));
                        hi[a] = std::max(hi[a], at_axis(tree_perm_[p], a));
                    }
                }
                int axis = 0;
                for (int a = 1; a < 3; ++a) {
                    if (hi[a] - lo[a] > hi[axis] - lo[axis]) {
                        axis = a;
                    }
                }
                // Distinct cells differ on some axis, so the widest one has lo < hi.
                auto* first = tree_perm_.data() + b;
                auto* last = tree_perm_.data() + e;
                std::nth_element(first, first + (e - b) / 2, last,
                                 [&](std::uint32_t u, std::uint32_t v) {
                                     return at_axis(u, axis) < at_axis(v, axis);
                                 });
                std::int32_t boundary =
                    at_axis(first[(e - b) / 2], axis);  // left: coordinate < boundary
                if (boundary == lo[axis]) {
                    ++boundary;
                }
                auto* split = std::partition(
                    first, last, [&](std::uint32_t u) { return at_axis(u, axis) < boundary; });
                split_at = static_cast<std::uint32_t>(split - tree_perm_.data());
                node.axis = static_cast<std::uint8_t>(axis);
                node.plane = origin_[axis] + static_cast<double>(boundary) * cell_;
            }
            for (std::size_t at = level_begin; at < level_end; ++at) {
                const Node node = nodes_[at];
                const std::uint32_t m = mid[at - level_begin];
                if (m == node.end) {
                    continue;
                }
                nodes_[at].left = static_cast<std::int32_t>(nodes_.size());  // right: left + 1
                nodes_.push_back({node.begin, m});
                nodes_.push_back({m, node.end});
            }
            level_begin = level_end;
        }
    });
}

void Grid::tree_knn(const pcl::PointXYZ& q,
                    std::uint32_t self,
                    std::size_t k,
                    std::vector<std::uint32_t>& idx,
                    std::vector<double>& d2) const {
    build_tree();
    idx.clear();
    d2.clear();
    const double v[3] = {q.x, q.y, q.z};
    // A point's cell coordinate is computed with rounding, so it may sit a hair across its
    // cell's plane: planes are widened by `slack` to keep the bounds below the true distances.
    const double slack = 1e-6 * cell_;
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
        const Node& node = nodes_[static_cast<std::size_t>(at)];
        if (node.left < 0) {
            for (std::uint32_t p = node.begin; p < node.end; ++p) {
                const Cell& cell = cells_[tree_perm_[p]];
                for (std::uint32_t s = cell.begin; s < cell.end(); ++s) {
                    const std::uint32_t i = index_of(s);
                    if (i == self) {
                        continue;
                    }
                    const float* at_s = point(s);
                    const double ex = double{at_s[0]} - v[0];
                    const double ey = double{at_s[1]} - v[1];
                    const double ez = double{at_s[2]} - v[2];
                    insert_candidate(i, ex * ex + ey * ey + ez * ez, k, idx, d2);
                }
            }
            continue;
        }
        const double diff = v[node.axis] - node.plane;
        const std::int32_t near = diff < 0 ? node.left : node.left + 1;
        const std::int32_t far = diff < 0 ? node.left + 1 : node.left;
        const double gap = std::max(0.0, std::abs(diff) - slack);
        stack.push_back({far, std::max(bound, gap * gap)});
        stack.push_back({near, bound});
    }
}

}  // namespace pc::search
