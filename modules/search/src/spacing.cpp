#include <algorithm>
#include <cmath>
#include <vector>

#include <pc/core/stats.h>
#include <pc/search/grid.h>
#include <pc/search/spacing.h>

namespace pc::search {

namespace {

/// Points per occupied cell of the grid median_spacing() samples by position.
constexpr double kSpacingOccupancy = 16;

}  // namespace

double median_spacing(const XyzView& cloud, std::size_t samples) {
    return median_spacing(Grid(cloud, Grid::suggest_cell(cloud, kSpacingOccupancy)), samples);
}

double median_spacing(const Grid& grid, std::size_t samples) {
    if (grid.finite_count() < 2) {
        return 0;
    }
    const std::size_t stride =
        std::max<std::size_t>(1, grid.finite_count() / std::max<std::size_t>(1, samples));
    std::vector<double> d;
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
    return d.empty() ? 0 : median(d);
}

}  // namespace pc::search
