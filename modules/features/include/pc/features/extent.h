#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <pc/core/cloud.h>

namespace pc::features {

/// The geometric extent of a set of points (paper Table 3), in cloud units.
struct Extent {
    std::size_t points = 0;              ///< finite points used (non-finite are skipped)
    std::array<double, 3> centroid{};    ///< mean of x, y, z
    std::array<double, 3> min{}, max{};  ///< axis-aligned bounding box
    double aabb_volume = 0;              ///< product of the three extents
    double hull_volume = 0;              ///< 3D convex hull volume (qhull's total)
    double hull_area = 0;                ///< 3D convex hull surface area (qhull's total)
    double mean_radius = 0;              ///< mean distance of the points to the centroid
    double max_radius = 0;               ///< largest distance to the centroid
    double equivalent_diameter = 0;      ///< diameter of the sphere of volume hull_volume
    bool degenerate = true;              ///< fewer than 4 points, or all coplanar: no hull
};

/// Extent of the points at `indices` (all points when empty). The hull is computed by qhull
/// ("Qt", totals from "FA"), the same library and totals as scipy.spatial.ConvexHull. A set with
/// fewer than 4 finite points, or coplanar/collinear, is degenerate: hull volume and area 0.
/// O(n log n).
[[nodiscard]] Extent extent(const XyzView& points, std::span<const std::uint32_t> indices = {});
[[nodiscard]] inline Extent extent(const Cloud& cloud,
                                   std::span<const std::uint32_t> indices = {}) {
    return extent(XyzView(cloud), indices);
}

/// One Extent per label value > 0 of `labels` (one per point), ascending label.
struct LabelledExtent {
    std::uint32_t label = 0;
    Extent extent;
};
[[nodiscard]] std::vector<LabelledExtent> extent_per_label(const XyzView& points,
                                                           std::span<const std::uint32_t> labels);
[[nodiscard]] inline std::vector<LabelledExtent> extent_per_label(
    const Cloud& cloud, std::span<const std::uint32_t> labels) {
    return extent_per_label(XyzView(cloud), labels);
}

}  // namespace pc::features
