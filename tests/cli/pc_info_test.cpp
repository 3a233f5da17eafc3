#include <algorithm>
#include <cmath>
#include <sstream>

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
    EXPECT_NE(r.out.find("\npoints 0\n"), std::string::npos);
}

TEST(PcInfo, CsvHasOneRowPerInputWithEveryFieldElement) {
    TempDir dir;
    spit(dir.file("a.pcd"),
         pcd_header("x y z h", "4 4 4 4", "F F F F", "1 1 1 3", "1", "1", "ascii") +
             "1 2 3 4 5 6\n");
    spit(dir.file("b.xyz"), "0 0 0\n2 2 2\n");
    const RunResult r = run_shell("@pc_info --csv " + dir.file("a.pcd") + " " + dir.file("b.xyz"));
    ASSERT_EQ(r.code, 0) << r.err;
    ASSERT_EQ(line_count(r.out), 3) << r.out;
    const std::string header = r.out.substr(0, r.out.find('\n'));
    EXPECT_EQ(header.rfind("input,tool,version,", 0), 0u) << header;
    EXPECT_NE(header.find(",fields.h.max.2,"), std::string::npos) << header;
    // h's third element is 6 in a; b has no h: an empty cell, the columns still line up.
    const auto cells = [](const std::string& line) {
        std::vector<std::string> out;
        std::stringstream ss(line);
        for (std::string c; std::getline(ss, c, ',');) {
            out.push_back(c);
        }
        return out;
    };
    const auto names = cells(header);
    const auto column = std::find(names.begin(), names.end(), "fields.h.max.2") - names.begin();
    std::stringstream lines(r.out);
    std::string line;
    std::getline(lines, line);
    std::getline(lines, line);
    EXPECT_EQ(cells(line)[column], "6") << line;
    std::getline(lines, line);
    EXPECT_EQ(line.rfind(dir.file("b.xyz") + ",pc_info,", 0), 0u) << line;
}

TEST(PcInfo, StatsGiveColourSpacingAndPercentiles) {
    // Four points 1 apart on a line, one duplicated; pure red, pure green, grey, grey.
    const std::string cloud =
        pcd_header("x y z r g b", "4 4 4 1 1 1", "F F F U U U", "1 1 1 1 1 1", "5", "5", "ascii") +
        "0 0 0 255 0 0\n1 0 0 0 255 0\n2 0 0 128 128 128\n3 0 0 128 128 128\n3 0 0 10 10 10\n";
    const RunResult r = run_shell("@pc_info --stats", cloud);
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["spacing"]["median"], 1.0);
    EXPECT_EQ(j["spacing"]["duplicates"], 1);
    EXPECT_EQ(j["colour"]["stats"]["grey"], 3);
    EXPECT_EQ(j["colour"]["stats"]["hue_histogram"]["red"], 1);
    EXPECT_EQ(j["colour"]["stats"]["hue_histogram"]["green"], 1);
    // x is 0 1 2 3 3: numpy.percentile(x, [10, 50, 90]) = 0.4, 2, 3; std = sqrt(1.36).
    EXPECT_NEAR(j["fields"][0]["p10"].get<double>(), 0.4, 1e-12);
    EXPECT_EQ(j["fields"][0]["median"], 2.0);
    EXPECT_EQ(j["fields"][0]["p90"], 3.0);
    EXPECT_NEAR(j["fields"][0]["stddev"].get<double>(), std::sqrt(1.36), 1e-12);
    // Without --stats, no percentiles (they cost a pass and a copy a field).
    const auto plain = nlohmann::json::parse(run_shell("@pc_info", cloud).out);
    EXPECT_FALSE(plain["fields"][0].contains("median"));
    EXPECT_FALSE(plain.contains("spacing"));
}

TEST(PcInfo, ManyInputsOneFailingGetAnErrorRowAndExit1) {
    TempDir dir;
    spit(dir.file("a.xyz"), "0 0 0\n");
    const RunResult r = run_shell("@pc_info --jsonl " + dir.file("a.xyz") + " " +
                                  dir.file("missing.pcd") + " " + dir.file("a.xyz"));
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(line_count(r.out), 3) << r.out;
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("missing.pcd: cannot open"), std::string::npos) << r.err;
    std::stringstream lines(r.out);
    std::string line;
    std::vector<nlohmann::json> rows;
    while (std::getline(lines, line)) {
        rows.push_back(nlohmann::json::parse(line));
    }
    EXPECT_EQ(rows[0]["points"], 1);
    EXPECT_TRUE(rows[1].contains("error"));
    EXPECT_FALSE(rows[1].contains("points"));
    EXPECT_EQ(rows[2]["input"], dir.file("a.xyz"));
    EXPECT_EQ(rows[2]["tool"], "pc_info");
    EXPECT_TRUE(rows[2]["parameters"].contains("stats"));
}

TEST(PcInfo, CsvAndTextTogetherIsAUsageError) {
    EXPECT_EQ(run_shell("@pc_info --csv --text", xyz_header("0", "binary")).code, 2);
}

}  // namespace
}  // namespace pc::test
