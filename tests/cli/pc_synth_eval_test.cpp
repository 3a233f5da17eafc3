// pc_synth and pc_eval through real processes: determinism, ground truth, the chain scored end to
// end, and hand-made labellings with known scores.
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/corpus.h"
#include "support/run_tool.h"

namespace pc::test {
namespace {

/// The spheres split's record in a pc_fruitcount report (the wood step may follow it).
nlohmann::json split_of(const nlohmann::json& report) {
    for (const auto& step : report["steps"]) {
        if (step["step"] == "recursive_split") {
            return step;
        }
    }
    ADD_FAILURE() << "no recursive_split step: " << report["steps"];
    return {};
}

const std::string kSmall = " --species peach --fruit-count 12 --canopy 0.35,0.35,0.3";

TEST(PcSynth, SameSeedSameBytesOtherSeedOtherBytes) {
    TempDir dir;
    for (const std::string mode : {"explicit", "implicit", "degraded"}) {
        for (const auto& [file, seed] : {std::pair{"a", 5}, {"b", 5}, {"c", 6}}) {
            const RunResult r = run_shell("@pc_synth" + kSmall + " --mode " + mode + " --seed " +
                                          std::to_string(seed) + " -o " + dir.file(file) +
                                          ".pcd --truth " + dir.file(file) + ".json");
            ASSERT_EQ(r.code, 0) << r.err;
        }
        EXPECT_EQ(slurp(dir.file("a.pcd")), slurp(dir.file("b.pcd"))) << mode;
        EXPECT_EQ(slurp(dir.file("a.json")), slurp(dir.file("b.json"))) << mode;
        EXPECT_NE(slurp(dir.file("a.pcd")), slurp(dir.file("c.pcd"))) << mode;
    }
}

TEST(PcSynth, ShippedScenesAreWhatTheGeneratorMakes) {
    // sample_clouds/scenes.txt: one `name|arguments` per line; make_scenes.sh regenerates them.
    TempDir dir;
    std::istringstream lines(slurp(std::string(PC_SAMPLE_CLOUDS_DIR) + "/scenes.txt"));
    int scenes = 0;
    for (std::string line; std::getline(lines, line);) {
        const auto bar = line.find('|');
        if (bar == std::string::npos) {
            continue;
        }
        const std::string name = line.substr(0, bar),
                          shipped = std::string(PC_SAMPLE_CLOUDS_DIR) + "/" + name;
        const RunResult r = run_shell("@pc_synth " + line.substr(bar + 1) + " -o " +
                                      dir.file("s.pcd") + " --truth " + dir.file("s.json"));
        ASSERT_EQ(r.code, 0) << r.err;
        EXPECT_EQ(slurp(dir.file("s.pcd")), slurp(shipped + ".pcd"))
            << name << ": run sample_clouds/make_scenes.sh";
        EXPECT_EQ(slurp(dir.file("s.json")), slurp(shipped + ".json")) << name;
        ++scenes;
    }
    EXPECT_EQ(scenes, 3);
}

TEST(PcSynth, TruthAgreesWithTheCloud) {
    TempDir dir;
    const RunResult r =
        run_shell("@pc_synth --species plum --fruit-count 40 --canopy 0.4,0.4,0.3 --truth " +
                  dir.file("t.json") + " | @pc_info");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto truth = nlohmann::json::parse(slurp(dir.file("t.json")));
    const auto info = nlohmann::json::parse(r.out);
    EXPECT_EQ(truth["fruit_count"], 40);
    EXPECT_EQ(truth["fruit_present"], 40);
    EXPECT_EQ(truth["fruits"].size(), 40u);
    EXPECT_EQ(truth["points"], info["points"]);
    EXPECT_NE(r.out.find("gt_instance"), std::string::npos);
}

TEST(PcSynth, SpheroidFruitCarryTheirShapeInTheTruth) {
    // --aspect through a pipe: every fruit's aspect within the spread, a unit axis, and the
    // cloud's fruit points as the truth counts them; round fruit have no shape keys.
    TempDir dir;
    const RunResult r = run_shell(
        "@pc_synth --species plum --fruit-count 30 --canopy 0.4,0.4,0.3 --mode surface "
        "--aspect 1.6 --aspect-spread 0.1 --truth " +
        dir.file("t.json") + " | @pc_info");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto truth = nlohmann::json::parse(slurp(dir.file("t.json")));
    EXPECT_EQ(truth["points"], nlohmann::json::parse(r.out)["points"]);
    for (const auto& f : truth["fruits"]) {
        EXPECT_NEAR(f["aspect"].get<double>(), 1.6, 0.16 + 1e-9);
        const auto a = f["axis"].get<std::vector<double>>();
        EXPECT_NEAR(a[0] * a[0] + a[1] * a[1] + a[2] * a[2], 1.0, 1e-9);
    }
    ASSERT_EQ(run_shell("@pc_synth" + kSmall + " --truth " + dir.file("r.json") + " -o " +
                        dir.file("r.pcd"))
                  .code,
              0);
    EXPECT_FALSE(nlohmann::json::parse(slurp(dir.file("r.json")))["fruits"][0].contains("aspect"));
}

TEST(PcSynth, BlushedFruitCarryTheirShareInTheTruth) {
    // --blush-* through a pipe: every fruit's blushed share within the range, the cloud's points
    // as the truth counts them; one-coloured fruit have no blush key.
    TempDir dir;
    const RunResult r = run_shell("@pc_synth" + kSmall +
                                  " --mode surface --blush-rgb 180,40,50 --blush-min 0.3 "
                                  "--blush-max 0.6 --truth " +
                                  dir.file("t.json") + " | @pc_info");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto truth = nlohmann::json::parse(slurp(dir.file("t.json")));
    EXPECT_EQ(truth["points"], nlohmann::json::parse(r.out)["points"]);
    for (const auto& f : truth["fruits"]) {
        EXPECT_GE(f["blush"].get<double>(), 0.3 - 1e-9);
        EXPECT_LE(f["blush"].get<double>(), 0.6 + 1e-9);
    }
    ASSERT_EQ(run_shell("@pc_synth" + kSmall + " --truth " + dir.file("r.json") + " -o " +
                        dir.file("r.pcd"))
                  .code,
              0);
    EXPECT_FALSE(nlohmann::json::parse(slurp(dir.file("r.json")))["fruits"][0].contains("blush"));
}

TEST(PcSynth, BadParametersAreUsageErrorsWithoutOutput) {
    TempDir dir;
    for (const std::string args :
         {" --fruit-radius -1", " --mode solid", " --species banana", " --fruit-rgb 300,0,0",
          " --fruit-count 100000 --canopy 0.1,0.1,0.1", " --voxel 0.1", " --aspect 5",
          " --aspect-spread 1", " --blush-rgb 300,0,0", " --blush-min 0.9 --blush-max 0.5",
          " --color-noise -5", " --color-noise 300"}) {
        const RunResult r = run_shell("@pc_synth" + args + " -o " + dir.file("x.pcd"));
        EXPECT_EQ(r.code, 2) << args << ": " << r.err;
        EXPECT_EQ(line_count(r.err), 1) << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir.file("x.pcd"))) << args;
    }
    const RunResult r =
        run_shell("@pc_synth" + kSmall + " --truth /nonexistent/t.json -o " + dir.file("x.pcd"));
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("/nonexistent/t.json"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("x.pcd")));
}

TEST(PcEval, WellSeparatedExplicitSceneThroughThePipedChainScoresOne) {
    TempDir dir;
    const RunResult r =
        run_shell("@pc_synth" + kSmall + " --truth " + dir.file("t.json") +
                  " | @pc_colorfilter --preset paper-dense | @pc_knn_outlier --preset paper-dense"
                  " | @pc_dbscan --preset paper-dense | @pc_recursive_split --preset paper-dense"
                  " | @pc_eval --truth " +
                  dir.file("t.json"));
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["match"], "overlap");
    EXPECT_EQ(j["count"], 12);
    EXPECT_EQ(j["gt_count"], 12);
    EXPECT_EQ(j["f1"], 1.0);
    EXPECT_EQ(j["merged"], 0);
    EXPECT_EQ(j["split"], 0);
}

TEST(PcFruitcount, DefaultCountsSamplingKindsColoursAndUnits) {
    // A few conditions of docs/robustness.md (its tune part), small: the default command, no
    // per-scene parameter, scored against the generator's truth. The fruit present in the cloud
    // are the oracle (a fruit the export lost cannot be counted).
    const std::string canopy = " --fruit-count 40 --canopy 0.45,0.45,0.4 --radius-spread 0.2";
    const std::vector<std::string> scenes = {
        // solid lattice, touching plums, 5 spacings a radius, red
        "--species plum --mode explicit --voxel 0.0034 --fruit-rgb 190,35,40",
        // NeRF-like visible surfaces, 3 spacings a radius, mask colours
        "--species plum --mode implicit --voxel 0.0057 --colors mask",
        // structure from motion in millimetres, dark purple, shaded
        "--species apple --mode sfm --voxel 0.0044 --fruit-rgb 75,30,65 --shading 0.6 "
        "--scale 1000",
        // cherries interpenetrating by up to 10 %, random in the volume, orange, normalised
        "--species plum --fruit-radius 0.012 --bunch-min 2 --bunch-max 6 --touch-gap 0.001 "
        "--overlap 0.1 --mode volume --voxel 0.0024 --fruit-rgb 235,140,45 --scale 0.45 "
        "--offset 0.1,-0.05,0.2",
        // random surface points jittered by 10 % of the radius, 8 spacings a radius
        "--species peach --mode surface --voxel 0.0044 --noise 0.1 --fruit-rgb 190,35,40",
        // scanner lines across interpenetrating cherries, 8 line spacings a radius, shaded
        // (lines through the points, not the normals' feet, measured R 20 % large: F1 0.78)
        "--species plum --fruit-radius 0.012 --bunch-min 2 --bunch-max 6 --touch-gap 0.001 "
        "--overlap 0.1 --mode stripes --voxel 0.0015 --fruit-rgb 235,140,45 --shading 0.6",
    };
    for (const std::string& scene : scenes) {
        TempDir dir;
        const RunResult r =
            run_shell("@pc_synth " + scene + canopy + " --truth " + dir.file("t.json") +
                      " | @pc_fruitcount --cloud " + dir.file("l.pcd") + " --plain");
        ASSERT_EQ(r.code, 0) << scene << ": " << r.err;
        const auto truth = nlohmann::json::parse(slurp(dir.file("t.json")));
        const int present = truth["fruit_present"];
        const RunResult e = run_shell("@pc_eval -i " + dir.file("l.pcd") + " --truth " +
                                      dir.file("t.json") + " --gt " + std::to_string(present));
        ASSERT_EQ(e.code, 0) << e.err;
        const auto j = nlohmann::json::parse(e.out);
        EXPECT_NEAR(std::stoi(r.out), present, 0.1 * present) << scene;
        EXPECT_GE(j["f1"].get<double>(), 0.9) << scene;
        EXPECT_EQ(r.err.find("bunch's"), std::string::npos) << scene << ": " << r.err;
    }
}

TEST(PcFruitcount, BunchesReadAsOneFruitAreLookedAtAgainOrAWarning) {
    // Grape-like bunches of 6-12 berries 9 mm in radius sampled at random in their volume, 2
    // points to a radius. The normals first read a bunch's radius (about 28 mm; 14 of 80 were
    // counted with it); its centres leave most points unclaimed, so R is measured again at a
    // smaller scale: about 11 mm, 61 counted (81 since the dense preset has no kNN filter, which
    // had dropped a tenth of these sparse points), and a warning that two sizes fit.
    const std::string scene =
        "@pc_synth --species plum --fruit-count 80 --fruit-radius 0.009 --bunch-min 6 "
        "--bunch-max 12 --overlap 0.1 --canopy 0.45,0.45,0.4 --mode volume --voxel 0.0045 | "
        "@pc_fruitcount";
    const auto warned = [](const nlohmann::json& j, const std::string& what) {
        bool found = false;
        for (const auto& w : j["warnings"]) {
            found = found || w.get<std::string>().find(what) != std::string::npos;
        }
        return found;
    };
    const RunResult r = run_shell(scene);
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_GT(j["count"].get<int>(), 50);
    EXPECT_LE(j["count"].get<int>(), 88);  // within 10 % of the 80
    EXPECT_GT(split_of(j)["larger_radius"].get<double>(), 2 * 0.009) << j["steps"];
    EXPECT_LT(split_of(j)["fruit_radius"].get<double>(), 1.4 * 0.009) << j["steps"];
    EXPECT_TRUE(warned(j, "two fruit sizes fit")) << j["warnings"];
    EXPECT_NE(r.err.find("give --fruit-radius"), std::string::npos) << r.err;
    EXPECT_EQ(split_of(j)["rule"], "solid fruit: their outer layer voted") << j["steps"];
    // Counted with a bunch's radius (here given), the bunches hold about a tenth of the points a
    // solid ball of that radius would: a warning.
    const RunResult given = run_shell(scene + " --fruit-radius 0.028");
    ASSERT_EQ(given.code, 0) << given.err;
    const auto g = nlohmann::json::parse(given.out);
    EXPECT_LT(g["count"].get<int>(), 40);
    EXPECT_TRUE(warned(g, "the radius may be a bunch's")) << g["warnings"];
}

TEST(PcFruitcount, CentresThatLeaveATenthOfThePointsAreAWarning) {
    // Cherry-like bunches of 2-6 fruit 12 mm in radius, sampled at random in their volume at 2
    // points to a radius, mask colours. Counted with R 16 mm (given here; the normals read 15 mm
    // until their sparse refit was dropped, session 58, and 122 were counted), the centres take
    // 84 % of the points, the rest is counted by DBSCAN's clusters, merged bunches among them:
    // 116 of 150. Nothing else looks wrong (no second size; eps moves nothing), so the share the
    // centres took is the warning. With the R the normals read now (12.7 mm) 152 are counted.
    const std::string scene =
        "@pc_synth --species plum --fruit-radius 0.012 --bunch-min 2 --bunch-max 6 --touch-gap "
        "0.001 --overlap 0.1 --fruit-count 150 --canopy 0.5,0.5,0.4 --radius-spread 0.2 --mode "
        "volume --voxel 0.006 --colors mask --seed 9 | @pc_fruitcount";
    const RunResult measured = run_shell(scene);
    ASSERT_EQ(measured.code, 0) << measured.err;
    const auto m = nlohmann::json::parse(measured.out);
    EXPECT_NEAR(m["count"].get<int>(), 150, 15) << m["steps"];
    const RunResult r = run_shell(scene + " --fruit-radius 0.016");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_LT(j["count"].get<int>(), 135);  // more than 10 % short of the 150
    const double claimed = split_of(j)["claimed"].get<double>();
    EXPECT_LT(claimed, 0.9) << j["steps"];
    EXPECT_GT(claimed, 0.4) << j["steps"];  // not the stronger warning about R
    bool warned = false;
    for (const auto& w : j["warnings"]) {
        warned =
            warned || w.get<std::string>().find("treat the count as rough") != std::string::npos;
    }
    EXPECT_TRUE(warned) << j["warnings"];
    EXPECT_NE(r.err.find("fruit centres took"), std::string::npos) << r.err;
}

TEST(PcFruitcount, WrongFruitRadiiAreWarnings) {
    // 60 plums 17 mm in radius (normals measure about 15-20 mm) in touching bunches, counted with
    // the radius estimated, given, given as their diameter, and given nearly 5 times too large.
    // The implicit export has floaters (0.05 a fruit): one of 16 points, a fifth of a fruit, is
    // counted (the dense preset has no kNN filter to drop it).
    const auto count = [](const std::string& flags) {
        const RunResult r = run_shell(
            "@pc_synth --species plum --mode implicit --fruit-count 60 --seed 3 | @pc_fruitcount " +
            flags);
        EXPECT_EQ(r.code, 0) << r.err;
        return std::pair{nlohmann::json::parse(r.out), r.err};
    };
    for (const std::string flags : {"", "--fruit-radius 0.017"}) {
        const auto [j, err] = count(flags);
        EXPECT_NEAR(j["count"].get<int>(), 60, 1) << flags;
        EXPECT_GT(split_of(j)["claimed"].get<double>(), 0.9) << j["steps"];
        EXPECT_TRUE(j["warnings"].empty()) << j["warnings"];
        EXPECT_FALSE(j.contains("eps_check")) << "centres took nearly every point: no check";
    }
    // The diameter: about a third counted, and the measured radius says why.
    const auto [diameter, diameter_err] = count("--fruit-radius 0.034");
    EXPECT_LT(diameter["count"].get<int>(), 30);
    EXPECT_NEAR(split_of(diameter)["measured_radius"].get<double>(), 0.017, 0.004);
    EXPECT_NE(diameter_err.find("is it a diameter"), std::string::npos) << diameter_err;
    // Far too large (nearly 5 times): few or no centres fit (the voting points, one per cube of
    // 0.3 x the given radius, are a few a fruit), most points keep their DBSCAN cluster, and
    // the warning asks about the radius ("fruit centres took only ..." or "found no fruit
    // centre"). (At 3.5 times, 0.06, the diameter warning above is the one that fires.)
    const auto [large, large_err] = count("--fruit-radius 0.08");
    EXPECT_LT(large["count"].get<int>(), 30);
    EXPECT_LT(split_of(large)["claimed"].get<double>(), 0.4) << large["steps"];
    EXPECT_NE(large_err.find("is the fruit radius right (--fruit-radius)?"), std::string::npos)
        << large_err;
    // DBSCAN's clusters make most of that count: eps matters, and is checked unasked.
    ASSERT_TRUE(large.contains("eps_check"));
    EXPECT_EQ(large["eps_check"]["counts"].size(), 3u);
    EXPECT_FALSE(count("--fruit-radius 0.08 --no-eps-check").first.contains("eps_check"));
    EXPECT_EQ(run_shell("@pc_fruitcount --eps-check --no-eps-check -i /dev/null").code, 2);
}

TEST(PcFruitcount, SmallGreenFruitAmongLeavesAreMeasuredWithoutTheLeaves) {
    // Green grapes (9 mm, bunches of 6-12, poor masks at 3 voxels a radius) among green leaves
    // of 35 mm. Where colour does not drop the leaves (every saturated point kept), their rims
    // set the first R near 20 mm (31 counted of 164 with it); measured again without the
    // clusters that are sheets, R is a grape's.
    TempDir dir;
    const std::string synth =
        "@pc_synth --species plum --fruit-radius 0.009 --bunch-min 6 --bunch-max 12 --touch-gap "
        "0.0005 --overlap 0.05 --fruit-count 200 --canopy 0.5,0.5,0.4 --radius-spread 0.2 --mode "
        "degraded --voxel 0.003 --seed 51708 --fruit-rgb 125,175,60 --truth " +
        dir.file("t.json") + " -o " + dir.file("t.pcd");
    ASSERT_EQ(run_shell(synth).code, 0);
    const int present = nlohmann::json::parse(slurp(dir.file("t.json")))["fruit_present"];
    const RunResult r =
        run_shell("@pc_fruitcount -i " + dir.file("t.pcd") + " --saturation 0.25:1 --value 0.04:1");
    ASSERT_EQ(r.code, 0) << r.err;
    auto j = nlohmann::json::parse(r.out);
    EXPECT_GT(j["count"].get<int>(), 0.75 * present);
    EXPECT_LE(j["count"].get<int>(), present);
    EXPECT_LT(split_of(j)["fruit_radius"].get<double>(), 1.3 * 0.009) << j["steps"];
    EXPECT_GT(split_of(j)["larger_radius"].get<double>(), 2 * 0.009) << j["steps"];
    EXPECT_NE(r.err.find("two fruit sizes fit"), std::string::npos) << r.err;
    // The default colour rule sees two groups of greens (grapes 86 degrees, leaves 109) and
    // keeps the grapes' (their centres claim 95 % of its points, 20 % of the leaves'): the
    // grape's R at once, and the count closer (149 of 164, 136 with the leaves).
    const RunResult d = run_shell("@pc_fruitcount -i " + dir.file("t.pcd"));
    ASSERT_EQ(d.code, 0) << d.err;
    j = nlohmann::json::parse(d.out);
    EXPECT_GT(j["count"].get<int>(), 0.85 * present);
    EXPECT_LE(j["count"].get<int>(), present);
    EXPECT_LT(split_of(j)["fruit_radius"].get<double>(), 1.3 * 0.009) << j["steps"];
    EXPECT_NE(j["steps"].front()["rule"].get<std::string>().find("the group whose fruit centres"),
              std::string::npos)
        << j["steps"];
    EXPECT_EQ(d.err.find("leaves were kept"), std::string::npos) << d.err;
}

/// Three fruit of 4 points on a line (x = 0.., 10.., 20..), with `label` as given.
std::string labelled(const std::vector<int>& labels, bool with_gt = true) {
    std::string s = pcd_header(with_gt ? "x y z label gt_instance" : "x y z label",
                               with_gt ? "4 4 4 4 4" : "4 4 4 4", with_gt ? "F F F U U" : "F F F U",
                               with_gt ? "1 1 1 1 1" : "1 1 1 1", "12", "12", "ascii");
    for (int n = 0; n < 12; ++n) {
        s += std::to_string(10 * (n / 4) + 0.1 * (n % 4)) + " 0 0 " + std::to_string(labels[n]);
        if (with_gt) {
            s += ' ';  // not `" " + std::string`: GCC 12 warns -Wrestrict on it
            s += std::to_string(n / 4 + 1);
        }
        s += '\n';
    }
    return s;
}

TEST(PcEval, MergeAndSplitAreReported) {
    const RunResult merged = run_shell("@pc_eval", labelled({1, 1, 1, 1, 1, 1, 1, 1, 2, 2, 2, 2}));
    ASSERT_EQ(merged.code, 0) << merged.err;
    auto j = nlohmann::json::parse(merged.out);
    EXPECT_EQ(j["count"], 2);
    EXPECT_EQ(j["merged"], 1);
    EXPECT_EQ(j["split"], 0);
    EXPECT_EQ(j["true_positives"], 1);
    const RunResult split =
        run_shell("@pc_eval --csv", labelled({1, 1, 3, 3, 2, 2, 2, 2, 4, 4, 4, 4}));
    ASSERT_EQ(split.code, 0) << split.err;
    EXPECT_NE(split.out.find(",overlap,4,3,"), std::string::npos) << split.out;
    EXPECT_NE(split.out.find(",0,1\n"), std::string::npos) << split.out;  // merged 0, split 1
}

TEST(PcEval, CentroidMatchingNeedsTheTruthFile) {
    TempDir dir;
    spit(dir.file("t.json"),
         R"({"fruit_count": 4, "fruits": [{"id": 1, "centre": [0.15, 0, 0], "radius": 1},
        {"id": 2, "centre": [10.15, 0, 0], "radius": 1}, {"id": 3, "centre": [20.15, 0, 0], "radius": 1}]})");
    const std::string cloud = labelled({1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3}, false);
    const RunResult r = run_shell("@pc_eval --truth " + dir.file("t.json"), cloud);
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["match"], "centroid");
    EXPECT_EQ(j["true_positives"], 3);
    EXPECT_EQ(j["gt_count"], 4);  // one fruit of the scene left no points
    EXPECT_EQ(j["recall"], 0.75);
    const RunResult none = run_shell("@pc_eval", cloud);
    EXPECT_EQ(none.code, 1);
    EXPECT_EQ(
        none.err,
        "pc_eval: error: <stdin>: no 'gt_instance' field (give --truth to match by centroid)\n");
    spit(dir.file("bad.json"), "{\"fruits\": [{\"id\": 1}]}");
    const RunResult bad = run_shell("@pc_eval --truth " + dir.file("bad.json"), cloud);
    EXPECT_EQ(bad.code, 1);
    EXPECT_EQ(line_count(bad.err), 1);
    EXPECT_NE(bad.err.find(dir.file("bad.json") + ": not a ground-truth file"), std::string::npos)
        << bad.err;
}

}  // namespace
}  // namespace pc::test
