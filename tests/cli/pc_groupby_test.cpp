#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/corpus.h"
#include "support/run_tool.h"

namespace pc::test {
namespace {

const std::string kSample = std::string(PC_SAMPLE_CLOUDS_DIR) + "/plum_bunches_explicit.pcd";

int points(const std::string& path) {
    return nlohmann::json::parse(run_shell("@pc_info " + path).out)["points"];
}

TEST(PcGroupby, AFilePerClusterWithAnIndexThatAddsUp) {
    TempDir dir;
    const RunResult count = run_shell("@pc_fruitcount -q -i " + kSample + " --cloud " +
                                      dir.file("l.pcd") + " --cloud-all " + dir.file("all.pcd"));
    ASSERT_EQ(count.code, 0) << count.err;
    const auto report = nlohmann::json::parse(count.out);
    const RunResult g = run_shell("@pc_groupby -i " + dir.file("l.pcd") + " --pattern " + dir.path +
                                  "/fruit/f_#.pcd");
    ASSERT_EQ(g.code, 0) << g.err;
    // One index row and one file per cluster of the count; the files hold every labelled point.
    EXPECT_EQ(line_count(g.out), 1 + static_cast<int>(report["count"]));
    EXPECT_EQ(g.out.rfind("label,points,file,centroid_x", 0), 0u);
    int total = 0;
    std::stringstream lines(g.out);
    std::string line;
    std::getline(lines, line);
    while (std::getline(lines, line)) {
        std::stringstream ss(line);
        std::string label, n, file;
        std::getline(ss, label, ',');
        std::getline(ss, n, ',');
        std::getline(ss, file, ',');
        EXPECT_EQ(points(file), std::stoi(n)) << file;
        total += std::stoi(n);
    }
    EXPECT_EQ(total + static_cast<int>(report["noise_points"]), points(dir.file("l.pcd")));
    // The whole cloud, marked: every input point, the same clusters as --cloud.
    EXPECT_EQ(points(dir.file("all.pcd")), points(kSample));
    // The labelled cloud carries the input's fields and the label, nothing of the index that
    // --cloud-all followed the points with (once a `_` padding field where it had been).
    std::ifstream header(dir.file("l.pcd"));
    std::string fields;
    while (std::getline(header, fields) && fields.rfind("FIELDS", 0) != 0) {
    }
    EXPECT_EQ(fields.find(" _"), std::string::npos) << fields;
    EXPECT_NE(fields.find(" label"), std::string::npos) << fields;
    const RunResult again = run_shell("@pc_groupby -i " + dir.file("all.pcd") + " --pattern " +
                                      dir.path + "/again/f_#.pcd");
    // The same rows but for the folder in the file names.
    std::string expected = g.out;
    for (std::size_t at; (at = expected.find("/fruit/")) != std::string::npos;) {
        expected.replace(at, 7, "/again/");
    }
    EXPECT_EQ(again.out, expected);
}

TEST(PcGroupby, BadPatternsAndFieldsAreRefused) {
    TempDir dir;
    EXPECT_EQ(run_shell("@pc_groupby -i " + kSample + " --pattern " + dir.file("x.pcd")).code, 2);
    EXPECT_EQ(run_shell("@pc_groupby -i " + kSample + " --pattern " + dir.file("x_#.las")).code, 2);
    const RunResult none = run_shell("@pc_groupby -i " + kSample + " --field label");
    EXPECT_EQ(none.code, 1);
    EXPECT_NE(none.err.find(kSample), std::string::npos) << none.err;
    // gt_instance: the true fruit; 0 (leaves, wood) only with --keep-zero.
    const RunResult truth =
        run_shell("@pc_groupby -i " + kSample + " --field gt_instance " +
                  "--keep-zero --min-points 1000 --pattern " + dir.path + "/t/#.pcd");
    ASSERT_EQ(truth.code, 0) << truth.err;
    EXPECT_EQ(line_count(truth.out), 2);  // only the background has 1000 points or more
    EXPECT_TRUE(std::filesystem::exists(dir.path + "/t/0.pcd"));
}

}  // namespace
}  // namespace pc::test
