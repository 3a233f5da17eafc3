#include <Eigen/LU>
#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/features/transform.h>

namespace pc::features {
namespace {

TEST(Transform, ParsesFourByFourAndThreeByFour) {
    const Matrix4 a = parse_matrix("1 0 0 5\n0 1 0 6\n0 0 1 7\n0 0 0 1", "m");
    const Matrix4 b = parse_matrix("1,0,0,5, 0,1,0,6, 0,0,1,7", "m");
    EXPECT_EQ(a, b);
    EXPECT_EQ(a(1, 3), 6);
    EXPECT_THROW((void)parse_matrix("1 2 3", "m"), InvalidArgument);
    EXPECT_THROW((void)parse_matrix("0 0 0 0 0 0 0 0 0 0 0 0", "m"), InvalidArgument);  // singular
}

TEST(Transform, RotationAboutZByNinetyDegrees) {
    const Matrix4 r = rotation({0, 0, 2}, 90);
    const Eigen::Vector4d p = r * Eigen::Vector4d(1, 0, 0, 1);
    EXPECT_NEAR(p.x(), 0, 1e-15);
    EXPECT_NEAR(p.y(), 1, 1e-15);
}

TEST(Transform, NerfstudioForwardIsScaleTimesTransform) {
    const Matrix4 m = nerfstudio_forward(
        R"({"transform": [[0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3]], "scale": 0.25})", "ns");
    const Eigen::Vector4d p = m * Eigen::Vector4d(1, 0, 0, 1);  // T p = (1, 3, 3)
    EXPECT_DOUBLE_EQ(p.x(), 0.25);
    EXPECT_DOUBLE_EQ(p.y(), 0.75);
    EXPECT_DOUBLE_EQ(p.z(), 0.75);
    const Eigen::Vector4d back = m.inverse() * p;
    EXPECT_NEAR(back.x(), 1, 1e-15);
    EXPECT_THROW((void)nerfstudio_forward(R"({"transform": [], "scale": 1})", "ns"), IoError);
    EXPECT_THROW((void)nerfstudio_forward("not json", "ns"), IoError);
}

}  // namespace
}  // namespace pc::features
