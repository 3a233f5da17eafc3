#pragma once

#include <cstdint>
#include <vector>

namespace pc {

/// Renumbers `labels` (0 = noise kept) as 1..N by decreasing cluster size, ties by smallest point
/// index; clusters below `min_size` points become 0. Returns N. The one numbering of every
/// clustering here (DBSCAN, the splits, join_instances).
std::uint32_t renumber_by_size(std::vector<std::uint32_t>& labels, std::uint32_t min_size = 0);

/// The root of `x` in a union-find forest (`parent[r] == r` at a root), halving the path to it.
[[nodiscard]] inline std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t x) {
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

}  // namespace pc
