#include <algorithm>
#include <cmath>
#include <limits>

#include <pc/cameras/visibility.h>
#include <pc/core/error.h>

namespace pc::cameras {

void VisibilityParams::validate() const {
    if (!(footprint > 0 && std::isfinite(footprint))) {
        throw InvalidArgument("visibility: footprint must be > 0, got " + format_number(footprint));
    }
    if (!(depth_tolerance >= 0 && std::isfinite(depth_tolerance))) {
        throw InvalidArgument("visibility: depth_tolerance must be >= 0, got " +
                              format_number(depth_tolerance));
    }
    if (max_splat < 0 || max_splat > 256) {
        throw InvalidArgument("visibility: max_splat must be in [0, 256], got " +
                              std::to_string(max_splat));
    }
}

std::vector<std::int32_t> visible_pixels(const XyzView& points,
                                         const View& view,
                                         double spacing,
                                         const VisibilityParams& params) {
    params.validate();
    view.camera.validate();
    if (!(spacing > 0 && std::isfinite(spacing))) {
        throw InvalidArgument("visibility: spacing must be > 0, got " + format_number(spacing));
    }
    const int w = view.camera.width, h = view.camera.height;
    if (static_cast<double>(w) * h > std::numeric_limits<std::int32_t>::max()) {
        throw InvalidArgument("visibility: images of more than 2^31 pixels are not supported");
    }
    struct Hit {
        std::int32_t pixel;
        float depth;
    };
    std::vector<Hit> hits(points.size, Hit{-1, 0});
    std::vector<float> depth(static_cast<std::size_t>(w) * static_cast<std::size_t>(h),
                             std::numeric_limits<float>::infinity());
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
        hits[i] = {v * w + u, static_cast<float>(q.z())};
        for (int y = std::max(0, v - r); y <= std::min(h - 1, v + r); ++y) {
            float* row = depth.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(w);
            for (int x = std::max(0, u - r); x <= std::min(w - 1, u + r); ++x) {
                row[x] = std::min(row[x], hits[i].depth);
            }
        }
    }
    const auto tolerance = static_cast<float>(params.depth_tolerance * spacing);
    std::vector<std::int32_t> out(points.size, -1);
    for (std::size_t i = 0; i < points.size; ++i) {
        const Hit& hit = hits[i];
        if (hit.pixel >= 0 && hit.depth <= depth[static_cast<std::size_t>(hit.pixel)] + tolerance) {
            out[i] = hit.pixel;
        }
    }
    return out;
}

}  // namespace pc::cameras
