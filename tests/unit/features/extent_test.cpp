#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include <pc/features/extent.h>

#include "support/clouds.h"

namespace pc::features {
namespace {

TEST(Extent, FilledCubeHullIsTheCubeExactly) {
    const Cloud c = test::grid({0, 0, 0}, 11, 0.1f);  // corners at 0 and 1.0000000149
    const Extent e = extent(c);
    const double side = double{10 * 0.1f};
    EXPECT_NEAR(e.hull_volume, side * side * side, 1e-6);
    EXPECT_NEAR(e.hull_area, 6 * side * side, 1e-6);
    EXPECT_FALSE(e.degenerate);
    EXPECT_NEAR(e.centroid[0], 0.5, 1e-6);
    EXPECT_NEAR(e.aabb_volume, e.hull_volume, 1e-6);
}

TEST(Extent, FinelySampledBallHullIsWithinOnePercent) {
    const double r = 2.0;
    const Extent e = extent(test::ball({1, 2, 3}, static_cast<float>(r), 200000, 5));
    const double v = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    EXPECT_NEAR(e.hull_volume, v, 0.01 * v);
    EXPECT_NEAR(e.mean_radius, 0.75 * r, 0.01 * r);  // uniform ball: E|x| = 3r/4
    EXPECT_NEAR(e.equivalent_diameter, 2 * r, 0.01 * 2 * r);
}

TEST(Extent, SphereShellMeanRadiusIsTheRadius) {
    const Extent e = extent(test::sphere_shell(1.5f, 20000, 3));
    EXPECT_NEAR(e.mean_radius, 1.5, 1e-3);
    EXPECT_NEAR(e.max_radius, 1.5, 2e-2);
}

TEST(Extent, InteriorPointsDoNotChangeTheHull) {
    // Every shell point is a hull vertex; the ball's points (radius < 1.5) never are. The hull is
    // computed over a prefiltered subset: it must be the shell's hull to rounding.
    const Cloud shell = test::sphere_shell(1.5f, 3000, 7);
    const Cloud both = test::concat(test::ball({0, 0, 0}, 1.45f, 100000, 8), shell);
    const Extent a = extent(shell), b = extent(both);
    EXPECT_NEAR(b.hull_volume, a.hull_volume, 1e-12 * a.hull_volume);
    EXPECT_NEAR(b.hull_area, a.hull_area, 1e-12 * a.hull_area);
    EXPECT_EQ(b.points, 103000u);
}

TEST(Extent, DegenerateInputsHaveNoHull) {
    Cloud plane;
    for (int i = 0; i < 10; ++i) {
        for (int j = 0; j < 10; ++j) {
            plane.push_back({static_cast<float>(i), static_cast<float>(j), 0});
        }
    }
    Cloud three = test::uniform(3, 1, 1), one = test::uniform(1, 1, 1), none;
    for (const Cloud* c : {&plane, &three, &one, &none}) {
        const Extent e = extent(*c);
        EXPECT_TRUE(e.degenerate);
        EXPECT_EQ(e.hull_volume, 0.0);
        EXPECT_EQ(e.points, c->size());
    }
}

TEST(Extent, PerLabelSkipsNoiseAndNonFinitePoints) {
    Cloud c = test::concat(test::grid({0, 0, 0}, 3, 1.0f), test::grid({10, 0, 0}, 3, 1.0f));
    c.push_back(test::nan_point());
    std::vector<std::uint32_t> labels(27, 2);
    labels.resize(54, 5);
    labels.push_back(2);
    labels[0] = 0;
    const auto per = extent_per_label(c, labels);
    ASSERT_EQ(per.size(), 2u);
    EXPECT_EQ(per[0].label, 2u);
    EXPECT_EQ(per[0].extent.points, 26u);
    EXPECT_NEAR(per[1].extent.hull_volume, 8.0, 1e-9);
}

}  // namespace
}  // namespace pc::features
