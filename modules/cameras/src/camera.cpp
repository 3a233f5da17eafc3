#include <array>
#include <cmath>
#include <utility>

#include <Eigen/LU>

#include <pc/cameras/camera.h>
#include <pc/core/error.h>

namespace pc::cameras {

namespace {

constexpr std::array<std::pair<Model, std::string_view>, 6> kNames{{
    {Model::kSimplePinhole, "SIMPLE_PINHOLE"},
    {Model::kPinhole, "PINHOLE"},
    {Model::kSimpleRadial, "SIMPLE_RADIAL"},
    {Model::kRadial, "RADIAL"},
    {Model::kOpenCv, "OPENCV"},
    {Model::kOpenCvFisheye, "OPENCV_FISHEYE"},
}};

}  // namespace

std::string_view model_name(Model model) {
    for (const auto& [m, name] : kNames) {
        if (m == model) {
            return name;
        }
    }
    return "?";
}

std::optional<Model> model_from_name(std::string_view name) {
    for (const auto& [m, n] : kNames) {
        if (n == name) {
            return m;
        }
    }
    return std::nullopt;
}

void Intrinsics::validate() const {
    if (width <= 0 || height <= 0) {
        throw InvalidArgument("camera: width and height must be > 0, got " + std::to_string(width) +
                              " x " + std::to_string(height));
    }
    if (!(fx > 0 && fy > 0 && std::isfinite(fx) && std::isfinite(fy))) {
        throw InvalidArgument("camera: focal lengths must be > 0, got " + format_number(fx) + ", " +
                              format_number(fy));
    }
    for (const double v : {cx, cy, k1, k2, k3, k4, p1, p2}) {
        if (!std::isfinite(v)) {
            throw InvalidArgument("camera: principal point and distortion must be finite");
        }
    }
}

std::optional<Eigen::Vector2d> project(const Intrinsics& c, const Eigen::Vector3d& q) {
    if (!(q.z() > 0)) {
        return std::nullopt;
    }
    const double x = q.x() / q.z(), y = q.y() / q.z(), r2 = x * x + y * y;
    double xd = x, yd = y;
    switch (c.model) {
        case Model::kSimplePinhole:
        case Model::kPinhole:
            break;
        case Model::kSimpleRadial:
        case Model::kRadial:
        case Model::kOpenCv: {
            // r(1 + k1 r² + k2 r⁴ + k3 r⁶) must still grow with r: past its first maximum the
            // polynomial folds far-off points back into the image.
            if (1 + r2 * (3 * c.k1 + r2 * (5 * c.k2 + r2 * 7 * c.k3)) <= 0) {
                return std::nullopt;
            }
            const double f = 1 + r2 * (c.k1 + r2 * (c.k2 + r2 * c.k3));
            xd = x * f + 2 * c.p1 * x * y + c.p2 * (r2 + 2 * x * x);
            yd = y * f + c.p1 * (r2 + 2 * y * y) + 2 * c.p2 * x * y;
            break;
        }
        case Model::kOpenCvFisheye: {
            const double r = std::sqrt(r2);
            if (r > 1e-12) {
                const double t = std::atan(r), t2 = t * t;
                const double td = t * (1 + t2 * (c.k1 + t2 * (c.k2 + t2 * (c.k3 + t2 * c.k4))));
                xd = x * td / r;
                yd = y * td / r;
            }
            break;
        }
    }
    return Eigen::Vector2d(c.fx * xd + c.cx, c.fy * yd + c.cy);
}

Similarity Similarity::inverse() const {
    Similarity s;
    s.scale = 1 / scale;
    s.linear = linear.inverse();
    s.translation = -(s.linear * translation) / scale;
    return s;
}

View moved(const View& view, const Similarity& to) {
    // camera = R p + t with p = to.inverse().apply(p'): scaled by to.scale (the same pixels),
    // camera' = R L⁻¹ (p' − d) + s t.
    const Eigen::Matrix3d back = to.linear.inverse();
    View v = view;
    v.rotation = view.rotation * back;
    v.translation = to.scale * view.translation - v.rotation * to.translation;
    return v;
}

}  // namespace pc::cameras
