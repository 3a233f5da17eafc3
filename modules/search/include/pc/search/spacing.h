#pragma once

#include <cstddef>

#include <pc/core/cloud.h>

namespace pc::search {

class Grid;

/// The median distance from a point to its nearest other point (the point spacing), over at most
/// `samples` finite points taken at a fixed stride (deterministic); 0 with fewer than 2 points or
/// when the sampled points all coincide with another.
[[nodiscard]] double median_spacing(const XyzView& points, std::size_t samples = 20000);
[[nodiscard]] inline double median_spacing(const Cloud& cloud, std::size_t samples = 20000) {
    return median_spacing(XyzView(cloud), samples);
}

/// The same from a grid of cell Grid::suggest_cell(points, 16) over the points (copied, or
/// sorted in place with Grid::order_cells_by_index(): the samples are taken by sorted position).
[[nodiscard]] double median_spacing(const Grid& grid, std::size_t samples = 20000);

/// How the points are spaced, for a report (pc_info --stats): nearest-other-point distances over
/// at most `samples` finite points taken at a fixed stride (as median_spacing, points that
/// coincide with another left out), and the exact duplicates over all points.
struct SpacingStats {
    double p10 = 0, median = 0, p90 = 0;  ///< of the sampled distances; 0 when none
    std::size_t sampled = 0;              ///< distances behind the percentiles
    std::size_t duplicates = 0;           ///< finite points with the x, y, z of an earlier point
};
[[nodiscard]] SpacingStats spacing_stats(const XyzView& points, std::size_t samples = 20000);

}  // namespace pc::search
