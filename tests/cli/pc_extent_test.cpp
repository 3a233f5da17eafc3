#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/corpus.h"
#include "support/run_tool.h"

namespace pc::test {
namespace {

/// The 8 corners of the unit cube plus its centre, ascii PCD with labels (cube 1, centre noise 0).
std::string cube_cloud() {
    std::string s = pcd_header("x y z label", "4 4 4 4", "F F F U", "1 1 1 1", "9", "9", "ascii");
    for (int i = 0; i < 8; ++i) {
        s += std::to_string(i & 1) + " " + std::to_string((i >> 1) & 1) + " " +
             std::to_string((i >> 2) & 1) + " 1\n";
    }
    return s + "0.5 0.5 0.5 0\n";
}

TEST(PcExtent, CubeCornersGiveTheUnitCube) {
    const RunResult r = run_shell("@pc_extent --per-label", cube_cloud());
    ASSERT_EQ(r.code, 0) << r.err;
    const auto c = nlohmann::json::parse(r.out)["clouds"][0];
    EXPECT_EQ(c["points"], 9);
    EXPECT_DOUBLE_EQ(c["hull"]["volume"].get<double>(), 1.0);
    EXPECT_DOUBLE_EQ(c["hull"]["area"].get<double>(), 6.0);
    EXPECT_DOUBLE_EQ(c["aabb"]["volume"].get<double>(), 1.0);
    EXPECT_DOUBLE_EQ(c["clusters"][0]["mean_radius"].get<double>(), std::sqrt(0.75));
    EXPECT_EQ(c["clusters"].size(), 1u);
    EXPECT_EQ(c["cluster_summary"]["count"], 1);
}

TEST(PcExtent, DegenerateInputsReportDegenerateAndExitZero) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"empty", xyz_header("0", "ascii")},
        {"one", xyz_header("1", "ascii") + "1 2 3\n"},
        {"three", xyz_header("3", "ascii") + "0 0 0\n1 0 0\n0 1 0\n"},
        {"plane", xyz_header("5", "ascii") + "0 0 0\n1 0 0\n0 1 0\n1 1 0\n0.5 0.5 0\n"}};
    for (const auto& [name, bytes] : cases) {
        const RunResult r = run_shell("@pc_extent", bytes);
        ASSERT_EQ(r.code, 0) << name << ": " << r.err;
        const auto c = nlohmann::json::parse(r.out)["clouds"][0];
        EXPECT_EQ(c["degenerate"], true) << name;
        if (c.contains("hull")) {
            EXPECT_EQ(c["hull"]["volume"], 0.0) << name;
        }
    }
}

TEST(PcExtent, SeveralInputsSideBySideWithNames) {
    TempDir dir;
    spit(dir.file("a.pcd"), cube_cloud());
    spit(dir.file("b.pcd"), xyz_header("1", "ascii") + "1 2 3\n");
    const RunResult r = run_shell("@pc_extent " + dir.file("a.pcd") + " " + dir.file("b.pcd") +
                                  " --names A,B --markdown");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("| A | 9 | 1 |"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("| B | 1 | 0 |"), std::string::npos) << r.out;
    EXPECT_EQ(run_shell("@pc_extent " + dir.file("a.pcd") + " --names A,B").code, 2);
    const RunResult csv =
        run_shell("@pc_extent --csv " + dir.file("a.pcd") + " " + dir.file("b.pcd"));
    EXPECT_EQ(line_count(csv.out), 3);
}

TEST(PcExtent, PerLabelWithoutLabelNamesTheFile) {
    TempDir dir;
    spit(dir.file("b.pcd"), xyz_header("1", "ascii") + "1 2 3\n");
    const RunResult r = run_shell("@pc_extent --per-label " + dir.file("b.pcd"));
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "pc_extent: error: " + dir.file("b.pcd") +
                         ": cloud has no 'label' field (label its clusters first: pc_dbscan, then "
                         "pc_recursive_split; or pc_fruitcount --cloud)\n");
}

}  // namespace
}  // namespace pc::test
