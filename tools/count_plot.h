#pragma once
// pc_count's and pc_fruitcount's --plot: the panels of a count.

#include <vector>

#include <pc/charts/panel.h>
#include <pc/segmentation/cluster_summary.h>

namespace pc::tools {

/// A count at a glance: how many points the clusters have (several fruit merged stand out on the
/// right, fragments on the left) and how large they are (half the mean side of each box).
inline std::vector<charts::Panel> count_panels(const segmentation::ClusterSummary& s) {
    charts::Panel sizes{
        charts::Panel::Kind::kHistogram, "cluster sizes", "points a cluster", {}, {{}}};
    charts::Panel radii{
        charts::Panel::Kind::kHistogram, "cluster radii", "half the mean box side", {}, {{}}};
    for (const auto& c : s.clusters) {
        sizes.values[0].push_back(static_cast<double>(c.points));
        radii.values[0].push_back(
            ((c.max[0] - c.min[0]) + (c.max[1] - c.min[1]) + (c.max[2] - c.min[2])) / 6);
    }
    return {sizes, radii};
}

}  // namespace pc::tools
