#pragma once
// The recursive split's options, declared once for pc_recursive_split and pc_fruitcount.

#include <string>

#include <pc/cli/tool.h>
#include <pc/segmentation/recursive_split.h>

namespace pc::tools {

/// Binds --rule, --core-fraction, --min-relative-size, --size-factor, --volume-factor,
/// --median-min-points, --size-band, --min-cluster-size, --restarts and --seed to `p`; each help
/// text starts with `prefix` ("split: " where other steps' options stand beside them).
inline void bind_split_options(cli::Tool& tool,
                               segmentation::RecursiveSplitParams& p,
                               const std::string& prefix) {
    tool.option(
        "rule", segmentation::split_rule_name(p.rule),
        [&p](const std::string& s) { p.rule = segmentation::parse_split_rule(s); },
        prefix +
            "paper: medians over all clusters; script: size median over clusters with more "
            "than --median-min-points, volume median over clusters within --size-band of it; "
            "cores: cut each cluster at the necks between its solid cores (no medians, no "
            "k-means); spheres: fruit centres found by normals voting, every point to its nearest "
            "centre");
    tool.option("fruit-radius", &p.fruit_radius,
                prefix +
                    "spheres rule: the fruit radius in the cloud's units, if known (0: "
                    "estimated from the cloud)");
    tool.option("core-fraction", &p.core_fraction,
                prefix + "cores rule: core depth as a fraction of the estimated fruit radius");
    tool.option("min-relative-size", &p.min_relative_size,
                prefix + "cores rule: clusters below this x the median cluster size become noise");
    tool.option("size-factor", &p.size_factor, prefix + "split needs points > this x median size");
    tool.option("volume-factor", &p.volume_factor,
                prefix + "and AABB volume > this x median volume");
    tool.option("median-min-points", &p.median_min_points,
                prefix + "script rule: size median over clusters with more points than this");
    tool.option(
        "size-band", &p.size_band,
        prefix + "script rule: volume median over clusters with |size - median| <= band x median");
    tool.option("min-cluster-size", &p.min_cluster_size,
                prefix + "final clusters with fewer points become noise (label 0)");
    tool.option("restarts", &p.restarts, prefix + "k-means++ restarts per split");
    tool.option("seed", &p.seed, prefix + "k-means seed");
}

}  // namespace pc::tools
