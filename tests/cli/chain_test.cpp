// The counting chain through real pipes, and pc_fruitcount against it.
#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <pc/io/pcd.h>
#include <pc/io/points.h>
#include <pc/io/read.h>
#include <pc/io/sink.h>

#include "support/corpus.h"
#include "support/run_tool.h"

namespace pc::test {
namespace {

const std::string kSample = std::string(PC_SAMPLE_CLOUDS_DIR) + "/fruit_small.ply";

int sample_fruit_count() {
    return nlohmann::json::parse(slurp(std::string(PC_SAMPLE_CLOUDS_DIR) + "/fruit_small.json"))
        .at("fruit_count");
}

std::string piped_chain(const std::string& preset) {
    const std::string p = " --preset " + preset;
    std::string cmd = "@pc_convert -i " + kSample + " | @pc_colorfilter" + p;
    if (preset == "invnerfseg") {
        cmd += " | @pc_crop" + p + " | @pc_voxel" + p;
    }
    if (preset != "dense") {  // the paper's presets drop a tenth by kNN distances; dense does not
        cmd += " | @pc_knn_outlier" + p;
    }
    return cmd + " | @pc_dbscan" + p + " | @pc_recursive_split" + p;
}

TEST(Chain, PipedChainCountsTheSampleFruit) {
    const RunResult r = run_shell(piped_chain("paper-dense") + " | @pc_count --plain");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    EXPECT_EQ(r.out, std::to_string(sample_fruit_count()) + "\n");
}

TEST(Chain, FruitcountGivesTheSameLabelsAsThePipedChain) {
    for (const std::string preset : {"dense", "paper-dense", "paper-sparse", "invnerfseg"}) {
        TempDir dir;
        const RunResult piped = run_shell(piped_chain(preset));
        ASSERT_EQ(piped.code, 0) << preset << ": " << piped.err;
        const RunResult one = run_shell("@pc_fruitcount -i " + kSample + " --preset " + preset +
                                        " --plain --cloud " + dir.file("l.pcd"));
        ASSERT_EQ(one.code, 0) << preset << ": " << one.err;
        const io::Blob a = io::parse_cloud(piped.out).blob;
        const io::Blob b = io::read_cloud(dir.file("l.pcd")).blob;
        EXPECT_EQ(a.cloud.data, b.cloud.data) << preset;  // every field, every point, every bit
        const RunResult count =
            run_shell("@pc_count --plain --preset " + preset + " -i " + dir.file("l.pcd"));
        EXPECT_EQ(count.out, one.out) << preset;
    }
}

TEST(Chain, FruitcountReportsErrorAndRecoveryAgainstGroundTruth) {
    const RunResult r = run_shell("@pc_fruitcount -i " + kSample + " --preset paper-dense --gt 12");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["count"], 12);
    EXPECT_EQ(j["count_error"], 0.0);
    EXPECT_EQ(j["recovery"], 1.0);
    ASSERT_EQ(j["clusters"].size(), 12u);
    // Every cluster centroid lies within one fruit radius of a true centre.
    const auto truth =
        nlohmann::json::parse(slurp(std::string(PC_SAMPLE_CLOUDS_DIR) + "/fruit_small.json"));
    const double radius = truth["radius"];
    for (const auto& c : j["clusters"]) {
        double best = 1e9;
        for (const auto& t : truth["centres"]) {
            double d2 = 0;
            for (int a = 0; a < 3; ++a) {
                const double d = c["centroid"][a].get<double>() - t[a].get<double>();
                d2 += d * d;
            }
            best = std::min(best, std::sqrt(d2));
        }
        EXPECT_LT(best, radius) << c.dump();
    }
}

TEST(Chain, FieldsPassThroughTheWholeChain) {
    const RunResult r = run_shell(piped_chain("paper-dense") + " | @pc_info --text");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("field_names x y z rgb label\n"), std::string::npos) << r.out;
}

TEST(PcDbscan, EpsAutoAndKneeReportTheChosenValueWithVerbose) {
    // auto: 4 x the point spacing; knee: the k-distance knee.
    for (const auto& [eps, said] : {std::pair{"auto", "pc_dbscan: dbscan: eps = 4 x spacing "},
                                    std::pair{"knee", "pc_dbscan: dbscan: eps knee = "}}) {
        const RunResult r = run_shell("@pc_convert -i " + kSample +
                                      " | @pc_colorfilter --min-mean 0.5 | @pc_dbscan --eps " +
                                      std::string(eps) + " --min-points 4 -v | @pc_count --plain");
        ASSERT_EQ(r.code, 0) << r.err;
        EXPECT_NE(r.err.find(said), std::string::npos) << r.err;
    }
}

TEST(PcDbscan, BadEpsIsAUsageError) {
    const RunResult r = run_shell("@pc_dbscan --eps -0.5 -i " + kSample);
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("dbscan: eps must be > 0, got -0.5"), std::string::npos) << r.err;
    EXPECT_EQ(run_shell("@pc_dbscan --eps fast -i " + kSample).code, 2);
}

TEST(PcKnnOutlier, APresetWithoutTheStepIsAUsageError) {
    // dense (pc_fruitcount's default) has no kNN step: its piped chain leaves the tool out.
    const RunResult r = run_shell("@pc_knn_outlier --preset dense -i " + kSample);
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("--preset: dense has no kNN outlier step"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty());
}

TEST(PcColorfilter, CloudWithoutColourIsAClearError) {
    const RunResult r =
        run_shell("@pc_colorfilter --min-mean 0.5", xyz_header("1", "ascii") + "1 2 3\n");
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err,
              "pc_colorfilter: error: cloud has no colour (looked for rgb, rgba, red green "
              "blue, r g b)\n");
}

TEST(PcColorfilter, InvertSplitsTheCloudIntoComplements) {
    const RunResult a =
        run_shell("@pc_colorfilter --min-mean 0.5 -i " + kSample + " | @pc_info --text");
    const RunResult b =
        run_shell("@pc_colorfilter --min-mean 0.5 --invert -i " + kSample + " | @pc_info --text");
    const auto points = [](const std::string& s) {
        return std::stoul(s.substr(s.find("points ") + 7));
    };
    EXPECT_EQ(points(a.out) + points(b.out), 5640u);
}

TEST(PcKnnOutlier, MarkAddsAFieldAndDropsNothing) {
    const RunResult r = run_shell("@pc_knn_outlier --mark outlier -i " + kSample);
    ASSERT_EQ(r.code, 0) << r.err;
    const io::Blob b = io::parse_cloud(r.out).blob;
    ASSERT_EQ(b.size(), 5640u);
    const auto flags = io::labels(b, "outlier");
    const auto marked = std::count(flags.begin(), flags.end(), 1u);
    EXPECT_EQ(marked, 564);  // exactly the top 10 % of 5640 distinct scores
}

TEST(PcCrop, PaperPresetHasNoCropAndInvnerfsegHasOne) {
    EXPECT_EQ(run_shell("@pc_crop --preset paper-dense -i " + kSample).code, 2);
    // The sample spans +-0.6 in x and y; the script's box keeps +-0.5, so some points go.
    const RunResult in =
        run_shell("@pc_crop --preset invnerfseg -i " + kSample + " | @pc_info --text");
    const RunResult out =
        run_shell("@pc_crop --preset invnerfseg --invert -i " + kSample + " | @pc_info --text");
    ASSERT_EQ(in.code, 0) << in.err;
    const auto points = [](const std::string& s) {
        return std::stoul(s.substr(s.find("points ") + 7));
    };
    EXPECT_GT(points(out.out), 0u);
    EXPECT_EQ(points(in.out) + points(out.out), 5640u);
}

TEST(PcDbscan, EmptyCloudWithAnEstimatedEpsIsNotAUsageError) {
    // An empty cloud has no spacing to estimate eps from: every rule passes it through labelled
    // (it was exit 2, a usage error, for what is valid data).
    for (const char* eps : {"auto", "knee", "3xs"}) {
        const RunResult r =
            run_shell(std::string("@pc_dbscan --eps ") + eps + " | @pc_count --plain",
                      xyz_header("0", "binary"));
        EXPECT_EQ(r.code, 0) << eps << ": " << r.err;
        EXPECT_EQ(r.out, "0\n") << eps;
    }
}

TEST(PcCount, EmptyCloudCountsZeroAndGroundTruthAddsRecovery) {
    const RunResult empty = run_shell("@pc_count --plain", xyz_header("0", "binary"));
    EXPECT_EQ(empty.code, 0) << empty.err;
    EXPECT_EQ(empty.out, "0\n");
    const RunResult r =
        run_shell("@pc_count --gt 4",
                  pcd_header("x y z label", "4 4 4 4", "F F F U", "1 1 1 1", "3", "3", "ascii") +
                      "0 0 0 1\n1 0 0 2\n2 0 0 0\n");
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["count"], 2);
    EXPECT_EQ(j["recovery"], 0.5);
    EXPECT_EQ(j["noise_points"], 1);
    // Clusters of one point each: far below a resolvable fruit, said in the report and on stderr.
    ASSERT_EQ(j["warnings"].size(), 1u) << r.out;
    EXPECT_NE(j["warnings"][0].get<std::string>().find("the median cluster has only 1 points"),
              std::string::npos);
    EXPECT_NE(r.err.find("pc_count: warning: the median cluster has only 1 points"),
              std::string::npos)
        << r.err;
}

TEST(PcFruitcount, ColourWordsRulesAndAGivenRadiusReachTheirSteps) {
    // A word fixes the colour rule and the report says which ran.
    const RunResult red = run_shell("@pc_fruitcount --fruit-color red -i " + kSample);
    ASSERT_EQ(red.code, 0) << red.err;
    const auto r = nlohmann::json::parse(red.out);
    EXPECT_EQ(r["steps"][0]["rule"], "red: hue 320..35 deg");
    // Any pc_colorfilter rule is accepted, but not together with a word.
    const RunResult rule =
        run_shell("@pc_fruitcount --hue 0:60 --saturation 0.2:1 --plain -i " + kSample);
    EXPECT_EQ(rule.code, 0) << rule.err;
    const RunResult both = run_shell("@pc_fruitcount --fruit-color red --hue 0:60 -i " + kSample);
    EXPECT_EQ(both.code, 2);
    EXPECT_NE(both.err.find("give either --fruit-color or colour rules"), std::string::npos)
        << both.err;
    const RunResult word = run_shell("@pc_fruitcount --fruit-color blue -i " + kSample);
    EXPECT_EQ(word.code, 2);
    EXPECT_NE(word.err.find("--fruit-color must be auto, mask, red"), std::string::npos)
        << word.err;
    // A known fruit radius is a prior the points may lower by up to a tenth; the split's record
    // and note say which radius was used.
    // (The sample's fruit are 0.03 in radius: fruit_small.json.)
    const RunResult given = run_shell("@pc_fruitcount -v --fruit-radius 0.03 -i " + kSample);
    ASSERT_EQ(given.code, 0) << given.err;
    const auto g = nlohmann::json::parse(given.out);
    nlohmann::json split;
    for (const auto& step : g["steps"]) {
        split = step["step"] == "recursive_split" ? step : split;
    }
    ASSERT_FALSE(split.is_null()) << g["steps"];
    EXPECT_GE(split["fruit_radius"].get<double>(), 0.9 * 0.03);
    EXPECT_LE(split["fruit_radius"].get<double>(), 0.03);
    EXPECT_NE(given.err.find("from the given 0.03)"), std::string::npos) << given.err;
    EXPECT_EQ(g["count"], sample_fruit_count());
}

TEST(PcFruitcount, ColourSmoothingFollowsTheColoursNoise) {
    // The same 40 plums sampled as SfM, their colours clean (pc_synth's ±8) and with N(0, 25) a
    // channel added: under `auto` the colour rule reads neighbourhood medians on the noisy cloud
    // only; the colour step's record says the noise it read and the neighbours it took (0: none).
    TempDir dir;
    const std::string scene =
        "@pc_synth --species plum --fruit-count 40 --canopy 0.4,0.4,0.3 --mode sfm";
    ASSERT_EQ(run_shell(scene + " -o " + dir.file("clean.pcd")).code, 0);
    const auto colour_step = [&](const std::string& cmd, int count = 40) {
        const RunResult r = run_shell(cmd);
        EXPECT_EQ(r.code, 0) << cmd << ": " << r.err;
        const auto j = nlohmann::json::parse(r.out);
        EXPECT_EQ(j["count"], count) << cmd;
        EXPECT_EQ(j["steps"][0]["step"], "color_filter");
        return j["steps"][0];
    };
    const auto noisy = colour_step(scene + " --color-noise 25 | @pc_fruitcount");
    EXPECT_GT(noisy["color_noise"].get<double>(), 20);
    EXPECT_EQ(noisy["color_smooth"], 8);
    const auto clean = colour_step("@pc_fruitcount -i " + dir.file("clean.pcd"));
    EXPECT_LT(clean["color_noise"].get<double>(), 10);
    EXPECT_EQ(clean["color_smooth"], 0);
    EXPECT_EQ(
        colour_step("@pc_fruitcount --color-smooth 4 -i " + dir.file("clean.pcd"))["color_smooth"],
        4);
    EXPECT_FALSE(colour_step("@pc_fruitcount --color-smooth off -i " + dir.file("clean.pcd"))
                     .contains("color_smooth"));
    // the paper's presets read each point's own colour (and count 12 here: their eps is for
    // another cloud)
    EXPECT_FALSE(colour_step("@pc_fruitcount --preset paper-dense --fruit-color auto -i " +
                                 dir.file("clean.pcd"),
                             12)
                     .contains("color_smooth"));
    // pc_colorfilter decides as pc_fruitcount does: the same points
    const RunResult kept = run_shell(scene + " --color-noise 25 | @pc_colorfilter | @pc_info");
    ASSERT_EQ(kept.code, 0) << kept.err;
    EXPECT_EQ(nlohmann::json::parse(kept.out)["points"], noisy["points_out"]);
    const RunResult v = run_shell("@pc_fruitcount -v -i " + dir.file("clean.pcd"));
    EXPECT_NE(v.err.find("color_smooth: colour noise "), std::string::npos) << v.err;
    for (const std::string bad : {"0.5", "65", "-1", "eight"}) {
        const RunResult r =
            run_shell("@pc_fruitcount --color-smooth " + bad + " -i " + dir.file("clean.pcd"));
        EXPECT_EQ(r.code, 2) << bad;
        EXPECT_EQ(line_count(r.err), 1) << r.err;
        EXPECT_NE(r.err.find("--color-smooth"), std::string::npos) << r.err;
    }
}

TEST(PcFruitcount, NoWoodKeepsThePartsColouredLikeTheWood) {
    // 50 yellow-green fruit beside brown bark as structure from motion (the condition matrix's
    // scene 2629, 19k points): the wood step drops the trunk and the bark pieces coloured like it
    // (50 counted); --no-wood keeps them (63 here). pc_recursive_split --preset dense ends with
    // the same step, and takes the same flag.
    TempDir dir;
    ASSERT_EQ(run_shell("@pc_synth --species apple --fruit-radius 0.045 --bunch-min 1 --bunch-max "
                        "2 --touch-gap 0.002 --fruit-count 50 --canopy 0.9,0.9,0.7 --aspect 1.5 "
                        "--aspect-spread 0.1 --radius-spread 0.2 --mode sfm --voxel 0.009 --seed "
                        "380841 --noise 0.1 --fruit-rgb 175,190,60 --shading 0.6 --branches 7 "
                        "--trunk-radius 0.039 --wood-rgb 100,75,50 -o " +
                        dir.file("tree.pcd"))
                  .code,
              0);
    const auto count = [&](const std::string& options) {
        const RunResult r = run_shell("@pc_fruitcount -i " + dir.file("tree.pcd") + options);
        EXPECT_EQ(r.code, 0) << options << ": " << r.err;
        return nlohmann::json::parse(r.out);
    };
    const auto with = count("");
    const auto without = count(" --no-wood --cloud " + dir.file("wooded.pcd"));
    EXPECT_EQ(with["count"], 50);
    EXPECT_GT(without["count"].get<int>(), 55);
    EXPECT_EQ(with["steps"].back()["step"], "wood_parts");
    EXPECT_NE(without["steps"].back()["step"], "wood_parts");
    // the parts kept with the wood, split again: the step drops the wood unless told not to
    const auto split = [&](const std::string& options) {
        const RunResult r = run_shell("@pc_recursive_split --preset dense" + options + " -i " +
                                      dir.file("wooded.pcd") + " | @pc_count --plain");
        EXPECT_EQ(r.code, 0) << options << ": " << r.err;
        return std::stoi(r.out);
    };
    EXPECT_LT(split(""), split(" --no-wood"));
}

TEST(PcFruitcount, EpsCheckWarnsWhenTheCountSwingsWithEps) {
    // The author script's eps 0.0065 sits below this sample's ~7 mm spacing: at 0.8x every fruit
    // falls apart into noise, at 1.25x they hold together. The default's lengths come from the
    // cloud, and its count stays put.
    const RunResult script =
        run_shell("@pc_fruitcount --preset invnerfseg --eps-check -i " + kSample);
    ASSERT_EQ(script.code, 0) << script.err;
    const auto s = nlohmann::json::parse(script.out);
    ASSERT_EQ(s["eps_check"]["eps"].size(), 3u);
    EXPECT_EQ(s["eps_check"]["eps"][1], 0.0065);
    EXPECT_EQ(s["eps_check"]["counts"][1], s["count"]);
    ASSERT_FALSE(s["warnings"].empty());
    EXPECT_NE(s["warnings"].back().get<std::string>().find("the count swings by more than 2x"),
              std::string::npos);
    EXPECT_NE(script.err.find("pc_fruitcount: warning: the count swings"), std::string::npos);
    const RunResult dense = run_shell("@pc_fruitcount --eps-check -i " + kSample);
    ASSERT_EQ(dense.code, 0) << dense.err;
    const auto d = nlohmann::json::parse(dense.out);
    EXPECT_EQ(d["eps_check"]["counts"], nlohmann::json::array({12, 12, 12}));
    EXPECT_TRUE(d["warnings"].empty()) << dense.out;
}

TEST(PcVoxel, CollapsesPointsAndKeepsFields) {
    const RunResult r = run_shell("@pc_voxel --leaf 0.05 -i " + kSample + " | @pc_info --text");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("field_names x y z rgb\n"), std::string::npos);
    EXPECT_EQ(run_shell("@pc_voxel --leaf 0 -i " + kSample).code, 2);
}

TEST(Chain, DensePresetCountsTheSameAfterScalingRotatingAndThinning) {
    // Every length of the dense preset comes from the cloud: NeRF exports live in normalised
    // frames, so a count must not depend on the unit or the orientation, nor on the resolution
    // (every second point kept: the spacing grows by 2^(1/3) in a solid, 2^(1/2) on a surface).
    for (const std::string name : {"plum_bunches_explicit", "plum_bunches_implicit"}) {
        const std::string in = std::string(PC_SAMPLE_CLOUDS_DIR) + "/" + name + ".pcd";
        const RunResult base = run_shell("@pc_fruitcount --plain -i " + in);
        ASSERT_EQ(base.code, 0) << base.err;
        if (name == "plum_bunches_explicit") {
            EXPECT_EQ(base.out, "60\n");  // all 60 plums of 10 touching bunches
        } else {
            EXPECT_NEAR(std::stoi(base.out), 60,
                        2);  // hollow: the size from the surfaces' curvature
        }
        for (const std::string t : {"--scale 0.001", "--scale 0.25", "--scale 4",
                                    "--rotate 1,2,3,40", "--rotate 0,0,1,45"}) {
            const RunResult r =
                run_shell("@pc_transform " + t + " -i " + in + " | @pc_fruitcount --plain");
            ASSERT_EQ(r.code, 0) << r.err;
            EXPECT_EQ(r.out, base.out) << name << " " << t;
        }
        const io::Blob all = io::parse_cloud(slurp(in)).blob;
        std::vector<std::uint32_t> even;
        for (std::uint32_t i = 0; i < all.size(); i += 2) {
            even.push_back(i);
        }
        io::StringSink half;
        io::write_pcd(io::copy_points(all, even), io::PcdEncoding::kBinary, half);
        const RunResult r = run_shell("@pc_fruitcount --plain", half.out);
        ASSERT_EQ(r.code, 0) << r.err;
        EXPECT_EQ(r.out, base.out) << name << " every second point";
    }
}

TEST(Chain, DarkFruitCountedZeroIsAWarningInTheReportAndOnStderr) {
    // A dark red ball (mean RGB 0.21): the paper's colour rule (mean RGB > 0.5) drops every
    // point. The count of 0 stands, with exit 0, but never silently.
    std::string cloud =
        pcd_header("x y z rgb", "4 4 4 4", "F F F U", "1 1 1 1", "2000", "2000", "ascii");
    for (int i = 0; i < 2000; ++i) {
        const double phi = 2.399963 * i;  // a golden-angle spiral over the sphere
        const double z = 1 - 2 * (i + 0.5) / 2000.0, rho = std::sqrt(1 - z * z);
        cloud += std::to_string(0.03 * rho * std::cos(phi)) + " " +
                 std::to_string(0.03 * rho * std::sin(phi)) + " " + std::to_string(0.03 * z) + " " +
                 std::to_string((120 << 16) | (20 << 8) | 20) + "\n";
    }
    const RunResult r = run_shell("@pc_fruitcount --preset paper-dense", cloud);
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["count"], 0);
    ASSERT_GE(j["warnings"].size(), 2u) << r.out;
    EXPECT_NE(j["warnings"][0].get<std::string>().find("color_filter kept 0 of 2000 points"),
              std::string::npos);
    EXPECT_NE(j["warnings"].back().get<std::string>().find("no cluster counted"),
              std::string::npos);
    EXPECT_EQ(j["steps"][0]["step"], "color_filter");
    EXPECT_EQ(j["steps"][0]["points_in"], 2000);
    EXPECT_EQ(j["steps"][0]["points_out"], 0);
    EXPECT_NE(r.err.find("pc_fruitcount: warning: color_filter kept 0 of 2000 points"),
              std::string::npos)
        << r.err;
    // The default chooses its rule from the cloud: natural colours, the saturated red is kept.
    const RunResult chosen = run_shell("@pc_fruitcount", cloud);
    ASSERT_EQ(chosen.code, 0) << chosen.err;
    const auto c = nlohmann::json::parse(chosen.out);
    EXPECT_EQ(c["count"], 1) << chosen.out;
    EXPECT_NE(c["steps"][0]["rule"].get<std::string>().find("auto: natural colours"),
              std::string::npos)
        << chosen.out;
    // One fruit as large as the cloud: the colour step cannot tell it from a lone blob that is
    // no fruit (the ground, a trunk), and says so.
    EXPECT_EQ(chosen.err.find("pc_fruitcount: warning: the fruit radius is over a tenth of the "
                              "spread of the points counted"),
              0u)
        << chosen.err;
    EXPECT_EQ(std::count(chosen.err.begin(), chosen.err.end(), '\n'), 1) << chosen.err;
    // Without the colour step the ball is one fruit, and nothing is doubtful.
    const RunResult no_color = run_shell("@pc_fruitcount --no-color", cloud);
    ASSERT_EQ(no_color.code, 0) << no_color.err;
    const auto one = nlohmann::json::parse(no_color.out);
    EXPECT_EQ(one["count"], 1);
    EXPECT_TRUE(one["warnings"].empty()) << no_color.out;
    EXPECT_EQ(one["cluster_sizes"]["median"], one["clusters"][0]["points"]);
    EXPECT_EQ(one["cluster_sizes"]["several"], 0);
    EXPECT_EQ(one["steps"][0]["step"], "dbscan");  // --no-color: dbscan, split
    EXPECT_GT(one["steps"][0]["eps"].get<double>(), 0);
    EXPECT_GT(one["steps"][0]["spacing"].get<double>(), 0);  // dense: eps from the spacing
}

}  // namespace
}  // namespace pc::test
