#include <algorithm>
#include <cmath>
#include <limits>

#include <pc/cameras/visibility.h>
#include <pc/core/error.h>

#include "splat.h"

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
    detail::check_splat(view, spacing, params);
    struct Hit {
        std::int32_t pixel;
        float depth;
    };
    std::vector<Hit> hits(points.size, Hit{-1, 0});
    std::vector<float> depth(
        static_cast<std::size_t>(view.camera.width) * static_cast<std::size_t>(view.camera.height),
        std::numeric_limits<float>::infinity());
    detail::splat(
        points, view, spacing, params,
        [&](std::size_t i, int pixel, float z) {
            hits[i] = {pixel, z};
        },
        [&](std::size_t, int pixel, float z) {
            float& d = depth[static_cast<std::size_t>(pixel)];
            d = std::min(d, z);
        });
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
