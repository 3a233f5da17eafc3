#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <Eigen/Core>

namespace pc::cameras {

/// The camera models COLMAP and nerfstudio write (COLMAP's names; nerfstudio's `camera_model`
/// uses the same for the ones it knows).
enum class Model { kSimplePinhole, kPinhole, kSimpleRadial, kRadial, kOpenCv, kOpenCvFisheye };

[[nodiscard]] std::string_view model_name(Model model);
/// The model of a COLMAP / nerfstudio name ("OPENCV", ...); nullopt for a name not listed above.
[[nodiscard]] std::optional<Model> model_from_name(std::string_view name);

/// Intrinsics in pixels. Pixel coordinates: u right, v down, the image's top-left corner at
/// (0, 0), so the first pixel's centre is (0.5, 0.5) (COLMAP's convention, which nerfstudio's cx,
/// cy follow). Distortion acts on normalised coordinates x = X/Z, y = Y/Z as COLMAP and OpenCV
/// define it: radial k1..k3 (k1 only for SIMPLE_RADIAL, k1 k2 for RADIAL) and tangential p1 p2
/// (OPENCV); OPENCV_FISHEYE maps the angle θ = atan(r) to θ(1 + k1θ² + k2θ⁴ + k3θ⁶ + k4θ⁸).
struct Intrinsics {
    Model model = Model::kPinhole;
    int width = 0;  ///< pixels
    int height = 0;
    double fx = 0, fy = 0, cx = 0, cy = 0;
    double k1 = 0, k2 = 0, k3 = 0, k4 = 0, p1 = 0, p2 = 0;

    /// Throws pc::InvalidArgument unless the size and focal lengths are > 0 and every value is
    /// finite.
    void validate() const;
};

/// One calibrated image: the world-to-camera pose in COLMAP / OpenCV axes (x right, y down, z
/// forward: a point is in front of the camera when its z > 0).
struct View {
    Intrinsics camera;
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< world -> camera
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();   ///< camera = rotation·world + this
    std::string image;  ///< the image's file name as the source gave it
    std::string mask;   ///< its mask's file name when the source gives one, else empty

    [[nodiscard]] Eigen::Vector3d to_camera(const Eigen::Vector3d& world) const {
        return rotation * world + translation;
    }
    /// The camera's centre in world coordinates (rotation orthonormal).
    [[nodiscard]] Eigen::Vector3d centre() const { return -rotation.transpose() * translation; }
};

/// The pixel (u, v) a point given in camera coordinates lands on, or nullopt when it is not in
/// front of the camera (z <= 0) or lies where the distortion polynomial folds back (beyond its
/// largest radius: such a point would land inside the image by mistake). The pixel may lie
/// outside the image; callers check the bounds.
[[nodiscard]] std::optional<Eigen::Vector2d> project(const Intrinsics& camera,
                                                     const Eigen::Vector3d& in_camera);

/// A similarity p' = scale · linear · p + translation (linear is a rotation for the frames
/// below): how a cloud or cameras move from one frame to another.
struct Similarity {
    double scale = 1;
    Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();

    [[nodiscard]] Eigen::Vector3d apply(const Eigen::Vector3d& p) const {
        return scale * (linear * p) + translation;
    }
    [[nodiscard]] Similarity inverse() const;
};

/// The same view expressed in the frame `to` maps its world into: every point p of the old
/// world projects to the same pixel as to.apply(p) does through the result (depths scale by
/// to.scale).
[[nodiscard]] View moved(const View& view, const Similarity& to);

}  // namespace pc::cameras
