// pc_render through the built tool: the view sample's cloud lifted and drawn as a fruit mask from
// each of its cameras agrees with the ray-cast ground-truth masks (pc_maskeval); colour images of
// the requested size; bad requests fail with one line.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "support/run_tool.h"

namespace pc::test {
namespace {

const std::string kViews = std::string(PC_SAMPLE_CLOUDS_DIR) + "/views";

TEST(PcRender, LiftedFruitDrawnFromEachCameraMatchesTheGroundTruthMasks) {
    TempDir d;
    std::filesystem::create_directory(d.file("pred"));
    ASSERT_EQ(run_shell("@pc_lift -i " + kViews + "/cloud.pcd --cameras " + kViews +
                        "/transforms.json -o " + d.file("lifted.pcd"))
                  .code,
              0);
    for (int k = 0; k < 8; ++k) {
        const std::string name = "frame_0" + std::to_string(k) + ".png";
        const RunResult r = run_shell("@pc_render -i " + d.file("lifted.pcd") + " --cameras " +
                                      kViews + "/transforms.json --frame " + std::to_string(k) +
                                      " --mask fruit -o " + d.file("pred/" + name));
        ASSERT_EQ(r.code, 0) << r.err;
    }
    const RunResult e = run_shell("@pc_maskeval " + d.file("pred") + " " + kViews + "/masks");
    ASSERT_EQ(e.code, 0) << e.err;
    const auto j = nlohmann::json::parse(e.out);
    EXPECT_EQ(j["views"], 8);
    // splats reach about a pixel beyond the silhouettes: recall complete, IoU about 0.8
    EXPECT_GT(j["method"]["summary"]["recall"]["min"].get<double>(), 0.95);
    EXPECT_GT(j["method"]["summary"]["iou"]["min"].get<double>(), 0.7);
}

TEST(PcRender, StandardViewsMakeASheetOfTheRequestedSize) {
    TempDir d;
    const RunResult r = run_shell("@pc_render -i " + kViews + "/cloud.pcd --view top,iso --size " +
                                  "120x90 --color gt -o " + d.file("s.png"));
    ASSERT_EQ(r.code, 0) << r.err;
    const cv::Mat m = cv::imread(d.file("s.png"), cv::IMREAD_UNCHANGED);
    EXPECT_EQ(m.rows, 90);
    EXPECT_EQ(m.cols, 2 * 120 + 70);  // two views and the colour bar
    EXPECT_EQ(m.channels(), 3);
}

TEST(PcRender, BadRequestsFailWithOneLine) {
    const std::string in = "@pc_render -i " + kViews + "/cloud.pcd ";
    const struct {
        std::string args;
        int code;
        std::string says;
    } cases[] = {
        {"--view nadir", 2, "--view must be top, front, side or iso"},
        {"--size 10x10", 2, "--size must be WxH"},
        {"--frame 3", 2, "--frame needs --cameras"},
        {"--cameras " + kViews + "/transforms.json --frame 8", 2, "--frame must be 0..7"},
        {"--mask fruit", 1, "fruit"},  // the sample has no fruit field before pc_lift
        {"--color intensity", 1, "no numeric field 'intensity'"},
        {"--view top,iso --mask gt", 2, "--mask draws one view"},
    };
    for (const auto& c : cases) {
        const RunResult r = run_shell(in + c.args + " > /dev/null");
        EXPECT_EQ(r.code, c.code) << c.args << ": " << r.err;
        EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
}

TEST(PcRender, AnImageIsNeverWrittenToATerminal) {
    // util-linux's script(1) gives the tool a terminal for its stdout (and stderr)
    if (run_shell("command -v script > /dev/null").code != 0) {
        GTEST_SKIP() << "script(1) is not installed";
    }
    const RunResult r = run_shell("script -qec '@pc_render -i " + kViews + "/cloud.pcd' /dev/null");
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_NE(r.out.find("refusing to write an image to a terminal"), std::string::npos) << r.out;
    EXPECT_LT(r.out.size(), 300u);  // one line, no PNG bytes
}

}  // namespace
}  // namespace pc::test
