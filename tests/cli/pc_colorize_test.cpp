#include <map>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/corpus.h"
#include "support/run_tool.h"

namespace pc::test {
namespace {

const std::string kSample = std::string(PC_SAMPLE_CLOUDS_DIR) + "/plum_bunches_explicit.pcd";

TEST(PcColorize, LabelsBecomeRgbThatViewersShowAndOtherFieldsPass) {
    TempDir dir;
    // Label the sample, colour it by label, write PLY as MeshLab and Open3D read it.
    const RunResult r =
        run_shell("@pc_fruitcount -q --plain -i " + kSample + " --cloud " + dir.file("l.pcd") +
                  " && @pc_colorize -i " + dir.file("l.pcd") + " -o " + dir.file("c.ply"));
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string ply = slurp(dir.file("c.ply"));
    EXPECT_NE(ply.find("property uchar red\nproperty uchar green\nproperty uchar blue\n"),
              std::string::npos);
    EXPECT_NE(ply.find("property uint label\n"), std::string::npos);
    EXPECT_NE(ply.find("property uint gt_instance\n"), std::string::npos);
    // Points of one label share one colour, and two labels differ (a sample of them).
    const RunResult text = run_shell("@pc_convert --to xyz -i " + dir.file("c.ply"));
    std::map<std::string, std::string> colour_of;
    std::set<std::string> colours;
    std::stringstream lines(text.out);
    std::string line;
    std::getline(lines, line);
    EXPECT_EQ(line, "//X Y Z R G B gt_instance label");
    while (std::getline(lines, line)) {
        std::stringstream ss(line);
        std::string x, y, z, r8, g8, b8, gt, label;
        ss >> x >> y >> z >> r8 >> g8 >> b8 >> gt >> label;
        const std::string c = r8 + " " + g8 + " " + b8;
        const auto [it, fresh] = colour_of.emplace(label, c);
        EXPECT_EQ(it->second, c) << "label " << label;
        colours.insert(c);
    }
    EXPECT_GT(colour_of.size(), 40u);
    EXPECT_EQ(colours.size(), colour_of.size());
}

TEST(PcColorize, AFieldThroughTheMapAndCloudCompareScalars) {
    TempDir dir;
    const RunResult r = run_shell("@pc_colorize --by z --range 0:1 -v -i " + kSample +
                                  " --ply-scalars -o " + dir.file("z.ply"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("viridis from 0 to 1"), std::string::npos) << r.err;
    const std::string ply = slurp(dir.file("z.ply"));
    EXPECT_NE(ply.find("property uint scalar_gt_instance\n"), std::string::npos);  // CloudCompare
    // Read back, the prefix goes: the field is gt_instance again.
    EXPECT_NE(run_shell("@pc_info --text " + dir.file("z.ply"))
                  .out.find("field_names x y z rgb gt_instance"),
              std::string::npos);
    const RunResult missing = run_shell("@pc_colorize --by opacity -i " + kSample);
    EXPECT_EQ(missing.code, 1);
    EXPECT_EQ(
        missing.err.rfind("pc_colorize: error: " + kSample + ": no numeric field 'opacity'", 0), 0u)
        << missing.err;
    EXPECT_EQ(run_shell("@pc_colorize --range 2 -i " + kSample).code, 2);
}

}  // namespace
}  // namespace pc::test
