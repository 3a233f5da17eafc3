#include "morton.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include <Eigen/Core>

namespace pc::cameras::detail {

std::vector<std::uint32_t> morton_order(const XyzView& points) {
    std::vector<std::uint32_t> order(points.size);
    std::iota(order.begin(), order.end(), 0u);
    Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
    Eigen::Vector3f hi = -lo;
    for (std::size_t i = 0; i < points.size; ++i) {
        const pcl::PointXYZ p = points[i];
        const Eigen::Vector3f q(p.x, p.y, p.z);
        if (q.allFinite()) {
            lo = lo.cwiseMin(q);
            hi = hi.cwiseMax(q);
        }
    }
    const Eigen::Vector3f scale =
        (1023.0f / (hi - lo).cwiseMax(Eigen::Vector3f::Constant(1e-30f)).array()).matrix();
    std::vector<std::uint32_t> key(points.size, 0);
    for (std::size_t i = 0; i < points.size; ++i) {
        const pcl::PointXYZ p = points[i];
        const Eigen::Vector3f q(p.x, p.y, p.z);
        if (!q.allFinite()) {
            continue;
        }
        const Eigen::Vector3f c = (q - lo).cwiseProduct(scale);
        const auto x = static_cast<std::uint32_t>(c.x()), y = static_cast<std::uint32_t>(c.y()),
                   z = static_cast<std::uint32_t>(c.z());
        std::uint32_t k = 0;
        for (int b = 9; b >= 0; --b) {
            k = (k << 3) | (((x >> b) & 1u) << 2) | (((y >> b) & 1u) << 1) | ((z >> b) & 1u);
        }
        key[i] = k;
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
    return order;
}

}  // namespace pc::cameras::detail
