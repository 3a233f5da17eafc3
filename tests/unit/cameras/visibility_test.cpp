// visible_pixels: two parallel sheets, the far one hidden behind the near one exactly where the
// near one covers it; points seen at the pixel project() gives; behind and outside refused.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include <pc/cameras/visibility.h>
#include <pc/core/error.h>

namespace pc::cameras {
namespace {

View camera_at_origin() {
    View v;  // identity pose: looks down +z
    v.camera.width = 200;
    v.camera.height = 100;
    v.camera.fx = v.camera.fy = 100;
    v.camera.cx = 100;
    v.camera.cy = 50;
    return v;
}

/// A square sheet of points spaced `s` at depth z over x in [x0, x1], y in [-0.4, 0.4].
void sheet(Cloud& c, double z, double x0, double x1, double s) {
    for (double x = x0; x <= x1 + 1e-9; x += s) {
        for (double y = -0.4; y <= 0.4 + 1e-9; y += s) {
            c.push_back({static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)});
        }
    }
}

TEST(Visibility, ANearSheetHidesTheFarOneWhereItCoversIt) {
    // Near sheet at z = 1 over x in [-0.5, 0]; far sheet at z = 2 over x in [-0.9, 0.9]. A far
    // point hides behind the near sheet iff its ray crosses z = 1 within the near sheet's x
    // range: x/2 in [-0.5, 0]. Points a splat away from that edge are left out of the oracle.
    const double s = 0.01;
    Cloud c;
    sheet(c, 1, -0.5, 0, s);
    const std::size_t near = c.size();
    sheet(c, 2, -0.9, 0.9, s);
    const View v = camera_at_origin();
    const std::vector<std::int32_t> px = visible_pixels(XyzView(c), v, s, {});
    std::size_t checked = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
        const double x = c[i].x, z = c[i].z;
        const auto p = project(v.camera, {x, c[i].y, z});
        ASSERT_TRUE(p);
        const bool inside = p->x() >= 0 && p->x() < 200 && p->y() >= 0 && p->y() < 100;
        if (i < near) {
            EXPECT_EQ(px[i] >= 0, inside) << i;
        } else if (std::abs(x / 2 - 0) > 0.03 && std::abs(x / 2 + 0.5) > 0.03) {
            const bool hidden = x / 2 > -0.5 && x / 2 < 0;
            EXPECT_EQ(px[i] >= 0, inside && !hidden) << x;
            ++checked;
        }
        if (px[i] >= 0) {
            EXPECT_EQ(px[i],
                      static_cast<std::int32_t>(p->y()) * 200 + static_cast<std::int32_t>(p->x()));
        }
    }
    EXPECT_GT(checked, 10000u);
}

TEST(Visibility, BehindOutsideAndNonFiniteAreNeverSeen) {
    Cloud c;
    c.push_back({0, 0, -1});
    c.push_back({10, 0, 1});
    c.push_back({std::nanf(""), 0, 1});
    c.push_back({0, 0, 1});
    const std::vector<std::int32_t> px = visible_pixels(XyzView(c), camera_at_origin(), 0.01, {});
    EXPECT_EQ(px[0], -1);
    EXPECT_EQ(px[1], -1);
    EXPECT_EQ(px[2], -1);
    EXPECT_EQ(px[3], 50 * 200 + 100);
    EXPECT_THROW((void)visible_pixels(XyzView(c), camera_at_origin(), 0, {}), InvalidArgument);
    EXPECT_THROW((void)visible_pixels(XyzView(c), camera_at_origin(), 0.01, {.footprint = 0}),
                 InvalidArgument);
}

}  // namespace
}  // namespace pc::cameras
