#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/run_tool.h"

namespace pc::test {
namespace {

const std::string kSample = std::string(PC_SAMPLE_CLOUDS_DIR) + "/plum_bunches_explicit.pcd";

int points(const std::string& pcd) {
    return nlohmann::json::parse(run_shell("@pc_info", pcd).out)["points"];
}

TEST(PcRange, KeepsAFieldsRangeThroughAPipeAndEveryFieldPasses) {
    // gt_instance 0 is the leaves and wood: the negated range keeps the fruit, the plain one the
    // rest; together every point, each once.
    const RunResult fruit =
        run_shell("@pc_convert -i " + kSample + " | @pc_range --limits 'gt_instance![0:0]'");
    const RunResult rest = run_shell("@pc_range -i " + kSample + " --limits 'gt_instance[0:0]'");
    ASSERT_EQ(fruit.code, 0) << fruit.err;
    ASSERT_EQ(rest.code, 0) << rest.err;
    const int all = points(run_shell("@pc_convert -i " + kSample).out);
    EXPECT_GT(points(fruit.out), 0);
    EXPECT_EQ(points(fruit.out) + points(rest.out), all);
    EXPECT_NE(run_shell("@pc_info --text", fruit.out).out.find("field_names x y z rgb gt_instance"),
              std::string::npos);
    // Limits on two fields are ANDed: the fruit points at z >= 0 only.
    const RunResult both =
        run_shell("@pc_range -i " + kSample + " --limits 'gt_instance[1:],z[0:]'");
    EXPECT_LT(points(both.out), points(fruit.out));
}

TEST(PcRange, BadLimitsAndMissingFieldsSayWhat) {
    const RunResult none = run_shell("@pc_range -i " + kSample);
    EXPECT_EQ(none.code, 2);
    const RunResult bad = run_shell("@pc_range -i " + kSample + " --limits 'opacity[0.1]'");
    EXPECT_EQ(bad.code, 2);
    EXPECT_NE(bad.err.find("expected FIELD[LO:HI]"), std::string::npos) << bad.err;
    const RunResult missing = run_shell("@pc_range -i " + kSample + " --limits 'opacity[0:]'");
    EXPECT_EQ(missing.code, 1);
    EXPECT_EQ(missing.err, "pc_range: error: " + kSample +
                               ": no field 'opacity' (the cloud has: x y z rgb gt_instance)\n");
    EXPECT_EQ(missing.out, "");
    const RunResult colour = run_shell("@pc_range -i " + kSample + " --limits 'rgb[0:]'");
    EXPECT_EQ(colour.code, 2);
    EXPECT_NE(colour.err.find("pc_colorfilter"), std::string::npos);
}

}  // namespace
}  // namespace pc::test
