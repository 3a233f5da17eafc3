#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <pc/core/stats.h>
#include <pc/search/grid.h>
#include <pc/search/spacing.h>

namespace pc::search {

namespace {

/// Points per occupied cell of the grid median_spacing() samples by position.
constexpr double kSpacingOccupancy = 16;

/// The distance from each sampled point to its nearest other point (see median_spacing).
std::vector<double> nearest_distances(const Grid& grid, std::size_t samples) {
    std::vector<double> d;
    if (grid.finite_count() < 2) {
        return d;
    }
    const std::size_t stride =
        std::max<std::size_t>(1, grid.finite_count() / std::max<std::size_t>(1, samples));
    std::vector<std::uint32_t> idx;
    std::vector<double> d2;
    for (std::size_t s = 0; s < grid.finite_count(); s += stride) {
        // The two nearest to the point's own coordinates: itself (0) first, then its nearest
        // other point, unless another coincides with it (then both are 0 and it is skipped).
        const float* p = grid.point(static_cast<std::uint32_t>(s));
        grid.knn_point(pcl::PointXYZ(p[0], p[1], p[2]), 2, idx, d2);
        if (d2.size() == 2 && d2[1] > 0) {
            d.push_back(std::sqrt(d2[1]));
        }
    }
    return d;
}

}  // namespace

double median_spacing(const XyzView& cloud, std::size_t samples) {
    return median_spacing(Grid(cloud, Grid::suggest_cell(cloud, kSpacingOccupancy)), samples);
}

double median_spacing(const Grid& grid, std::size_t samples) {
    std::vector<double> d = nearest_distances(grid, samples);
    return d.empty() ? 0 : median(d);
}

SpacingStats spacing_stats(const XyzView& points, std::size_t samples) {
    SpacingStats s;
    std::vector<double> d =
        nearest_distances(Grid(points, Grid::suggest_cell(points, kSpacingOccupancy)), samples);
    s.sampled = d.size();
    if (!d.empty()) {
        s.p10 = percentile(d, 10);
        s.median = percentile(d, 50);
        s.p90 = percentile(d, 90);
    }
    std::vector<std::array<float, 3>> xyz;
    xyz.reserve(points.size);
    for (std::size_t i = 0; i < points.size; ++i) {
        const pcl::PointXYZ p = points[i];
        if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
            // +0.0f turns -0 into 0: the same point, though its bits differ
            xyz.push_back({p.x + 0.0f, p.y + 0.0f, p.z + 0.0f});
        }
    }
    std::sort(xyz.begin(), xyz.end());
    for (std::size_t i = 1; i < xyz.size(); ++i) {
        s.duplicates += xyz[i] == xyz[i - 1];
    }
    return s;
}

}  // namespace pc::search
