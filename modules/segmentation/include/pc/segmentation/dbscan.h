#pragma once

#include <cstdint>
#include <vector>

#include <pc/core/cloud.h>

namespace pc::search {
class Grid;
}  // namespace pc::search

namespace pc::segmentation {

/// Label given to points that belong to no cluster.
inline constexpr std::uint32_t kNoise = 0;

/// Parameters of dbscan(). eps has no universal value: it is in cloud units.
struct DbscanParams {
    double eps = 0.015;            ///< neighbour iff distance <= eps (scikit-learn), cloud units
    std::uint32_t min_points = 10; ///< neighbours a core point needs, ITSELF INCLUDED (sklearn)

    void validate() const;
};

struct DbscanResult {
    std::vector<std::uint32_t> labels;  ///< per point: 1..cluster_count, or kNoise
    std::vector<std::uint8_t> core;     ///< per point: 1 = core point
    std::uint32_t cluster_count = 0;
};

/// Exact DBSCAN (Ester et al., KDD 1996) on a uniform grid of cell eps. Clusters are the connected
/// components of core points; a border point (not core, within eps of a core point) joins the
/// cluster of its nearest core point (ties: the smallest index), so the result does not depend on
/// visiting order. Clusters are numbered 1..N by decreasing size, ties by smallest point index.
/// Non-finite points are noise and nobody's neighbour. O(n · neighbours), counting in parallel.
[[nodiscard]] DbscanResult dbscan(const Cloud& cloud, const DbscanParams& params);

/// The same over a grid already built on the cloud (n points) with cells of at least eps, so
/// that a caller can free the cloud first (the grid keeps its own sorted copy of the points) or
/// have the grid sort the cloud in place (Grid::kInPlace).
[[nodiscard]] DbscanResult dbscan(const search::Grid& grid, std::size_t n, const DbscanParams& params);
/// The same, taking the grid: its coordinates and cells are freed before the result is
/// allocated (release_all_but_order), so the result does not add to the clustering's peak. The
/// grid keeps its order: an in-place grid's restore_order() is still to be called.
[[nodiscard]] DbscanResult dbscan(search::Grid&& grid, std::size_t n, const DbscanParams& params);

/// eps from the knee of the sorted distances to the (min_points − 1)-th nearest other point (the
/// core-distance curve), found as the point farthest below the chord (Kneedle), with the curve
/// clipped at its 99.5th percentile so a few far floaters do not flatten it. Deterministic.
[[nodiscard]] double estimate_eps(const XyzView& points, std::uint32_t min_points);
[[nodiscard]] inline double estimate_eps(const Cloud& cloud, std::uint32_t min_points) {
    return estimate_eps(XyzView(cloud), min_points);
}

}  // namespace pc::segmentation
