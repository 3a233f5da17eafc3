#pragma once

#include <cstdint>
#include <vector>

#include <pc/core/cloud.h>

namespace pc::segmentation {

/// Label given to points that belong to no cluster.
inline constexpr std::uint32_t kNoise = 0;

/// Parameters of dbscan(). eps has no universal value: it is in cloud units.
struct DbscanParams {
    double eps = 0.015;             ///< neighbour iff distance <= eps (scikit-learn), cloud units
    std::uint32_t min_points = 10;  ///< neighbours a core point needs, ITSELF INCLUDED (sklearn)

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
/// The records may be reordered while it runs (thin records, of at most 16 bytes, are sorted
/// where they are instead of copied: search::grid_over()); they are back in their order when it
/// returns or throws.
[[nodiscard]] DbscanResult dbscan(XyzRecords& points, const DbscanParams& params);
/// The same over a copy of a pcl cloud (for tests and small clouds).
[[nodiscard]] inline DbscanResult dbscan(Cloud cloud, const DbscanParams& params) {
    XyzRecords records(cloud);
    return dbscan(records, params);
}

/// eps from the knee of the sorted distances to the (min_points − 1)-th nearest other point (the
/// core-distance curve), found as the point farthest below the chord (Kneedle), with the curve
/// clipped at its 99.5th percentile so a few far floaters do not flatten it. Deterministic.
[[nodiscard]] double estimate_eps(const XyzView& points, std::uint32_t min_points);
[[nodiscard]] inline double estimate_eps(const Cloud& cloud, std::uint32_t min_points) {
    return estimate_eps(XyzView(cloud), min_points);
}

}  // namespace pc::segmentation
