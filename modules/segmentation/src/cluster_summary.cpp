#include <algorithm>
#include <limits>
#include <map>

#include <pc/core/error.h>
#include <pc/segmentation/cluster_summary.h>

namespace pc::segmentation {

ClusterSummary summarize_clusters(const XyzView& cloud,
                                  std::span<const std::uint32_t> labels,
                                  std::size_t min_points) {
    if (labels.size() != cloud.size) {
        throw InvalidArgument("summarize_clusters: labels must be one per point");
    }
    std::map<std::uint32_t, ClusterInfo> acc;
    ClusterSummary s;
    for (std::size_t i = 0; i < cloud.size; ++i) {
        const pcl::PointXYZ p = cloud[i];
        if (labels[i] == 0 || !is_finite(p)) {
            ++s.noise_points;
            continue;
        }
        auto [it, fresh] = acc.try_emplace(labels[i]);
        ClusterInfo& c = it->second;
        const double v[3] = {p.x, p.y, p.z};
        if (fresh) {
            c.id = labels[i];
            for (int a = 0; a < 3; ++a) {
                c.min[a] = c.max[a] = v[a];
            }
        }
        ++c.points;
        for (int a = 0; a < 3; ++a) {
            c.centroid[a] += v[a];
            c.min[a] = std::min(c.min[a], v[a]);
            c.max[a] = std::max(c.max[a], v[a]);
        }
    }
    for (auto& [id, c] : acc) {
        if (c.points < min_points) {
            s.noise_points += c.points;
            ++s.small_clusters;
            continue;
        }
        for (int a = 0; a < 3; ++a) {
            c.centroid[a] /= static_cast<double>(c.points);
        }
        s.clusters.push_back(c);
    }
    return s;
}

}  // namespace pc::segmentation
