// Sphere fitting and hollow splitting on exact shells.
#include <gtest/gtest.h>

#include <pc/segmentation/sphere_split.h>

#include "support/clouds.h"

namespace pc::segmentation {
namespace {

TEST(FitSphere, ACapGivesItsSphereExactly) {
    Cloud c;
    std::vector<std::uint32_t> all;
    for (const auto& p : test::sphere_shell(2.0f, 2000, 7)) {
        if (p.z > 1.0f) {  // a cap: the fit must not assume the centroid is the centre
            c.push_back({p.x + 5, p.y - 3, p.z + 2});
            all.push_back(static_cast<std::uint32_t>(c.size() - 1));
        }
    }
    const Sphere s = fit_sphere(c, all);
    ASSERT_TRUE(s.ok);
    EXPECT_NEAR(s.centre[0], 5, 1e-3);
    EXPECT_NEAR(s.centre[1], -3, 1e-3);
    EXPECT_NEAR(s.centre[2], 2, 1e-3);
    EXPECT_NEAR(s.radius, 2, 1e-3);
    EXPECT_LT(s.rms, 1e-4);
    EXPECT_FALSE(fit_sphere(c, std::vector<std::uint32_t>{0, 1, 2}).ok);  // too few points
}

TEST(SplitHollow, TwoTouchingShellsBecomeTwoAndOneStaysOne) {
    Cloud c;
    std::vector<std::uint32_t> one, two;
    for (const auto& p : test::sphere_shell(1.0f, 600, 4)) {
        c.push_back(p);
    }
    for (const auto& p : test::sphere_shell(1.0f, 600, 5)) {
        c.push_back({p.x + 2.05f, p.y, p.z});
    }
    for (std::uint32_t i = 0; i < c.size(); ++i) {
        (i < 600 ? one : two).push_back(i);
    }
    std::vector<std::uint32_t> both = one;
    both.insert(both.end(), two.begin(), two.end());
    for (std::uint64_t seed = 0; seed < 5; ++seed) {
        const auto part = split_hollow(c, both, 1.0, 0.07, 600, {.seed = seed});
        for (std::size_t k = 0; k < both.size(); ++k) {
            EXPECT_EQ(part[k], part[k < 600 ? 0 : 600]) << "seed " << seed << " point " << k;
        }
        EXPECT_NE(part[0], part[600]) << "seed " << seed;
        const auto single = split_hollow(c, one, 1.0, 0.07, 600, {.seed = seed});
        EXPECT_EQ(std::count(single.begin(), single.end(), 0u), 600) << "seed " << seed;
    }
}

}  // namespace
}  // namespace pc::segmentation
