#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/corpus.h"
#include "support/run_tool.h"

namespace pc::test {
namespace {

/// An Open3D-style PLY (double x y z, uchar colours) with known coordinates.
std::string open3d_ply() {
    std::string s = ply_header("binary_little_endian", "3",
                               "property double x\nproperty double y\nproperty double z\n"
                               "property uchar red\nproperty uchar green\nproperty uchar blue\n");
    const double xyz[3][3] = {{0.25, -1.0, 2.0}, {-0.5, 3.0, 0.125}, {1.0, 0.0, -7.5}};
    for (const auto& p : xyz) {
        s.append(reinterpret_cast<const char*>(p), 24);
        s += "\x10\x20\x30";
    }
    return s;
}

TEST(PcInfo, Open3dDoublePlyThroughPcConvertHasTheRightBounds) {
    const RunResult r = run_shell("@pc_convert | @pc_info", open3d_ply());
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["points"], 3);
    EXPECT_EQ(j["format"], "pcd binary");
    EXPECT_EQ(j["bbox"]["min"], nlohmann::json({-0.5, -1.0, -7.5}));
    EXPECT_EQ(j["bbox"]["max"], nlohmann::json({1.0, 3.0, 2.0}));
    EXPECT_EQ(j["colour"]["present"], true);
    EXPECT_EQ(j["fields"][0]["type"], "F");
    EXPECT_EQ(j["fields"][0]["size"], 8);
    EXPECT_DOUBLE_EQ(j["fields"][2]["mean"].get<double>(), (2.0 + 0.125 - 7.5) / 3);
}

TEST(PcInfo, CountsNonFinitePointsAndKeepsThemOutOfTheBounds) {
    const RunResult r =
        run_shell("@pc_info", xyz_header("3", "ascii") + "1 1 1\nnan 0 0\n2 inf 2\n");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["non_finite_points"], 2);
    EXPECT_EQ(j["bbox"]["min"], nlohmann::json({1.0, 1.0, 1.0}));
    EXPECT_EQ(j["is_dense"], false);
}

TEST(PcInfo, EmptyCloudReportsZeroPoints) {
    const RunResult r = run_shell("@pc_info --text", xyz_header("0", "binary"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("points 0\n"), std::string::npos);
}

TEST(PcInfo, CsvHasOneRowPerFieldElement) {
    const RunResult r = run_shell("@pc_info --csv", pcd_header("x y z h", "4 4 4 4", "F F F F",
                                                               "1 1 1 3", "1", "1", "ascii") +
                                                        "1 2 3 4 5 6\n");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(line_count(r.out), 1 + 3 + 3);
    EXPECT_NE(r.out.find("h,F,4,3,2,6,6,6,1\n"), std::string::npos) << r.out;
}

TEST(PcInfo, CsvAndTextTogetherIsAUsageError) {
    EXPECT_EQ(run_shell("@pc_info --csv --text", xyz_header("0", "binary")).code, 2);
}

}  // namespace
}  // namespace pc::test
