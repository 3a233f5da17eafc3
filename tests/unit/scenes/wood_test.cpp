// Wood (trunk and branches): the layout's invariants and its points in both kinds of mode, against
// the closed form of a truncated cone.
#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/scenes/render.h>

namespace pc::scenes {
namespace {

constexpr double kPi = 3.141592653589793;

/// Where q lies relative to the branch: its position t along the axis (0 at `from`, 1 at `to`)
/// and its distance from the axis.
std::pair<double, double> along_and_off(const Branch& b, const std::array<float, 3>& q) {
    double axis[3], rel[3], length2 = 0, t = 0;
    for (int a = 0; a < 3; ++a) {
        axis[a] = b.to[a] - b.from[a];
        rel[a] = q[a] - b.from[a];
        length2 += axis[a] * axis[a];
        t += rel[a] * axis[a];
    }
    t /= length2;
    double off2 = 0;
    for (int a = 0; a < 3; ++a) {
        const double d = rel[a] - t * axis[a];
        off2 += d * d;
    }
    return {t, std::sqrt(off2)};
}

/// One branch 0.3 long along x, radius 0.02 tapering to 0.01, bark (100, 80, 60); nothing else.
Scene one_branch() {
    Scene s;
    s.branches.push_back({{0, 0, 0}, {0.3, 0, 0}, 0.02, 0.01});
    return s;
}

RenderParams bare(Mode mode, double spacing = 0.002) {
    return {.mode = mode, .voxel = spacing, .leaf_leak = 0, .background = 0, .outliers = 0};
}

SceneParams tree(std::uint32_t branches) {
    SceneParams p = species("peach");
    p.fruit_count = 40;
    p.canopy = {0.6, 0.6, 0.5};
    p.branches = branches;
    p.seed = 11;
    return p;
}

double level(const SceneParams& p, const Vec3& q) {
    double s = 0;
    for (int a = 0; a < 3; ++a) {
        s += (q[a] / p.canopy[a]) * (q[a] / p.canopy[a]);
    }
    return std::sqrt(s);
}

TEST(Wood, ATrunkForksIntoBranchesInsideTheCanopyAndLeavesFruitAndLeavesAsTheyWere) {
    const SceneParams p = tree(5);
    const Scene with = make_scene(p), without = make_scene(tree(0));
    ASSERT_EQ(with.branches.size(), 1u + 3 * 5);  // the trunk, 5 main branches, 2 side each
    EXPECT_TRUE(without.branches.empty());
    const Branch& trunk = with.branches[0];
    EXPECT_DOUBLE_EQ(trunk.from[2], -p.canopy[2] - 0.3);  // on the ground
    EXPECT_DOUBLE_EQ(trunk.to[2], -0.3 * p.canopy[2]);    // the fork
    EXPECT_DOUBLE_EQ(trunk.r_from, p.trunk_radius);
    for (std::size_t b = 1; b < with.branches.size(); ++b) {
        const Branch& x = with.branches[b];
        EXPECT_GT(x.r_from, x.r_to);  // tapering
        EXPECT_GT(x.r_to, 0);
        // main branches end at 0.85 of the canopy, side branches inside 0.95 of it
        if ((b - 1) % 3 == 0) {
            EXPECT_NEAR(level(p, x.to), 0.85, 1e-9);
            EXPECT_EQ(x.from, trunk.to);
        } else {
            EXPECT_LE(level(p, x.to), 0.95 + 1e-9);
        }
    }
    // wood has its own random stream: the fruit and leaves are those of the scene without it
    ASSERT_EQ(with.fruits.size(), without.fruits.size());
    for (std::size_t f = 0; f < with.fruits.size(); ++f) {
        EXPECT_EQ(with.fruits[f].centre, without.fruits[f].centre);
    }
    ASSERT_EQ(with.leaves.size(), without.leaves.size());
    EXPECT_EQ(with.leaves.back().centre, without.leaves.back().centre);
}

TEST(Wood, SampledPointsLieOnTheBranchSideOnePerSpacingSquaredInBarkColour) {
    const Scene s = one_branch();
    const double v = 0.002;
    const Rendered r = render(s, bare(Mode::kSurface, v));
    // the side of a thin cone: pi (r1 + r2) length / spacing^2
    EXPECT_EQ(r.xyz.size(),
              static_cast<std::size_t>(std::llround(kPi * (0.02 + 0.01) * 0.3 / (v * v))));
    std::size_t near_thick_end = 0;
    for (std::size_t n = 0; n < r.xyz.size(); ++n) {
        const auto [t, off] = along_and_off(s.branches[0], r.xyz[n]);
        ASSERT_GE(t, -1e-6);
        ASSERT_LE(t, 1 + 1e-6);
        ASSERT_NEAR(off, 0.02 + t * (0.01 - 0.02), 1e-6);
        near_thick_end += t < 0.5;
        EXPECT_EQ(r.gt[n], 0u);
        const double red = (r.rgb[n] >> 16) & 255, blue = r.rgb[n] & 255;
        EXPECT_NEAR(red, 100 * 0.975, 100 * 0.16 + 8 + 1);  // tone 0.85..1.1 x 0.95..1.05, ±8
        EXPECT_NEAR(blue, 60 * 0.975, 60 * 0.16 + 8 + 1);
    }
    // uniform over the side (density along the axis as the radius): the thick half holds
    // integral of (0.02 - 0.01 t) over [0, 1/2] / over [0, 1] = 7/12
    EXPECT_NEAR(static_cast<double>(near_thick_end) / r.xyz.size(), 7.0 / 12, 0.02);
}

TEST(Wood, LatticePointsAreVoxelCentresOneEachOnTheSurface) {
    const Scene s = one_branch();
    const double v = 0.002;
    const Rendered r = render(s, bare(Mode::kExplicit, v));
    ASSERT_GT(r.xyz.size(), 1000u);
    std::set<std::tuple<long, long, long>> voxels;
    for (const auto& q : r.xyz) {
        long idx[3];
        for (int a = 0; a < 3; ++a) {
            const double i = q[a] / v - 0.5;
            idx[a] = std::lround(i);
            ASSERT_NEAR(i, static_cast<double>(idx[a]), 1e-3);  // a voxel centre
        }
        EXPECT_TRUE(voxels.insert({idx[0], idx[1], idx[2]}).second);  // one point per voxel
        const auto [t, off] = along_and_off(s.branches[0], q);
        // within half a voxel's diagonal of the side
        EXPECT_NEAR(off, 0.02 + std::clamp(t, 0.0, 1.0) * (0.01 - 0.02), 0.87 * v);
    }
}

TEST(Wood, NoWoodPointInsideAFruitMaskColoursAreDarkAndLeakDropsBranches) {
    Scene s = one_branch();
    s.fruits.push_back({{0.15, 0, 0.02}, 0.03, 0});  // a fruit hanging on the branch
    s.bunch_count = 1;
    RenderParams p = bare(Mode::kSurface);
    const Rendered r = render(s, p);
    std::size_t wood = 0;
    for (std::size_t n = 0; n < r.xyz.size(); ++n) {
        if (r.gt[n] == 0) {
            ++wood;
            EXPECT_GT(s.fruits[0].level({r.xyz[n][0], r.xyz[n][1], r.xyz[n][2]}), 1 - 1e-6);
        }
    }
    EXPECT_GT(wood, 1000u);
    p.colors = Colors::kMask;
    const Rendered mask = render(s, p);
    for (std::size_t n = 0; n < mask.rgb.size(); ++n) {
        EXPECT_EQ(mask.gt[n] == 0, (mask.rgb[n] & 255) <= 12);  // wood black, fruit white
    }
    p.wood_leak = 0;
    const Rendered none = render(s, p);
    EXPECT_EQ(none.xyz.size(), none.fruit_points[0]);
    p.wood_leak = 1.5;
    EXPECT_THROW((void)render(s, p), InvalidArgument);
    SceneParams bad = tree(101);
    EXPECT_THROW((void)make_scene(bad), InvalidArgument);
    bad = tree(3);
    bad.trunk_radius = 0;
    EXPECT_THROW((void)make_scene(bad), InvalidArgument);
}

}  // namespace
}  // namespace pc::scenes
