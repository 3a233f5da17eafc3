#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <pc/core/cloud.h>

namespace pc::features {

/// Parameters of compare(). Lengths are in cloud units.
struct CompareParams {
    double tau = 0.01;    ///< distance threshold of accuracy / completeness (<= tau counts), > 0
    double voxel = 0.01;  ///< voxel side for interior coverage, > 0

    void validate() const;
};

/// Nearest-neighbour distances from every finite point of one cloud to the other.
struct DirectionStats {
    std::size_t points = 0;                         ///< finite query points
    double mean = 0, median = 0, rms = 0, max = 0;  ///< NaN when either side has no point
    double within_tau = 0;  ///< fraction of query points with distance <= tau
};

struct CompareResult {
    DirectionStats a_to_b, b_to_a;
    double chamfer = 0;             ///< mean(a→b) + mean(b→a), not squared
    double precision = 0;           ///< accuracy: a_to_b.within_tau (A = reconstruction)
    double recall = 0;              ///< completeness: b_to_a.within_tau (B = reference)
    double fscore = 0;              ///< 2PR / (P + R), 0 when both are 0 (Tanks and Temples)
    std::size_t b_voxels = 0;       ///< voxels occupied by B
    std::size_t shared_voxels = 0;  ///< of those, also occupied by A
    double interior_coverage = 0;   ///< shared_voxels / b_voxels (0 when B is empty)
    /// How much the bounding boxes share: the product over the axes of the overlap over the
    /// shorter side (an axis where a cloud is flat counts 1 if it lies within); 0 if disjoint.
    double box_overlap = 0;
};

/// Cloud-to-cloud comparison of A (reconstruction) against B (reference). Exact nearest
/// neighbours (grid + k-d tree). Voxels are floor(p / voxel) on a grid anchored at the origin,
/// shared by both clouds. Non-finite points are skipped. An empty side gives undefined (NaN)
/// distances and zero scores.
/// `progress`, when set, hears after each stage (A to B, B to A, coverage): several seconds each
/// on clouds of millions of points.
[[nodiscard]] CompareResult compare(const Cloud& a,
                                    const Cloud& b,
                                    const CompareParams& params,
                                    const std::function<void(const std::string&)>& progress = {});

/// What makes a comparison doubtful, in words: an empty side; clouds whose bounding boxes share
/// under 25 % (different frames?); an F-score under 0.01 (tau in other units?).
[[nodiscard]] std::vector<std::string> compare_warnings(const CompareResult& r,
                                                        const CompareParams& params);

}  // namespace pc::features
