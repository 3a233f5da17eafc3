// Projection: pixels computed by hand for the pinhole, OpenCV's own projectPoints and
// fisheye::projectPoints as the oracle for the distortion models, fold-back refused, and a view
// moved into another frame sees every point where it saw it before.
#include <cmath>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include <pc/cameras/camera.h>
#include <pc/core/error.h>
#include <pc/core/random.h>

namespace pc::cameras {
namespace {

Intrinsics camera(Model model) {
    Intrinsics c;
    c.model = model;
    c.width = 640;
    c.height = 480;
    c.fx = 500;
    c.fy = 400;
    c.cx = 320;
    c.cy = 240;
    return c;
}

TEST(Camera, PinholeLandsOnTheHandComputedPixel) {
    // x = 0.2 / 2 = 0.1, y = -0.1 / 2 = -0.05: u = 320 + 500 * 0.1, v = 240 - 400 * 0.05
    const auto px = project(camera(Model::kPinhole), {0.2, -0.1, 2});
    ASSERT_TRUE(px);
    EXPECT_DOUBLE_EQ(px->x(), 370);
    EXPECT_DOUBLE_EQ(px->y(), 220);
    EXPECT_FALSE(project(camera(Model::kPinhole), {0.2, -0.1, -2}));  // behind
    EXPECT_FALSE(project(camera(Model::kPinhole), {0.2, -0.1, 0}));
}

TEST(Camera, RadialAndOpenCvModelsMatchOpenCvProjectPoints) {
    Rng rng(7);
    for (const Model m : {Model::kSimpleRadial, Model::kRadial, Model::kOpenCv}) {
        Intrinsics c = camera(m);
        c.k1 = -0.12;
        c.k2 = m == Model::kSimpleRadial ? 0 : 0.03;
        c.k3 = m == Model::kOpenCv ? -0.004 : 0;
        c.p1 = m == Model::kOpenCv ? 0.0015 : 0;
        c.p2 = m == Model::kOpenCv ? -0.0007 : 0;
        const cv::Matx33d k(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
        const std::vector<double> dist{c.k1, c.k2, c.p1, c.p2, c.k3};
        for (int i = 0; i < 200; ++i) {
            const Eigen::Vector3d q(rng.uniform(-0.6, 0.6), rng.uniform(-0.45, 0.45), 1);
            std::vector<cv::Point3d> in{{q.x(), q.y(), q.z()}};
            std::vector<cv::Point2d> out;
            cv::projectPoints(in, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), k, dist, out);
            const auto px = project(c, 3.5 * q);  // any depth: same pixel
            ASSERT_TRUE(px) << model_name(m);
            EXPECT_NEAR(px->x(), out[0].x, 1e-9) << model_name(m);
            EXPECT_NEAR(px->y(), out[0].y, 1e-9) << model_name(m);
        }
    }
}

TEST(Camera, FisheyeMatchesOpenCvFisheyeProjectPoints) {
    Intrinsics c = camera(Model::kOpenCvFisheye);
    c.k1 = 0.05;
    c.k2 = -0.01;
    c.k3 = 0.002;
    c.k4 = -0.0003;
    const cv::Matx33d k(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
    const cv::Vec4d dist(c.k1, c.k2, c.k3, c.k4);
    Rng rng(8);
    for (int i = 0; i < 200; ++i) {
        // up to about 70 degrees off the axis
        const Eigen::Vector3d q(rng.uniform(-2, 2), rng.uniform(-2, 2), 1);
        std::vector<cv::Point3d> in{{q.x(), q.y(), q.z()}};
        std::vector<cv::Point2d> out;
        cv::fisheye::projectPoints(in, out, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), k, dist);
        const auto px = project(c, q);
        ASSERT_TRUE(px);
        EXPECT_NEAR(px->x(), out[0].x, 1e-8);
        EXPECT_NEAR(px->y(), out[0].y, 1e-8);
    }
    const auto centre = project(c, {0, 0, 1});
    ASSERT_TRUE(centre);
    EXPECT_DOUBLE_EQ(centre->x(), 320);
}

TEST(Camera, PointsWhereTheDistortionFoldsBackAreNotProjected) {
    // r (1 - 0.5 r²) grows up to r² = 2/3 and falls after: a point at r = 1.2 would land at
    // 0.336, inside the image, by mistake.
    Intrinsics c = camera(Model::kRadial);
    c.k1 = -0.5;
    EXPECT_TRUE(project(c, {0.5, 0, 1}));
    EXPECT_FALSE(project(c, {1.2, 0, 1}));
}

TEST(Camera, AMovedViewSeesTheMovedPointOnTheSamePixel) {
    View v;
    v.camera = camera(Model::kOpenCv);
    v.camera.k1 = -0.05;
    v.rotation =
        Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
    v.translation = {0.1, -0.2, 3};
    const Similarity s{
        2.5,
        Eigen::AngleAxisd(-1.1, Eigen::Vector3d(0.2, 1, 0.3).normalized()).toRotationMatrix(),
        {4, -1, 0.5}};
    const View w = moved(v, s);
    Rng rng(9);
    for (int i = 0; i < 50; ++i) {
        const Eigen::Vector3d p(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        const auto a = project(v.camera, v.to_camera(p));
        const auto b = project(w.camera, w.to_camera(s.apply(p)));
        ASSERT_EQ(a.has_value(), b.has_value());
        if (a) {
            EXPECT_NEAR((*a - *b).norm(), 0, 1e-9);
        }
        EXPECT_NEAR(w.to_camera(s.apply(p)).z(), s.scale * v.to_camera(p).z(), 1e-9);
        EXPECT_NEAR((s.inverse().apply(s.apply(p)) - p).norm(), 0, 1e-12);
    }
    EXPECT_NEAR((w.centre() - s.apply(v.centre())).norm(), 0, 1e-9);
}

TEST(Camera, NamesRoundTripAndBadIntrinsicsAreRefused) {
    for (const Model m : {Model::kSimplePinhole, Model::kPinhole, Model::kSimpleRadial,
                          Model::kRadial, Model::kOpenCv, Model::kOpenCvFisheye}) {
        EXPECT_EQ(model_from_name(model_name(m)), m);
    }
    EXPECT_FALSE(model_from_name("FOV"));
    Intrinsics c = camera(Model::kPinhole);
    EXPECT_NO_THROW(c.validate());
    c.fx = 0;
    EXPECT_THROW(c.validate(), InvalidArgument);
    c = camera(Model::kPinhole);
    c.width = 0;
    EXPECT_THROW(c.validate(), InvalidArgument);
    c = camera(Model::kPinhole);
    c.k1 = std::nan("");
    EXPECT_THROW(c.validate(), InvalidArgument);
}

}  // namespace
}  // namespace pc::cameras
