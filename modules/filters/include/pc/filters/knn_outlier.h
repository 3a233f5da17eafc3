#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <pc/core/cloud.h>

namespace pc::search {
class Grid;
}  // namespace pc::search

namespace pc::filters {

/// Parameters of knn_outlier(). Score = mean distance to the k nearest other points.
struct KnnOutlierParams {
    std::uint32_t k = 5;  ///< neighbours averaged, the point itself NOT counted (sklearn k+1)
    double drop_percentile = 10;  ///< outlier iff score >= the (100 - P)th percentile (numpy
                                  ///< linear interpolation); 0 drops nothing. Range [0, 100)
    std::optional<double> std_mul;  ///< if set: outlier iff score > mean + M·σ (sample σ, as PCL
                                    ///< and Open3D); replaces the percentile rule

    void validate() const;
};

struct KnnOutlierResult {
    std::vector<double> mean_distance;  ///< per point; +inf for non-finite or isolated points
    std::vector<std::uint8_t> outlier;  ///< per point: 1 = outlier, 0 = inlier
    double threshold = 0;               ///< the score cut actually used
};

/// Statistical outlier scoring (paper 2.3.2). Exact kNN on a uniform grid, OpenMP-parallel.
/// Non-finite points are outliers and are nobody's neighbour; the threshold is computed over the
/// finite points' scores. Deterministic: independent of thread count.
[[nodiscard]] KnnOutlierResult knn_outlier(const XyzView& points, const KnnOutlierParams& params);
[[nodiscard]] inline KnnOutlierResult knn_outlier(const Cloud& cloud, const KnnOutlierParams& params) {
    return knn_outlier(XyzView(cloud), params);
}

// knn_outlier() in two steps, for a caller that builds the grid itself (e.g. one sorting the
// cloud in place, which it restores before the second step: the flags then cost no more memory).
/// The grid cell knn_outlier() uses for these points.
[[nodiscard]] double cell_for_knn(const XyzView& points);
/// Each of the n points' mean distance to its k nearest other points (+inf when non-finite or
/// alone), over a grid built on them (cells of any size; cell_for_knn() is the fastest).
[[nodiscard]] std::vector<double> knn_mean_distance(const search::Grid& grid, std::size_t n, std::uint32_t k);
/// The same into `mean` (one entry a point, every entry written): storage the caller may have
/// used before, e.g. lent to the grid's build (search::Grid::Lent::keys).
void knn_mean_distance(const search::Grid& grid, std::uint32_t k, std::span<double> mean);
/// The threshold and flags from those scores (the result keeps them as mean_distance).
[[nodiscard]] KnnOutlierResult knn_outlier(std::vector<double> mean_distance, const KnnOutlierParams& params);

}  // namespace pc::filters
