#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <pc/core/cloud.h>

namespace pc::segmentation {

/// Which clusters define the "median cluster" the split thresholds are relative to.
enum class SplitRule {
    kPaper,    ///< medians of point count and AABB volume over all clusters (paper 2.3.3)
    kScript,   ///< the author script: size median over clusters with > median_min_points points;
               ///< volume median over clusters within ±size_band of that median size
    kCores,    ///< not a median rule: each cluster is cut at the necks between its solid cores
               ///< (core_split(), distance-transform watershed); no k-means
    kSpheres,  ///< not a median rule: fruit centres found by normals voting (sphere_vote()), on
               ///< solid and surface clouds alike; every point goes to its nearest centre
};

/// Parses "paper", "script", "cores" or "spheres"; throws pc::InvalidArgument.
[[nodiscard]] SplitRule parse_split_rule(const std::string& text);
/// The name parse_split_rule() reads ("paper", "script", "cores"): for --help defaults.
[[nodiscard]] std::string split_rule_name(SplitRule rule);

/// Parameters of recursive_split(). A cluster is split iff
/// points > size_factor × median size AND AABB volume > volume_factor × median volume,
/// with both medians taken once, from the input clusters (thresholds fixed from the first pass).
struct RecursiveSplitParams {
    SplitRule rule = SplitRule::kPaper;
    double size_factor = 1.0;    ///< point-count factor (strict >), >= 0
    double volume_factor = 2.0;  ///< AABB-volume factor (strict >), >= 0; paper-sparse uses 5
    std::uint32_t median_min_points =
        20;                  ///< script rule: size median over clusters with MORE points
    double size_band = 0.2;  ///< script rule: volume median over clusters with |n − m| <= band·m
    std::uint32_t min_cluster_size = 0;  ///< final clusters with fewer points become noise (0)
    std::uint32_t restarts = 6;          ///< k-means++ restarts per split (k = 2)
    std::uint64_t seed = 0;      ///< k-means seed; each cluster's engine also mixes its first index
    double core_fraction = 0.5;  ///< cores rule: core depth as a fraction of the fruit radius
    double min_relative_size =
        0;                    ///< cores rule: clusters below this × the median size become noise
    double fruit_radius = 0;  ///< spheres rule: the fruit radius if known (0: from the cloud)
    /// spheres rule: an estimated R whose centres claim few points is measured again without
    /// the points on branches (SphereVoteParams::branch_below; false: never)
    bool branch_recheck = true;

    void validate() const;
};

struct RecursiveSplitResult {
    std::vector<std::uint32_t> labels;  ///< per point: 1..cluster_count by decreasing size, or 0
    std::uint32_t cluster_count = 0;
    std::uint32_t splits = 0;     ///< successful k = 2 splits
    double size_threshold = 0;    ///< points above which a cluster may split
    double volume_threshold = 0;  ///< AABB volume above which a cluster may split
    double spacing = 0;           ///< cores rule: median nearest-neighbour distance
    double fruit_radius = 0;      ///< cores and spheres rules: the fruit radius used
    std::uint32_t peaks = 0;      ///< spheres rule: fruit centres found
    bool solid = false;           ///< spheres rule: solid fruit (their outer layer voted)
    double claimed = 0;           ///< spheres rule: share of the points given to a fruit centre
    double measured_radius = 0;   ///< spheres rule, radius given: the one the points give (0: none)
    double larger_radius = 0;  ///< spheres rule: a first estimate replaced as a bunch's (0: none)
    double median_part = 0;    ///< spheres rule: SphereVoteResult::median_part
    double hollow_radius = 0;  ///< cores rule: fruit radius estimated on hollow clusters
};

/// Recursive geometric splitting (paper 2.3.3): clusters violating both thresholds are split by
/// k-means (k = 2) on x, y, z; both halves are re-examined; no depth limit (a split that leaves a
/// half empty stops). Label 0 stays noise; non-finite points become noise. Numbering: decreasing
/// size, ties by smallest point index. Deterministic for a given seed.
/// `labels` (one per point) is taken by value: moved in, the cores rule frees it early.
[[nodiscard]] RecursiveSplitResult recursive_split(const XyzView& points,
                                                   std::vector<std::uint32_t> labels,
                                                   const RecursiveSplitParams& params);
[[nodiscard]] inline RecursiveSplitResult recursive_split(const Cloud& cloud,
                                                          std::vector<std::uint32_t> labels,
                                                          const RecursiveSplitParams& params) {
    return recursive_split(XyzView(cloud), std::move(labels), params);
}

}  // namespace pc::segmentation
