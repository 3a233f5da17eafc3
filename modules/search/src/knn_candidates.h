#pragma once
// Shared by the grid's ring search (grid_knn.cpp) and its k-d tree over cells (grid_tree.cpp).

#include <cstdint>
#include <vector>

namespace pc::search::detail {

/// Inserts (dd, i) into the ascending (d², index) list of at most k entries.
inline void insert_candidate(std::uint32_t i,
                             double dd,
                             std::size_t k,
                             std::vector<std::uint32_t>& idx,
                             std::vector<double>& d2) {
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

inline constexpr std::int64_t kMaxRing = 2;  // rings searched before falling back to the tree
inline constexpr std::uint32_t kLeafCells =
    16;  // cells per k-d tree leaf (4: 4 % more CPU and 3 MB more at 1M, kNN; 16 vs 8: as fast, 0.9
         // MB less)

}  // namespace pc::search::detail
