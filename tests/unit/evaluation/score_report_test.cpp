#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <pc/evaluation/score_report.h>

namespace pc::evaluation {
namespace {

/// 4 predictions against 5 fruit, 3 matched: precision 3/4, recall 3/5, F1 2PR/(P+R) = 2/3.
InstanceScores scores() {
    InstanceScores s;
    s.count = 4;
    s.gt_count = 5;
    s.true_positives = 3;
    s.precision = 0.75;
    s.recall = 0.6;
    s.f1 = 2.0 / 3.0;
    s.recovery = 0.8;
    s.merged = {2};
    s.matches = {{1, 10, 50, 0.9}, {2, 11, 40, 0.6}, {3, 12, 30, 0.7}};
    return s;
}

TEST(ScoreReport, JsonCountsFalsePositivesAndMissedFruit) {
    const auto j = nlohmann::json::parse(
        score_report(scores(), "tree", "tree.pcd", "overlap", ScoreFormat::kJson));
    EXPECT_EQ(j["name"], "tree");
    EXPECT_EQ(j["false_positives"], 1);  // 4 predictions - 3 matched
    EXPECT_EQ(j["missed"], 2);           // 5 fruit - 3 matched
    EXPECT_DOUBLE_EQ(j["f1"].get<double>(), 2.0 / 3.0);
    EXPECT_EQ(j["merged_labels"], nlohmann::json({2}));
    ASSERT_EQ(j["matches"].size(), 3u);
    EXPECT_EQ(j["matches"][1]["iou"], 0.6);
    const auto c = nlohmann::json::parse(
        score_report(scores(), "tree", "tree.pcd", "centroid", ScoreFormat::kJson));
    EXPECT_EQ(c["matches"][0]["distance"], 50.0);
    EXPECT_FALSE(c["matches"][0].contains("iou"));
}

TEST(ScoreReport, CsvAndMarkdownAreOneRowUnderTheirHeader) {
    EXPECT_EQ(
        score_report(scores(), "tree", "tree.pcd", "overlap", ScoreFormat::kCsv),
        "name,match,count,gt_count,recovery,true_positives,false_positives,missed,precision,"
        "recall,f1,merged,split\ntree,overlap,4,5,0.8,3,1,2,0.75,0.6,0.6666666666666666,1,0\n");
    EXPECT_EQ(score_report(scores(), "tree", "tree.pcd", "overlap", ScoreFormat::kMarkdown),
              "| Cloud | Count | GT | Recovery | Precision | Recall | F1 | Merged | Split |\n"
              "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n"
              "| tree | 4 | 5 | 0.800 | 0.750 | 0.600 | 0.667 | 1 | 0 |\n");
}

}  // namespace
}  // namespace pc::evaluation
