#include <cmath>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/features/compare.h>

#include "support/clouds.h"

namespace pc::features {
namespace {

TEST(Compare, CloudAgainstItselfIsPerfect) {
    const Cloud a = test::uniform(3000, 1.0f, 4);
    const CompareResult r = compare(a, a, {.tau = 0.001, .voxel = 0.05});
    EXPECT_EQ(r.a_to_b.max, 0.0);
    EXPECT_EQ(r.chamfer, 0.0);
    EXPECT_EQ(r.fscore, 1.0);
    EXPECT_EQ(r.interior_coverage, 1.0);
}

TEST(Compare, ShiftedLatticeDistancesAreTheShift) {
    const Cloud a = test::grid({0, 0, 0}, 6, 1.0f);
    const Cloud b = test::grid({0, 0, 0.25f}, 6, 1.0f);
    const CompareResult r = compare(a, b, {.tau = 0.2, .voxel = 1.0});
    EXPECT_DOUBLE_EQ(r.a_to_b.mean, 0.25);
    EXPECT_DOUBLE_EQ(r.b_to_a.max, 0.25);
    EXPECT_DOUBLE_EQ(r.chamfer, 0.5);
    EXPECT_EQ(r.precision, 0.0);  // 0.25 > tau
    EXPECT_EQ(r.fscore, 0.0);
}

TEST(Compare, HollowShellCoversLittleOfASolidBall) {
    const Cloud solid = test::ball({0, 0, 0}, 1.0f, 60000, 5);
    const Cloud hollow = test::sphere_shell(1.0f, 20000, 6);
    const CompareResult r = compare(hollow, solid, {.tau = 0.05, .voxel = 0.1});
    EXPECT_LT(r.interior_coverage, 0.5);  // only the outer layer of voxels is shared
    const CompareResult self = compare(solid, solid, {.tau = 0.05, .voxel = 0.1});
    EXPECT_EQ(self.interior_coverage, 1.0);
    // The ball's points are about 0.04 apart, so every shell point has one within 0.1.
    EXPECT_EQ(compare(hollow, solid, {.tau = 0.1, .voxel = 0.1}).precision, 1.0);
}

TEST(Compare, EmptySideGivesUndefinedDistancesAndZeroScores) {
    const CompareResult r = compare(Cloud{}, test::uniform(10, 1, 1), {});
    EXPECT_EQ(r.a_to_b.points, 0u);
    EXPECT_EQ(r.b_to_a.points, 10u);  // B's points are there, with nothing to measure to
    EXPECT_TRUE(std::isnan(r.b_to_a.mean));
    EXPECT_EQ(r.recall, 0.0);
    EXPECT_EQ(r.fscore, 0.0);
    ASSERT_EQ(compare_warnings(r, {}).size(), 1u);
    EXPECT_EQ(compare_warnings(r, {})[0].rfind("A has no finite point", 0), 0u);
}

TEST(Compare, WarnsWhenTheCloudsAreInDifferentFrames) {
    // The same cube twice: once where it is, once moved by 3 sides (a frame that does not match).
    const Cloud a = test::uniform(500, 1, 1);
    Cloud b = a;
    EXPECT_DOUBLE_EQ(compare(a, b, {}).box_overlap, 1.0);
    EXPECT_TRUE(compare_warnings(compare(a, b, {}), {}).empty());
    for (auto& p : b.points) {
        p.x += 3;
    }
    const CompareResult moved = compare(a, b, {});
    EXPECT_EQ(moved.box_overlap, 0.0);
    ASSERT_EQ(compare_warnings(moved, {}).size(), 1u);
    EXPECT_NE(compare_warnings(moved, {})[0].find("one frame"), std::string::npos);
    // Half a side along x: the boxes share about half of the smaller one.
    for (auto& p : b.points) {
        p.x -= 2.5f;
    }
    EXPECT_NEAR(compare(a, b, {}).box_overlap, 0.5, 0.02);
}

TEST(Compare, RejectsNonPositiveTau) {
    EXPECT_THROW((void)compare(Cloud{}, Cloud{}, {.tau = 0}), InvalidArgument);
}

}  // namespace
}  // namespace pc::features
