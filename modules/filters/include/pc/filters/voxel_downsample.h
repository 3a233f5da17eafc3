#pragma once

#include <cstdint>
#include <vector>

#include <pc/core/cloud.h>

namespace pc::filters {

/// Parameters of voxel_downsample().
struct VoxelParams {
    double leaf = 0.01;  ///< voxel side, cloud units (> 0)

    void validate() const;
};

struct VoxelResult {
    std::vector<std::uint32_t> voxel;  ///< per point: voxel id 0..count-1, or io::kNoGroup
    std::uint32_t count = 0;           ///< occupied voxels
};

/// Voxel-grid assignment as Open3D's voxel_down_sample: the grid starts half a leaf below the
/// finite points' minimum, so voxel index = floor((p - (min - leaf/2)) / leaf). Voxel ids follow
/// the order of each voxel's first point. Non-finite points get no voxel. O(n log n).
/// io::aggregate() turns the result into one point per voxel (centroid, mean colour, ...).
[[nodiscard]] VoxelResult voxel_downsample(const XyzView& points, const VoxelParams& params);
[[nodiscard]] inline VoxelResult voxel_downsample(const Cloud& cloud, const VoxelParams& params) {
    return voxel_downsample(XyzView(cloud), params);
}

}  // namespace pc::filters
