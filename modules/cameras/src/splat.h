// Internal: the z-buffer's splatting, shared by visible_pixels() and render_nearest().
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <pc/cameras/camera.h>
#include <pc/cameras/visibility.h>
#include <pc/core/cloud.h>
#include <pc/core/error.h>

namespace pc::cameras::detail {

/// Throws pc::InvalidArgument for bad params, intrinsics or spacing, and images of more than
/// 2^31 pixels: callers check before they allocate their buffers.
inline void check_splat(const View& view, double spacing, const VisibilityParams& params) {
    params.validate();
    view.camera.validate();
    if (!(spacing > 0 && std::isfinite(spacing))) {
        throw InvalidArgument("visibility: spacing must be > 0, got " + format_number(spacing));
    }
    if (static_cast<double>(view.camera.width) * view.camera.height >
        std::numeric_limits<std::int32_t>::max()) {
        throw InvalidArgument("visibility: images of more than 2^31 pixels are not supported");
    }
}

/// For each finite point in front of `view`'s camera that projects into its image (inputs as
/// check_splat() accepts them): `on_point(i, pixel, depth)` with its own pixel (v·width + u), and
/// `on_pixel(i, pixel, depth)` for every pixel of its splat, a square of radius
/// fx·footprint·spacing / depth pixels (at most max_splat) clipped to the image.
template <class OnPoint, class OnPixel>
void splat(const XyzView& points,
           const View& view,
           double spacing,
           const VisibilityParams& params,
           OnPoint&& on_point,
           OnPixel&& on_pixel) {
    const int w = view.camera.width, h = view.camera.height;
    const double reach = view.camera.fx * params.footprint * spacing;
    for (std::size_t i = 0; i < points.size; ++i) {
        const pcl::PointXYZ p = points[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            continue;
        }
        const Eigen::Vector3d q = view.to_camera({p.x, p.y, p.z});
        const auto px = project(view.camera, q);
        if (!px || !(px->x() >= 0 && px->x() < w && px->y() >= 0 && px->y() < h)) {
            continue;
        }
        const int u = static_cast<int>(px->x()), v = static_cast<int>(px->y());
        const int r = static_cast<int>(std::min<double>(params.max_splat, reach / q.z()));
        const auto z = static_cast<float>(q.z());
        on_point(i, v * w + u, z);
        for (int y = std::max(0, v - r); y <= std::min(h - 1, v + r); ++y) {
            for (int x = std::max(0, u - r); x <= std::min(w - 1, u + r); ++x) {
                on_pixel(i, y * w + x, z);
            }
        }
    }
}

}  // namespace pc::cameras::detail
