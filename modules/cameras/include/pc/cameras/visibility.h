#pragma once

#include <cstdint>
#include <vector>

#include <pc/cameras/camera.h>
#include <pc/core/cloud.h>

namespace pc::cameras {

/// Parameters of visible_pixels(), in multiples of the point spacing s.
struct VisibilityParams {
    double footprint = 1.0;        ///< × s: the radius of surface each point covers (its splat)
    double depth_tolerance = 2.0;  ///< × s: visible when at most this behind the nearest surface
    int max_splat = 16;            ///< pixels: the largest splat radius (points very near a camera)

    void validate() const;
};

/// Where each point is seen in `view`: the pixel index v·width + u, or -1 when it is not in front
/// of the camera, falls outside the image, or lies behind another surface. A z-buffer holds, per
/// pixel, the nearest depth of the points whose splat (a square of radius fx·footprint·s / z
/// pixels, at least the point's own pixel) covers it; a point is visible when its depth is within
/// depth_tolerance·s of the nearest depth at its own pixel. `spacing` is s in the cloud's units
/// (> 0). Non-finite points are never visible. Deterministic.
[[nodiscard]] std::vector<std::int32_t> visible_pixels(const XyzView& points,
                                                       const View& view,
                                                       double spacing,
                                                       const VisibilityParams& params);

}  // namespace pc::cameras
