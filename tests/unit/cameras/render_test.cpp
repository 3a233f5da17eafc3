// render_nearest and look_at: the target lands on the principal point, a near sheet covers the
// far one where it lies in front of it, empty pixels stay -1.
#include <vector>

#include <gtest/gtest.h>

#include <pc/cameras/render.h>
#include <pc/core/error.h>

namespace pc::cameras {
namespace {

TEST(Render, LookAtPutsTheTargetOnThePrincipalPointWithUpUp) {
    const View v = look_at({3, -4, 2}, {1, 1, 1}, Eigen::Vector3d::UnitZ(), 200, 100, 0.7);
    const auto centre = project(v.camera, v.to_camera({1, 1, 1}));
    ASSERT_TRUE(centre);
    EXPECT_NEAR(centre->x(), 100, 1e-9);
    EXPECT_NEAR(centre->y(), 50, 1e-9);
    const auto above = project(v.camera, v.to_camera({1, 1, 1.1}));
    ASSERT_TRUE(above);
    EXPECT_LT(above->y(), 50);  // up in the world is up in the image
    // looking straight down along `up` still gives a camera
    const View top = look_at({0, 0, 5}, {0, 0, 0}, Eigen::Vector3d::UnitZ(), 64, 64, 0.7);
    EXPECT_TRUE(top.rotation.allFinite());
    EXPECT_NEAR(top.rotation.determinant(), 1, 1e-12);
}

TEST(Render, TheNearestPointWinsEachPixel) {
    // a camera at the origin looking down +z; sheet A at z = 1 over x < 0, sheet B at z = 2
    // everywhere: pixels left of the centre show A, right of it B.
    View v = look_at({0, 0, 0}, {0, 0, 1}, -Eigen::Vector3d::UnitY(), 100, 100, 1.0);
    Cloud c;
    for (double x = -1; x <= 1.0001; x += 0.01) {
        for (double y = -1; y <= 1.0001; y += 0.01) {
            if (x < 0) {
                c.push_back({static_cast<float>(x), static_cast<float>(y), 1});
            }
            c.push_back({static_cast<float>(2 * x), static_cast<float>(2 * y), 2});
        }
    }
    const std::vector<std::int32_t> idx = render_nearest(XyzView(c), v, 0.01, {});
    ASSERT_EQ(idx.size(), 100u * 100u);
    for (int y = 10; y < 90; y += 7) {
        const std::int32_t left = idx[static_cast<std::size_t>(y) * 100 + 20];
        const std::int32_t right = idx[static_cast<std::size_t>(y) * 100 + 80];
        ASSERT_GE(left, 0);
        ASSERT_GE(right, 0);
        EXPECT_EQ(c[static_cast<std::size_t>(left)].z, 1) << y;
        EXPECT_EQ(c[static_cast<std::size_t>(right)].z, 2) << y;
    }
    Cloud far;
    far.push_back({0, 0, -1});  // behind: nothing drawn
    const std::vector<std::int32_t> none = render_nearest(XyzView(far), v, 0.01, {});
    EXPECT_TRUE(std::all_of(none.begin(), none.end(), [](std::int32_t i) { return i == -1; }));
    EXPECT_THROW((void)render_nearest(XyzView(c), v, 0, {}), InvalidArgument);
}

}  // namespace
}  // namespace pc::cameras
