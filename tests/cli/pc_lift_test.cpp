// pc_lift on the shipped view sample (sample_clouds/make_views.py: three spheres over the ground,
// eight cameras, masks ray-cast against the analytic spheres): every ground point stays
// non-fruit, fruit points seen by the cameras are fruit but for a few rim points seen once; the
// COLMAP model of the same cameras gives the same bytes; bad camera and mask files fail cleanly.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <pc/io/blob.h>
#include <pc/io/read.h>

#include "support/run_tool.h"

namespace pc::test {
namespace {

const std::string kViews = std::string(PC_SAMPLE_CLOUDS_DIR) + "/views";

std::uint32_t field(const io::Blob& b, const char* name, std::size_t i) {
    const pcl::PCLPointField* f = io::find_field(b, name);
    EXPECT_NE(f, nullptr) << name;
    std::uint32_t v = 0;
    if (f != nullptr) {
        std::memcpy(&v, b.cloud.data.data() + i * b.cloud.point_step + f->offset, 4);
    }
    return v;
}

TEST(PcLift, MasksLiftedOntoTheSampleMarkTheFruitAndNotTheGround) {
    TempDir dir;
    const RunResult r = run_shell("cd " + kViews + " && @pc_lift -i cloud.pcd --cameras " +
                                  "transforms.json -o " + dir.file("a.pcd"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    const io::Blob b = io::read_cloud(dir.file("a.pcd")).blob;
    std::size_t fruit_seen = 0, fruit_missed = 0, ground_seen = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
        const std::uint32_t views = field(b, "views", i), votes = field(b, "votes", i);
        const bool fruit = field(b, "fruit", i) != 0, truth = field(b, "gt", i) != 0;
        ASSERT_LE(votes, views);
        EXPECT_EQ(fruit, views > 0 && 2 * votes >= views);  // --min-ratio 0.5
        if (views == 0) {
            continue;
        }
        if (truth) {
            ++fruit_seen;
            fruit_missed += !fruit;
        } else {
            ++ground_seen;
            EXPECT_FALSE(fruit) << i;
        }
    }
    EXPECT_GT(fruit_seen, 2500u);
    EXPECT_GT(ground_seen, 3000u);
    EXPECT_LT(fruit_missed, fruit_seen / 100);  // rim points seen by one view: 19 of 2600 here

    // The same cameras as a COLMAP model (world-to-camera quaternions, 12 decimals), masks found
    // by image name: the same bytes.
    const RunResult c = run_shell("@pc_lift -i " + kViews + "/cloud.pcd --cameras " + kViews +
                                  "/colmap --masks " + kViews + "/masks -o " + dir.file("c.pcd"));
    ASSERT_EQ(c.code, 0) << c.err;
    EXPECT_TRUE(slurp(dir.file("a.pcd")) == slurp(dir.file("c.pcd")));
}

TEST(PcLift, ASynthTreeRenderedIntoMasksLiftsBackToItsTruth) {
    // pc_synth's tree (fruit, leaves, ground, floaters) drawn by pc_render as gt_instance masks
    // (16-bit ids, 0 where no fruit) through the sample's eight cameras, then lifted: every point
    // a camera sees is fruit exactly when it is one (8648 points seen of 11342 here).
    TempDir d;
    std::filesystem::create_directory(d.file("masks"));
    ASSERT_EQ(run_shell("@pc_synth --species plum --fruit-count 40 --canopy 0.45,0.45,0.4 --mode "
                        "surface --voxel 0.004 -o " +
                        d.file("tree.pcd"))
                  .code,
              0);
    for (int k = 0; k < 8; ++k) {
        const RunResult r =
            run_shell("@pc_render -i " + d.file("tree.pcd") + " --cameras " + kViews +
                      "/transforms.json --frame " + std::to_string(k) + " --mask gt_instance -o " +
                      d.file("masks/frame_0" + std::to_string(k) + ".png"));
        ASSERT_EQ(r.code, 0) << r.err;
    }
    const RunResult r =
        run_shell("@pc_lift -i " + d.file("tree.pcd") + " --cameras " + kViews +
                  "/transforms.json --masks " + d.file("masks") + " -o " + d.file("lifted.pcd"));
    ASSERT_EQ(r.code, 0) << r.err;
    const io::Blob b = io::read_cloud(d.file("lifted.pcd")).blob;
    std::size_t seen = 0, fruit = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
        if (field(b, "views", i) == 0) {
            continue;
        }
        ++seen;
        fruit += field(b, "gt_instance", i) != 0;
        EXPECT_EQ(field(b, "fruit", i) != 0, field(b, "gt_instance", i) != 0) << i;
    }
    EXPECT_GT(seen, b.size() / 2);
    EXPECT_GT(fruit, 1000u);
}

TEST(PcLift, InstanceMasksCountBunchesTheGeometricSplitCannot) {
    // Grape-like bunches of 6-12 berries 9 mm in radius, interpenetrating up to 10 %, sampled at
    // random in their volume about 2 points to a radius: pc_fruitcount's geometric split reads
    // each bunch as one fruit (14 of 80 here). Their gt_instance masks through the sample's eight
    // cameras (320 x 240, a pixel about 7 mm at the fruit) lifted with --instances give the
    // berries back.
    TempDir d;
    std::filesystem::create_directory(d.file("masks"));
    ASSERT_EQ(run_shell("@pc_synth --species plum --fruit-count 80 --fruit-radius 0.009 "
                        "--bunch-min 6 --bunch-max 12 --overlap 0.1 --canopy 0.45,0.45,0.4 "
                        "--mode volume --voxel 0.0045 -o " +
                        d.file("tree.pcd"))
                  .code,
              0);
    for (int k = 0; k < 8; ++k) {
        const std::string name = "frame_0" + std::to_string(k) + ".png";
        ASSERT_EQ(run_shell("@pc_render -i " + d.file("tree.pcd") + " --cameras " + kViews +
                            "/transforms.json --frame " + std::to_string(k) +
                            " --mask gt_instance -o " + d.file("masks/" + name))
                      .code,
                  0);
    }
    const RunResult r = run_shell("@pc_lift -i " + d.file("tree.pcd") + " --cameras " + kViews +
                                  "/transforms.json --masks " + d.file("masks") +
                                  " --instances -v -o " + d.file("lifted.pcd"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find(" instances"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
    const RunResult e = run_shell("@pc_eval -i " + d.file("lifted.pcd"));
    ASSERT_EQ(e.code, 0) << e.err;
    const auto score = nlohmann::json::parse(e.out);
    const double f1 = score["f1"], count = score["count"];
    EXPECT_GE(f1, 0.9) << e.out;  // 0.97: 81 labels for 80 berries
    EXPECT_NEAR(count, 80, 8) << e.out;
    const RunResult g = run_shell("@pc_fruitcount -q -i " + d.file("tree.pcd") + " --cloud " +
                                  d.file("geometric.pcd") + " > /dev/null && @pc_eval -i " +
                                  d.file("geometric.pcd"));
    ASSERT_EQ(g.code, 0) << g.err;
    EXPECT_LT(nlohmann::json::parse(g.out)["f1"].get<double>(), f1);

    // Binary masks hold one instance a view: every fruit point joins one label, and a warning.
    const RunResult b = run_shell("@pc_lift -i " + kViews + "/cloud.pcd --cameras " + kViews +
                                  "/transforms.json --instances -o " + d.file("binary.pcd"));
    EXPECT_EQ(b.code, 0) << b.err;
    EXPECT_NE(b.err.find("warning: every fruit point joined into one instance"), std::string::npos)
        << b.err;
    // JPEG compression changes ids: refused for instances.
    std::filesystem::create_directory(d.file("jpeg"));
    ASSERT_EQ(run_shell("cd " + d.file("jpeg") + " && for k in 0 1 2 3 4 5 6 7; do cp " +
                        d.file("masks") + "/frame_0$k.png frame_0$k.jpg; done")
                  .code,
              0);
    const RunResult j = run_shell("@pc_lift -i " + d.file("tree.pcd") + " --cameras " + kViews +
                                  "/transforms.json --masks " + d.file("jpeg") +
                                  " --instances -o " + d.file("j.pcd"));
    EXPECT_EQ(j.code, 1);
    EXPECT_NE(j.err.find("instance masks must be PNG"), std::string::npos) << j.err;
    EXPECT_FALSE(std::ifstream(d.file("j.pcd")).good());
}

TEST(PcLift, InstanceMasksThatDisagreeAcrossViewsAreAWarning) {
    // The sample's three fruit drawn as instance masks from their ids (gt = 1..3): no warning.
    // Five of the eight views replaced by the sample's binary masks (one instance holding every
    // fruit): a third of the fruit points are seen only by such views, a warning.
    TempDir d;
    for (const char* sub : {"ids", "mixed"}) {
        std::filesystem::create_directory(d.file(sub));
    }
    for (int k = 0; k < 8; ++k) {
        const std::string name = "frame_0" + std::to_string(k) + ".png";
        ASSERT_EQ(run_shell("@pc_render -i " + kViews + "/cloud.pcd --cameras " + kViews +
                            "/transforms.json --frame " + std::to_string(k) + " --mask gt -o " +
                            d.file("ids/" + name))
                      .code,
                  0);
        std::filesystem::copy_file(k < 3 ? d.file("ids/" + name) : kViews + "/masks/" + name,
                                   d.file("mixed/" + name));
    }
    const std::string lift =
        "@pc_lift -i " + kViews + "/cloud.pcd --cameras " + kViews + "/transforms.json --instances";
    const RunResult good = run_shell(lift + " --masks " + d.file("ids") + " | @pc_count --plain");
    ASSERT_EQ(good.code, 0) << good.err;
    EXPECT_EQ(good.out, "3\n");
    EXPECT_TRUE(good.err.empty()) << good.err;
    const RunResult mixed = run_shell(lift + " --masks " + d.file("mixed") + " > /dev/null");
    ASSERT_EQ(mixed.code, 0) << mixed.err;
    EXPECT_NE(mixed.err.find("fruit points have a doubtful label"), std::string::npos) << mixed.err;
}

TEST(PcLift, BadCameraAndMaskFilesFailWithOneLineAndNoOutput) {
    TempDir dir;
    const std::string out = dir.file("out.pcd");
    const std::string in = " -i " + kViews + "/cloud.pcd -o " + out;
    std::ofstream(dir.file("bad.json")) << R"({"frames": [{"transform_matrix": [[1,0,0]]}]})";
    std::ofstream(dir.file("tiny.png")) << "not a png";
    const struct {
        std::string args;
        int code;
        std::string says;
    } cases[] = {
        {"", 2, "--cameras is required"},
        {" --cameras " + dir.file("missing.json"), 1, "missing.json: cannot open"},
        {" --cameras " + dir.file("bad.json"), 1, "bad.json: frame 0"},
        {" --cameras " + kViews + "/colmap", 1, "give --masks DIR"},
        {" --cameras " + kViews + "/transforms.json --masks " + dir.path, 1,
         "no mask frame_00.png or .jpg"},
        {" --cameras " + kViews + "/transforms.json --min-ratio 2", 2, "min_ratio"},
        {" --cameras " + kViews + "/transforms.json --colmap-frame", 2, "has no applied_transform"},
    };
    for (const auto& k : cases) {
        const RunResult r = run_shell("@pc_lift" + in + k.args);
        EXPECT_EQ(r.code, k.code) << k.args << ": " << r.err;
        EXPECT_NE(r.err.find(k.says), std::string::npos) << k.args << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(std::ifstream(out).good()) << k.args;
    }
    // masks of another size than the camera, and a mask that is not an image
    const RunResult small = run_shell(
        "mkdir -p " + dir.file("m") + " && cp " + kViews + "/masks/*.png " + dir.file("m") +
        " && cp " + dir.file("tiny.png") + " " + dir.file("m/frame_03.png") + " && @pc_lift" + in +
        " --cameras " + kViews + "/transforms.json --masks " + dir.file("m"));
    EXPECT_EQ(small.code, 1);
    EXPECT_NE(small.err.find("frame_03.png: not an image"), std::string::npos) << small.err;
    EXPECT_FALSE(std::ifstream(out).good());
}

TEST(PcLift, CamerasThatSeeNoPointAreAWarning) {
    // The sample's cloud moved 100 m away: no camera sees it.
    const RunResult r = run_shell("@pc_transform -i " + kViews +
                                  "/cloud.pcd --translate 100,0,0 | @pc_lift --cameras " + kViews +
                                  "/transforms.json > /dev/null");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("warning: no camera sees any point"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace pc::test
