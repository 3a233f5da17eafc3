#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <pc/core/cloud.h>

namespace pc::segmentation {

struct ClusterInfo {
    std::uint32_t id = 0;
    std::size_t points = 0;              ///< finite member points
    std::array<double, 3> centroid{};    ///< mean of the members' x, y, z
    std::array<double, 3> min{}, max{};  ///< axis-aligned bounding box
};

struct ClusterSummary {
    std::vector<ClusterInfo> clusters;  ///< ascending id; only clusters with >= min_points
    std::size_t noise_points = 0;       ///< label 0, plus members of clusters below min_points
    std::size_t small_clusters = 0;     ///< clusters left out for having fewer than min_points
};

/// Per-cluster statistics of a labelled cloud (pc_count's report). Non-finite points are counted
/// as noise. Clusters with fewer than `min_points` points are not counted. O(n).
[[nodiscard]] ClusterSummary summarize_clusters(const XyzView& points,
                                                std::span<const std::uint32_t> labels,
                                                std::size_t min_points = 1);
[[nodiscard]] inline ClusterSummary summarize_clusters(const Cloud& cloud,
                                                       std::span<const std::uint32_t> labels,
                                                       std::size_t min_points = 1) {
    return summarize_clusters(XyzView(cloud), labels, min_points);
}

}  // namespace pc::segmentation
