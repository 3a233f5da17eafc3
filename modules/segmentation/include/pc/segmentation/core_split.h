#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include <pc/core/cloud.h>
#include <pc/segmentation/sphere_split.h>

namespace pc::segmentation {

/// Parameters of core_split(). Lengths are multiples of the point spacing s (the median distance
/// from a point to its nearest other point) or of the fruit radius R estimated from the clusters,
/// so the result does not change when the cloud is scaled or rotated.
struct CoreSplitParams {
    double core_fraction = 0.5;  ///< a core point is deeper than this × R
    double boundary_radius =
        2.0;  ///< × s: the neighbourhood that decides whether a point is inside
    double boundary_offset = 0.2;  ///< boundary iff |mean neighbour offset| > this × the radius
    double isotropy = 0.5;  ///< ... or the neighbours' smallest/largest variance < this (a sheet)
    double link = 1.75;  ///< × s: points closer than this are adjacent (lattice diagonals: √3)
    double min_core_fraction =
        0.1;  ///< cores with fewer points than this × an ideal core are ignored
    std::uint32_t min_cluster_size = 0;  ///< final clusters with fewer points become noise
    double min_relative_size = 0;  ///< ... and those with fewer than this × the median final size
    bool merge_fragments = true;   ///< join solid parts whose union fits in one fruit
    double fragment_extent = 1.5;  ///< ... within this × the fruit's radius of the union's centroid
    bool hollow = true;            ///< split hollow clusters (no interior at all) into spheres
    HollowSplitParams spheres;     ///< how (split_hollow)

    void validate() const;
};

struct CoreSplitResult {
    std::vector<std::uint32_t> labels;  ///< per point: 1..cluster_count by decreasing size, or 0
    std::uint32_t cluster_count = 0;
    std::uint32_t splits = 0;  ///< clusters cut into two or more parts
    double spacing = 0;        ///< s
    double fruit_radius = 0;   ///< R: the median over clusters of their greatest depth
    double largest_depth = 0;  ///< the 98th percentile of the same (the best-kept fruit)
    double hollow_radius = 0;  ///< hollow clusters: median radius of the single-fruit-like ones
    std::uint32_t hollow_splits = 0;     ///< hollow clusters cut into spheres
    std::uint32_t merged_fragments = 0;  ///< hollow parts joined to another on the same sphere
    std::vector<float> depth;  ///< per point: distance to the nearest boundary point (0 for noise)
};

/// Separates touching objects inside each cluster at the necks between their solid cores: a
/// point is on the boundary when its neighbours (same cluster, within boundary_radius) lie mostly
/// to one side; its depth is the distance to the nearest boundary point (a point-cloud distance
/// transform). The fruit radius R is the median over clusters of their greatest depth (a bunch of
/// touching fruit is no deeper than one fruit). Points deeper than core_fraction × R form cores
/// (connected through `link`); a cluster with two or more cores is flooded from them in order of
/// decreasing depth (marker watershed), and every point takes the part that reaches it first.
/// Hollow clusters (no interior point: NeRF-like surfaces) have no cores; with `hollow` they are
/// cut into spheres instead (split_hollow), with the fruit radius read from the curvature of the
/// surfaces (median radius of spherical patches within 8 s of evenly strided points; without 20
/// such patches they stay whole); a cluster whose own sphere fit has RMS < 0.15 × its radius and a
/// radius up to 1.33 × the fruit's is one fruit. Afterwards hollow pieces lying on one fruit-sized
/// sphere (fitted centres closer than R/2) are joined: occlusion cuts fruit into caps. Label 0
/// stays noise; non-finite points become noise. Deterministic. `labels` (one per point) is taken by
/// value: move it in and it is freed once the clustered points are copied into the records the
/// steps sort, before the steps allocate.
[[nodiscard]] CoreSplitResult core_split(const XyzView& points,
                                         std::vector<std::uint32_t> labels,
                                         const CoreSplitParams& params);
[[nodiscard]] inline CoreSplitResult core_split(const Cloud& cloud,
                                                std::vector<std::uint32_t> labels,
                                                const CoreSplitParams& params) {
    return core_split(XyzView(cloud), std::move(labels), params);
}

}  // namespace pc::segmentation
