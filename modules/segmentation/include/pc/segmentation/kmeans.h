#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <pcl/point_types.h>

namespace pc::segmentation {

/// Parameters of kmeans().
struct KMeansParams {
    std::uint32_t k = 2;                 ///< clusters wanted (>= 1)
    std::uint32_t restarts = 6;          ///< k-means++ seedings; the lowest inertia wins
    std::uint32_t max_iterations = 300;  ///< Lloyd iterations per restart
    std::uint64_t seed = 0;              ///< seeds a local engine: same input, same output

    void validate() const;
};

struct KMeansResult {
    std::vector<std::uint32_t> assignment;       ///< per point: 0..k-1
    std::vector<std::array<double, 3>> centres;  ///< k centres
    double inertia = 0;                          ///< sum of squared distances to the centre
};

/// Lloyd's k-means with k-means++ seeding (Arthur & Vassilvitskii 2007) on finite points, in
/// double. Ties go to the lower centre. Fewer distinct points than k leaves some centres empty.
[[nodiscard]] KMeansResult kmeans(std::span<const pcl::PointXYZ> points,
                                  const KMeansParams& params);

}  // namespace pc::segmentation
