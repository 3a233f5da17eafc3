#pragma once

#include <cstdint>
#include <vector>

#include <pc/cameras/camera.h>
#include <pc/cameras/visibility.h>
#include <pc/core/cloud.h>

namespace pc::cameras {

/// What `view` sees of the points: per pixel (row-major, width × height of its camera) the index
/// of the nearest point whose splat covers the pixel, or -1. Splats and `spacing` as in
/// visible_pixels() (`params.depth_tolerance` is not used). Deterministic: equal depths keep the
/// lower index.
[[nodiscard]] std::vector<std::int32_t> render_nearest(const XyzView& points,
                                                       const View& view,
                                                       double spacing,
                                                       const VisibilityParams& params);

/// A camera looking at `target` from `eye` with the world's `up` pointing up in the image,
/// pinhole, `width` × `height` pixels, `fov_y` radians top to bottom.
[[nodiscard]] View look_at(const Eigen::Vector3d& eye,
                           const Eigen::Vector3d& target,
                           const Eigen::Vector3d& up,
                           int width,
                           int height,
                           double fov_y);

}  // namespace pc::cameras
