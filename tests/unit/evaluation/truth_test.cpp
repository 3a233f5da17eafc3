#include <string>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/evaluation/truth.h>

namespace pc::evaluation {
namespace {

TEST(Truth, ReadsFruitAndTheCount) {
    const Truth t = parse_truth(
        R"({"fruit_count": 3, "species": "apple", "fruits": [
              {"id": 4, "centre": [0.5, -1, 2.25], "radius": 0.035, "bunch": 1},
              {"id": 9, "centre": [0, 0, 0], "radius": 1e-3}]})");
    EXPECT_EQ(t.fruit_count, 3u);  // one fruit hidden: counted, not listed
    ASSERT_EQ(t.fruits.size(), 2u);
    EXPECT_EQ(t.fruits[0].id, 4u);
    EXPECT_EQ(t.fruits[0].centre, (std::array<double, 3>{0.5, -1, 2.25}));
    EXPECT_EQ(t.fruits[1].radius, 1e-3);
    EXPECT_EQ(
        parse_truth(R"({"fruits": [{"id": 1, "centre": [1, 2, 3], "radius": 2}]})").fruit_count,
        1u);
}

TEST(Truth, RefusesWhatIsNotAGroundTruthFile) {
    for (const std::string bad : {"", "not json", "[]", R"({"fruit": []})", R"({"fruits": 3})",
                                  R"({"fruits": [{"id": 1, "centre": [1, 2], "radius": 1}]})",
                                  R"({"fruits": [{"id": 0, "centre": [1, 2, 3], "radius": 1}]})",
                                  R"({"fruits": [{"id": 1, "centre": [1, 2, 3], "radius": -1}]})",
                                  R"({"fruits": [{"id": -1, "centre": [1, 2, 3], "radius": 1}]})",
                                  R"({"fruits": [{"id": "a", "centre": [1, 2, 3], "radius": 1}]})",
                                  R"({"fruits": [], "fruit_count": -2})"}) {
        EXPECT_THROW((void)parse_truth(bad), IoError) << bad;
    }
}

}  // namespace
}  // namespace pc::evaluation
