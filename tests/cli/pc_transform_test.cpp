#include <cmath>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <pc/io/points.h>
#include <pc/io/read.h>

#include "support/corpus.h"
#include "support/run_tool.h"

namespace pc::test {
namespace {

const std::string kSample = std::string(PC_SAMPLE_CLOUDS_DIR) + "/fruit_small.ply";

/// x y z normal_x normal_y normal_z (F 4) and a label: two points.
std::string cloud_with_normals() {
    return pcd_header("x y z normal_x normal_y normal_z label", "4 4 4 4 4 4 4", "F F F F F F U",
                      "1 1 1 1 1 1 1", "2", "2", "ascii") +
           "1 0 0 1 0 0 7\n0.1 0.2 0.3 0 0 1 9\n";
}

TEST(PcTransform, TransformThenInverseIsTheIdentityWithinFloatPrecision) {
    TempDir dir;
    spit(dir.file("a.pcd"), cloud_with_normals());
    const std::string t =
        " --rotate 1,2,3,33 --scale 2.5 --translate 4,-5,6 --matrix 1,0,0,1,0,1,0,2,0,0,1,3";
    const RunResult r =
        run_shell("@pc_transform -i " + dir.file("a.pcd") + t + " | @pc_transform --inverse" + t +
                  " | @pc_compare - " + dir.file("a.pcd") + " --tau 1e-5");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_LT(j["a_to_b"]["max"].get<double>(), 2e-6);
    EXPECT_EQ(j["fscore"], 1.0);
}

TEST(PcTransform, NormalsRotateWithThePointsAndOtherFieldsStay) {
    const RunResult r =
        run_shell("@pc_transform --rotate 0,0,1,90 --scale 3", cloud_with_normals());
    ASSERT_EQ(r.code, 0) << r.err;
    const io::Blob b = io::parse_cloud(r.out).blob;
    const Cloud c = io::xyz(b);
    EXPECT_NEAR(c[0].x, 0, 1e-6);
    EXPECT_NEAR(c[0].y, 3, 1e-6);
    const auto* nx = io::find_field(b, "normal_x");
    const auto* ny = io::find_field(b, "normal_y");
    EXPECT_NEAR(io::value_as_double(&b.cloud.data[nx->offset], nx->datatype), 0, 1e-6);
    EXPECT_NEAR(io::value_as_double(&b.cloud.data[ny->offset], ny->datatype), 1, 1e-6);  // unit
    EXPECT_EQ(io::labels(b), (std::vector<std::uint32_t>{7, 9}));
}

TEST(PcTransform, NerfstudioRoundTrip) {
    TempDir dir;
    spit(
        dir.file("dp.json"),
        R"({"transform": [[0.0, 0.6, 0.8, 0.1], [1.0, 0.0, 0.0, -0.2], [0.0, 0.8, -0.6, 0.3]], "scale": 0.24})");
    const RunResult r =
        run_shell("@pc_transform -i " + kSample + " --nerfstudio " + dir.file("dp.json") +
                  " --inverse | @pc_transform --nerfstudio " + dir.file("dp.json") +
                  " | @pc_compare - " + kSample + " --tau 1e-9");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_LT(nlohmann::json::parse(r.out)["a_to_b"]["max"].get<double>(),
              1e-12);  // F 8 coordinates
}

TEST(PcTransform, CenterAndNormalize) {
    const RunResult r =
        run_shell("@pc_transform -i " + kSample + " --center --normalize mean-radius | @pc_extent");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto c = nlohmann::json::parse(r.out)["clouds"][0];
    // pc_extent measures float coordinates (pc::Cloud), so float precision is the bound.
    EXPECT_NEAR(c["mean_radius"].get<double>(), 1.0, 1e-6);
    EXPECT_NEAR(c["centroid"][0].get<double>(), 0.0, 1e-6);
    const RunResult d =
        run_shell("@pc_transform -i " + kSample + " --normalize diagonal | @pc_info");
    const auto j = nlohmann::json::parse(d.out);
    double diag2 = 0;
    for (int a = 0; a < 3; ++a) {
        const double e = j["bbox"]["max"][a].get<double>() - j["bbox"]["min"][a].get<double>();
        diag2 += e * e;
    }
    EXPECT_NEAR(std::sqrt(diag2), 1.0, 1e-12);
}

TEST(PcTransform, BadArgumentsAreUsageErrors) {
    EXPECT_EQ(run_shell("@pc_transform --scale 0 -i " + kSample).code, 2);
    EXPECT_EQ(run_shell("@pc_transform --rotate 0,0,0,90 -i " + kSample).code, 2);
    EXPECT_EQ(run_shell("@pc_transform --matrix 1,2,3 -i " + kSample).code, 2);
    EXPECT_EQ(run_shell("@pc_transform --normalize unit -i " + kSample).code, 2);
    // A file that is not there is an I/O error, as a missing -i is (exit 1, not 2).
    const RunResult missing =
        run_shell("@pc_transform --nerfstudio /nonexistent.json -i " + kSample);
    EXPECT_EQ(missing.code, 1);
    EXPECT_EQ(missing.err,
              "pc_transform: error: /nonexistent.json: cannot read the --nerfstudio "
              "file: No such file or directory\n");
}

TEST(Messages, SayWhatWasExpectedAndWhatToDo) {
    // issue 21's rough edges, each message as a new user reads it
    const RunResult rotate = run_shell("@pc_transform --rotate 0,0,1 -i " + kSample);
    EXPECT_EQ(rotate.code, 2);
    EXPECT_NE(rotate.err.find("expected AX,AY,AZ,DEG (an axis and an angle in degrees), got "
                              "'0,0,1'"),
              std::string::npos)
        << rotate.err;
    const RunResult preset = run_shell("@pc_fruitcount --preset bogus -i " + kSample);
    EXPECT_EQ(preset.code, 2);
    EXPECT_NE(preset.err.find("(known: dense, paper-dense, paper-sparse, invnerfseg)"),
              std::string::npos)
        << preset.err;
    const RunResult typo = run_shell("@pc_dbscan --esp 3 -i " + kSample);
    EXPECT_EQ(typo.code, 2);
    EXPECT_NE(typo.err.find("unrecognised option '--esp'; did you mean --eps?"), std::string::npos)
        << typo.err;
    const RunResult far = run_shell("@pc_dbscan --zzzzzz 3 -i " + kSample);
    EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;
    const RunResult unlabelled = run_shell("@pc_count -i " + kSample);
    EXPECT_EQ(unlabelled.code, 1);
    EXPECT_EQ(unlabelled.err,
              "pc_count: error: " + kSample +
                  ": cloud has no 'label' field (label its clusters first: "
                  "pc_dbscan, then pc_recursive_split; or pc_fruitcount --cloud)\n");
}

TEST(PcCompare, TakesTwoInputsWithAFromStdinWhenOnlyBIsGiven) {
    EXPECT_EQ(run_shell("@pc_compare " + kSample + " " + kSample + " " + kSample).code, 2);
    const RunResult piped = run_shell("@pc_compare --plain-is-not-an-option " + kSample);
    EXPECT_EQ(piped.code, 2);
    const RunResult r = run_shell("@pc_convert -i " + kSample + " | @pc_compare " + kSample);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["a"], "<stdin>");
    const RunResult csv = run_shell("@pc_compare --csv " + kSample + " " + kSample);
    EXPECT_EQ(line_count(csv.out), 2);
}

}  // namespace
}  // namespace pc::test
