#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <pc/core/cloud.h>

namespace pc::filters {

/// Parameters of knn_outlier(). Score = mean distance to the k nearest other points.
struct KnnOutlierParams {
    std::uint32_t k = 5;  ///< neighbours averaged, the point itself NOT counted (sklearn k+1)
    double drop_percentile = 10;    ///< outlier iff score >= the (100 - P)th percentile (numpy
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
/// finite points' scores. Deterministic: independent of thread count. The records may be
/// reordered while it runs (search::grid_over()); they are back in their order when it returns
/// or throws.
[[nodiscard]] KnnOutlierResult knn_outlier(XyzRecords& points, const KnnOutlierParams& params);
/// The same over a copy of a pcl cloud (for tests and small clouds).
[[nodiscard]] inline KnnOutlierResult knn_outlier(Cloud cloud, const KnnOutlierParams& params) {
    XyzRecords records(cloud);
    return knn_outlier(records, params);
}

}  // namespace pc::filters
