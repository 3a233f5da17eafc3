#pragma once

#include <cstdint>
#include <vector>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace pc {

/// The narrow view algorithms take: positions only, one per input point, in input order.
/// Non-finite points stay in place (as NaN/Inf) so that indices match the full cloud.
using Cloud = pcl::PointCloud<pcl::PointXYZ>;

/// Indices into a cloud, ascending unless a function says otherwise.
using Indices = std::vector<std::uint32_t>;

/// True when x, y and z are all finite.
[[nodiscard]] inline bool is_finite(const pcl::PointXYZ& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

}  // namespace pc
