#include <algorithm>
#include <cmath>
#include <limits>

#include <pc/cameras/render.h>
#include <pc/core/error.h>

namespace pc::cameras {

std::vector<std::int32_t> render_nearest(const XyzView& points,
                                         const View& view,
                                         double spacing,
                                         const VisibilityParams& params) {
    params.validate();
    view.camera.validate();
    if (!(spacing > 0 && std::isfinite(spacing))) {
        throw InvalidArgument("render: spacing must be > 0, got " + format_number(spacing));
    }
    if (points.size > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
        throw InvalidArgument("render: more than 2^31 points");
    }
    const int w = view.camera.width, h = view.camera.height;
    const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    std::vector<float> depth(n, std::numeric_limits<float>::infinity());
    std::vector<std::int32_t> index(n, -1);
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
        for (int y = std::max(0, v - r); y <= std::min(h - 1, v + r); ++y) {
            const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(w);
            for (int x = std::max(0, u - r); x <= std::min(w - 1, u + r); ++x) {
                if (z < depth[row + x]) {
                    depth[row + x] = z;
                    index[row + x] = static_cast<std::int32_t>(i);
                }
            }
        }
    }
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
