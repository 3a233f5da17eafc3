#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include <pc/core/error.h>
#include <pc/core/stats.h>
#include <pc/filters/knn_outlier.h>
#include <pc/search/grid.h>

namespace pc::filters {

void KnnOutlierParams::validate() const {
    if (k < 1) {
        throw InvalidArgument("knn_outlier: k must be >= 1, got " + std::to_string(k));
    }
    if (!(drop_percentile >= 0 && drop_percentile < 100)) {
        throw InvalidArgument("knn_outlier: drop_percentile must be in [0, 100), got " +
                              format_number(drop_percentile));
    }
    if (std_mul && !std::isfinite(*std_mul)) {
        throw InvalidArgument("knn_outlier: std_mul must be finite, got " +
                              format_number(*std_mul));
    }
}

namespace {
/// Points per occupied grid cell (Grid::suggest_cell). Measured with k = 5 on four clouds (the
/// bench canopy, balls, implicit peach, explicit plum): 8 to 24 equally fast and 4 about 25 %
/// slower; with k = 30 12 to 60 equally fast. Larger cells also mean fewer cells to hold: 16.
constexpr double kOccupancy = 16.0;

/// Each of the grid's n points' mean distance to its k nearest other points (+inf when
/// non-finite or alone).
std::vector<double> knn_mean_distance(const search::Grid& grid, std::size_t n, std::uint32_t k) {
    std::vector<double> mean(n, std::numeric_limits<double>::infinity());
    grid.all_knn(
        k, [&](std::uint32_t i, const std::vector<std::uint32_t>&, const std::vector<double>& d2) {
            if (d2.empty()) {
                return;
            }
            double sum = 0;
            for (double v : d2) {
                sum += std::sqrt(v);
            }
            mean[i] = sum / static_cast<double>(d2.size());
        });
    return mean;
}

/// The threshold and flags from the scores.
KnnOutlierResult flag_outliers(std::vector<double> mean_distance, const KnnOutlierParams& params) {
    const std::size_t n = mean_distance.size();
    KnnOutlierResult r;
    r.mean_distance = std::move(mean_distance);
    r.outlier.assign(n, 1);
    // The scores' statistics are taken where they are: a copy of them (8 bytes a point) was
    // the largest block of the step.
    if (params.std_mul) {
        double mean = 0, sq = 0;
        std::size_t finite = 0;
        for (double v : r.mean_distance) {
            if (std::isfinite(v)) {
                mean += v;
                ++finite;
            }
        }
        mean /= static_cast<double>(std::max<std::size_t>(finite, 1));
        for (double v : r.mean_distance) {
            if (std::isfinite(v)) {
                sq += (v - mean) * (v - mean);
            }
        }
        const double sigma = finite > 1 ? std::sqrt(sq / static_cast<double>(finite - 1)) : 0.0;
        r.threshold = mean + *params.std_mul * sigma;
        for (std::size_t i = 0; i < n; ++i) {
            r.outlier[i] = !(r.mean_distance[i] <= r.threshold);
        }
        return r;
    }
    const bool none = params.drop_percentile == 0;
    r.threshold = none ? std::numeric_limits<double>::infinity()
                       : percentile_of_finite(r.mean_distance, 100.0 - params.drop_percentile);
    for (std::size_t i = 0; i < n; ++i) {
        const double v = r.mean_distance[i];
        r.outlier[i] = !std::isfinite(v) || (!none && v >= r.threshold);
    }
    return r;
}

}  // namespace

KnnOutlierResult knn_outlier(XyzRecords& points, const KnnOutlierParams& params) {
    params.validate();
    std::vector<double> mean;
    {  // the grid (and the records' order) is released before the flags are allocated
        const auto grid =
            search::grid_over(points, search::Grid::suggest_cell(points.view(), kOccupancy));
        mean = knn_mean_distance(*grid, points.size, params.k);
    }
    return flag_outliers(std::move(mean), params);
}

}  // namespace pc::filters
