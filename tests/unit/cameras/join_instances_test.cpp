// join_instances: small sighting tables written by hand, whose right answer can be read off them:
// two fruit touching (points either side of the contact land in the other fruit's instance in one
// view each), a view that sees both fruit as one instance, points seen in more views than links
// are kept for, points not kept or never sighted, and the answer's independence of the sightings'
// order.
#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include <pc/cameras/join_instances.h>
#include <pc/core/error.h>

namespace pc::cameras {
namespace {

constexpr std::uint32_t kPer = 100;  // points 0..99 are fruit X, 100..199 fruit Y

/// Views 0 and 1 see X and Y apart (ids 1/2 and 5/3); view 2 sees only X (id 7). Five points of X
/// next to the contact fall in Y's instance in view 1, five of Y in X's instance in view 0.
std::vector<Sighting> touching() {
    std::vector<Sighting> s;
    for (std::uint32_t i = 0; i < 2 * kPer; ++i) {
        const bool x = i < kPer;
        const bool spill0 = i >= kPer && i < kPer + 5, spill1 = i >= kPer - 5 && i < kPer;
        s.push_back({i, 0, (x || spill0) ? 1u : 2u});
        s.push_back({i, 1, (x && !spill1) ? 5u : 3u});
        if (x) {
            s.push_back({i, 2, 7});
        }
    }
    return s;
}

std::set<std::uint32_t> labels_of(const std::vector<std::uint32_t>& l,
                                  std::uint32_t from,
                                  std::uint32_t to) {
    return {l.begin() + from, l.begin() + to};
}

TEST(JoinInstances, TouchingFruitStayApartAndContactPointsGoToTheirMajority) {
    const std::vector<std::uint8_t> keep(2 * kPer, 1);
    const std::vector<std::uint32_t> l = join_instances(touching(), keep, {}).labels;
    EXPECT_EQ(labels_of(l, 0, kPer), std::set<std::uint32_t>{1});  // X is larger: label 1
    EXPECT_EQ(labels_of(l, kPer + 5, 2 * kPer), std::set<std::uint32_t>{2});
    for (std::uint32_t i = kPer; i < kPer + 5; ++i) {
        // sighted once in X's instance (view 0) and once in Y's (view 1): a tie, the lower group
        EXPECT_NE(l[i], 0u);
    }
    // Doubtful: those five ties; X's five spilled points have two sightings of three in X.
    const JoinResult r = join_instances(touching(), keep, {});
    EXPECT_EQ(r.labelled, 2 * kPer);
    EXPECT_EQ(r.doubtful, 5u);
}

TEST(JoinInstances, AViewThatSeesTwoFruitAsOneCannotJoinThem) {
    std::vector<Sighting> s = touching();
    for (std::uint32_t i = 0; i < 2 * kPer; ++i) {
        s.push_back({i, 3, 9});  // view 3: X and Y one blob
    }
    const std::vector<std::uint32_t> l =
        join_instances(s, std::vector<std::uint8_t>(2 * kPer, 1), {}).labels;
    EXPECT_EQ(labels_of(l, 0, kPer - 5), std::set<std::uint32_t>{1});
    EXPECT_EQ(labels_of(l, kPer + 5, 2 * kPer), std::set<std::uint32_t>{2});
}

TEST(JoinInstances, MostViewsSeeingTwoFruitAsOneAreOutvotedByTheViewsThatSeeThemApart) {
    // Views 0, 1 and 2 see X and Y as one instance, views 3 and 4 apart (X: 1, Y: 2): two
    // against three, and yet every view that separates them is right.
    std::vector<Sighting> s;
    for (std::uint32_t i = 0; i < 2 * kPer; ++i) {
        for (std::uint32_t v = 0; v < 3; ++v) {
            s.push_back({i, v, 9});
        }
        for (std::uint32_t v = 3; v < 5; ++v) {
            s.push_back({i, v, i < kPer ? 1u : 2u});
        }
    }
    const JoinResult r = join_instances(s, std::vector<std::uint8_t>(2 * kPer, 1), {});
    EXPECT_EQ(labels_of(r.labels, 0, kPer).size(), 1u);
    EXPECT_EQ(labels_of(r.labels, kPer, 2 * kPer).size(), 1u);
    EXPECT_NE(r.labels[0], r.labels[kPer]);
    EXPECT_EQ(r.doubtful, 0u);  // the merging views are left out: views 3 and 4 agree
}

TEST(JoinInstances, BinaryMasksJoinEverythingOneViewSeesAsFruit) {
    // one instance per view: nothing tells X from Y
    std::vector<Sighting> s = touching();
    for (Sighting& x : s) {
        x.instance = 1;
    }
    const std::vector<std::uint32_t> l =
        join_instances(s, std::vector<std::uint8_t>(2 * kPer, 1), {}).labels;
    EXPECT_EQ(labels_of(l, 0, 2 * kPer), std::set<std::uint32_t>{1});
}

TEST(JoinInstances, PointsNotKeptOrNeverSightedAreZeroAndInstanceZeroIsNoSighting) {
    std::vector<Sighting> s = touching();
    s.push_back({2 * kPer, 0, 0});  // a point sighted only on background
    std::vector<std::uint8_t> keep(2 * kPer + 2, 1);
    keep[3] = 0;
    const std::vector<std::uint32_t> l = join_instances(s, keep, {}).labels;
    ASSERT_EQ(l.size(), keep.size());
    EXPECT_EQ(l[3], 0u);
    EXPECT_EQ(l[2 * kPer], 0u);
    EXPECT_EQ(l[2 * kPer + 1], 0u);
    EXPECT_EQ(l[4], 1u);
    EXPECT_TRUE(join_instances({}, keep, {}).labels.size() == keep.size());
    EXPECT_THROW((void)join_instances(s, keep, {}, {.fragment = 1.5}), InvalidArgument);
}

TEST(JoinInstances, ManyViewsLinkedAsStarsStillKeepTheFruitApart) {
    // 40 views see X and Y apart with ids that differ from view to view; every point links one
    // of its 40 instances to the others. Every fifth view spills 3 contact points each way.
    std::vector<Sighting> s;
    for (std::uint32_t v = 0; v < 40; ++v) {
        for (std::uint32_t i = 0; i < 2 * kPer; ++i) {
            const bool x = i < kPer;
            const bool spill = v % 5 == 0 && ((x && i >= kPer - 3) || (!x && i < kPer + 3));
            s.push_back({i, v, (x != spill) ? 2 * v + 1 : 2 * v + 2});
        }
    }
    const std::vector<std::uint32_t> l =
        join_instances(s, std::vector<std::uint8_t>(2 * kPer, 1), {}).labels;
    const auto x = labels_of(l, 0, kPer), y = labels_of(l, kPer, 2 * kPer);
    EXPECT_EQ(x.size(), 1u);
    EXPECT_EQ(y.size(), 1u);
    EXPECT_NE(*x.begin(), *y.begin());
}

TEST(JoinInstances, APartSeenOnlyByViewsThatSeeNothingElseOfItsFruitJoinsTheFruitItTouches) {
    // X: points 0..99 in views 0 and 1; a sliver of X, points 100..109, only in view 2; Y:
    // points 110..209 in views 0, 1 and 2. The sliver shares no point with X's instances.
    std::vector<Sighting> s;
    for (std::uint32_t i = 0; i < 100; ++i) {
        s.push_back({i, 0, 1});
        s.push_back({i, 1, 1});
        s.push_back({110 + i, 0, 2});
        s.push_back({110 + i, 1, 2});
        s.push_back({110 + i, 2, 5});
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> touching;
    for (std::uint32_t i = 100; i < 110; ++i) {
        s.push_back({i, 2, 4});
        touching.emplace_back(i, i - 10);  // next to X's points 90..99
    }
    touching.emplace_back(109, 110);  // and one next to Y
    const std::vector<std::uint8_t> keep(210, 1);
    const std::vector<std::uint32_t> alone = join_instances(s, keep, {}).labels;
    EXPECT_EQ(labels_of(alone, 100, 110), std::set<std::uint32_t>{3});  // a third label
    const std::vector<std::uint32_t> l = join_instances(s, keep, touching).labels;
    EXPECT_EQ(labels_of(l, 0, 110).size(), 1u);
    EXPECT_EQ(labels_of(l, 110, 210).size(), 1u);
    EXPECT_NE(l[0], l[110]);
    // Only parts up to `fragment` of the larger group's size join: 10 points are 0.1 of X's.
    const std::vector<std::uint32_t> apart =
        join_instances(s, keep, touching, {.fragment = 0.05}).labels;
    EXPECT_EQ(labels_of(apart, 100, 110).size(), 1u);
    EXPECT_NE(apart[100], apart[0]);
}

TEST(JoinInstances, TheOrderOfTheSightingsDoesNotMatter) {
    std::vector<Sighting> s = touching();
    const std::vector<std::uint8_t> keep(2 * kPer, 1);
    const std::vector<std::uint32_t> first = join_instances(s, keep, {}).labels;
    std::mt19937 rng(7);
    std::shuffle(s.begin(), s.end(), rng);
    EXPECT_EQ(join_instances(s, keep, {}).labels, first);
}

}  // namespace
}  // namespace pc::cameras
