#include <algorithm>
#include <cmath>
#include <limits>

#include <pc/cameras/render.h>
#include <pc/core/error.h>

#include "splat.h"

namespace pc::cameras {

std::vector<std::int32_t> render_nearest(const XyzView& points,
                                         const View& view,
                                         double spacing,
                                         const VisibilityParams& params) {
    detail::check_splat(view, spacing, params);
    if (points.size > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
        throw InvalidArgument("render: more than 2^31 points");
    }
    const std::size_t n =
        static_cast<std::size_t>(view.camera.width) * static_cast<std::size_t>(view.camera.height);
    std::vector<float> depth(n, std::numeric_limits<float>::infinity());
    std::vector<std::int32_t> index(n, -1);
    detail::splat(
        points, view, spacing, params, [](std::size_t, int, float) {},
        [&](std::size_t i, int pixel, float z) {
            const auto k = static_cast<std::size_t>(pixel);
            if (z < depth[k]) {
                depth[k] = z;
                index[k] = static_cast<std::int32_t>(i);
            }
        });
    return index;
}

View look_at(const Eigen::Vector3d& eye,
             const Eigen::Vector3d& target,
             const Eigen::Vector3d& up,
             int width,
             int height,
             double fov_y) {
    const Eigen::Vector3d forward = (target - eye).normalized();
    Eigen::Vector3d right = forward.cross(up);
    if (right.norm() < 1e-9) {  // looking along `up`: any right angle will do
        right = forward.cross(Eigen::Vector3d::UnitX());
    }
    right.normalize();
    const Eigen::Vector3d down = forward.cross(right);
    View v;
    v.rotation.row(0) = right;
    v.rotation.row(1) = down;
    v.rotation.row(2) = forward;
    v.translation = -v.rotation * eye;
    v.camera.width = width;
    v.camera.height = height;
    v.camera.fx = v.camera.fy = 0.5 * height / std::tan(0.5 * fov_y);
    v.camera.cx = 0.5 * width;
    v.camera.cy = 0.5 * height;
    return v;
}

}  // namespace pc::cameras
