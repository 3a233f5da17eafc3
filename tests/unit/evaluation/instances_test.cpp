// Instance scores: hand-made labellings with known answers, and a brute-force check of matching.
#include <map>
#include <random>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/evaluation/instances.h>

namespace pc::evaluation {
namespace {

using Ids = std::vector<std::uint32_t>;

/// `fruit` fruit of `each` points each, then `clutter` points of no fruit.
Ids truth(std::uint32_t fruit, std::uint32_t each, std::uint32_t clutter = 0) {
    Ids t;
    for (std::uint32_t f = 1; f <= fruit; ++f) {
        t.insert(t.end(), each, f);
    }
    t.insert(t.end(), clutter, 0);
    return t;
}

TEST(Overlap, PerfectLabellingUnderOtherNumbersScoresOne) {
    const Ids gt = truth(5, 10, 7);
    Ids pred(gt.size());
    for (std::size_t n = 0; n < gt.size(); ++n) {
        pred[n] = gt[n] ? 100 + (gt[n] * 7) % 5 : 0;  // renumbered; clutter is noise
    }
    const InstanceScores s = score_by_overlap(pred, gt, 0, {});
    EXPECT_EQ(s.count, 5u);
    EXPECT_EQ(s.gt_count, 5u);
    EXPECT_EQ(s.true_positives, 5u);
    EXPECT_DOUBLE_EQ(s.f1, 1.0);
    EXPECT_DOUBLE_EQ(s.recovery, 1.0);
    EXPECT_TRUE(s.merged.empty());
    EXPECT_TRUE(s.split.empty());
}

TEST(Overlap, TwoFruitMergedIsOneMerge) {
    const Ids gt = truth(4, 10);
    Ids pred = gt;
    for (auto& l : pred) {
        l = l == 2 ? 1 : l;  // fruit 1 and 2 in one prediction
    }
    const InstanceScores s = score_by_overlap(pred, gt, 0, {});
    EXPECT_EQ(s.count, 3u);
    EXPECT_EQ(s.merged, Ids{1});
    EXPECT_TRUE(s.split.empty());
    EXPECT_EQ(s.true_positives, 2u);  // IoU of the merged prediction is exactly 0.5: no match
    EXPECT_DOUBLE_EQ(s.precision, 2.0 / 3.0);
    EXPECT_DOUBLE_EQ(s.recall, 2.0 / 4.0);
    EXPECT_DOUBLE_EQ(s.f1, 4.0 / 7.0);
}

TEST(Overlap, OneFruitSplitInTwoIsOneSplit) {
    const Ids gt = truth(3, 10);
    Ids pred = gt;
    for (int k = 0; k < 3; ++k) {
        pred[k] = 9;  // 3 of fruit 1's 10 points form their own prediction
    }
    const InstanceScores s = score_by_overlap(pred, gt, 0, {});
    EXPECT_EQ(s.count, 4u);
    EXPECT_EQ(s.split, Ids{1});
    EXPECT_TRUE(s.merged.empty());
    EXPECT_EQ(s.true_positives, 3u);  // the 7-point part still matches (IoU 0.7)
    EXPECT_DOUBLE_EQ(s.precision, 3.0 / 4.0);
    EXPECT_DOUBLE_EQ(s.recall, 1.0);
}

TEST(Overlap, NoiseSmallClustersAndAbsentFruit) {
    const Ids gt = truth(3, 10);
    Ids pred = gt;
    pred[25] = 0;   // noise is never a prediction
    pred[26] = 50;  // a one-point prediction
    InstanceParams p;
    p.min_points = 2;
    const InstanceScores s =
        score_by_overlap(pred, gt, 5, p);  // 2 fruit never made it into the cloud
    EXPECT_EQ(s.count, 3u);
    EXPECT_EQ(s.gt_count, 5u);
    EXPECT_EQ(s.true_positives, 3u);
    EXPECT_DOUBLE_EQ(s.recall, 3.0 / 5.0);
    EXPECT_DOUBLE_EQ(s.recovery, 3.0 / 5.0);
    EXPECT_THROW((void)score_by_overlap(pred, gt, 2, p), InvalidArgument);  // fewer than present
}

TEST(Overlap, MatchesAreExactlyThePairsAboveHalfIoU) {
    // With IoU > 0.5 a pair is unique on both sides, so greedy matching must find every such pair.
    std::mt19937 rng(3);
    for (int trial = 0; trial < 50; ++trial) {
        Ids gt(400), pred(400);
        for (std::size_t n = 0; n < gt.size(); ++n) {
            gt[n] = rng() % 12;
            pred[n] = rng() % 4 ? gt[n] + 100 * (rng() % 2) : rng() % 15;
        }
        std::map<std::uint32_t, double> ls, gs;
        std::map<std::pair<std::uint32_t, std::uint32_t>, double> both;
        for (std::size_t n = 0; n < gt.size(); ++n) {
            ls[pred[n]] += pred[n] != 0;
            gs[gt[n]] += gt[n] != 0;
            both[{pred[n], gt[n]}] += pred[n] != 0 && gt[n] != 0;
        }
        std::size_t expected = 0;
        for (const auto& [k, n] : both) {
            expected += n > 0 && n / (ls[k.first] + gs[k.second] - n) > 0.5;
        }
        EXPECT_EQ(score_by_overlap(pred, gt, 0, {}).true_positives, expected) << trial;
    }
}

TEST(Centroid, MatchesWithinTheRadiusAndAttributesPointsToSpheres) {
    Cloud cloud;
    Ids pred;
    const auto add = [&](float x, float y, float z, std::uint32_t l) {
        cloud.push_back({x, y, z});
        pred.push_back(l);
    };
    // Fruit 1 at the origin (r 1): prediction 1 around it. Fruit 2 at x=10 (r 1) and fruit 3 at
    // x=12.5: prediction 2 spans both (centroid at 11.25, outside both radii).
    for (float d : {-0.5f, 0.5f}) {
        add(d, 0, 0, 1);
        add(10 + d, 0, 0, 2);
        add(12.5f + d, 0, 0, 2);
    }
    add(30, 0, 0, 3);  // a far floater
    const std::vector<TruthFruit> fruits = {
        {1, {0, 0, 0}, 1}, {2, {10, 0, 0}, 1}, {3, {12.5, 0, 0}, 1}};
    const InstanceScores s = score_by_centroid(cloud, pred, fruits, 0, {});
    EXPECT_EQ(s.count, 3u);
    EXPECT_EQ(s.gt_count, 3u);
    ASSERT_EQ(s.true_positives, 1u);
    EXPECT_EQ(s.matches[0].label, 1u);
    EXPECT_EQ(s.matches[0].fruit, 1u);
    EXPECT_EQ(s.merged, Ids{2});
    InstanceParams wide;
    wide.radius_factor =
        1.5;  // now 11.25 is within 1.5 of fruit 2 (and of fruit 3: tie, smaller id)
    const InstanceScores w = score_by_centroid(cloud, pred, fruits, 0, wide);
    EXPECT_EQ(w.true_positives, 2u);
    EXPECT_EQ(w.matches[1].fruit, 2u);
}

TEST(Params, BadValuesAreRefused) {
    InstanceParams p;
    p.min_iou = 0.3;
    EXPECT_THROW(p.validate(), InvalidArgument);
    p = {};
    p.share = 1.0;
    EXPECT_THROW(p.validate(), InvalidArgument);
    EXPECT_THROW((void)score_by_overlap(Ids{1, 2}, Ids{1}, 0, {}), InvalidArgument);
}

}  // namespace
}  // namespace pc::evaluation
