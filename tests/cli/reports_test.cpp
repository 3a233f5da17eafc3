// Reports that say what they did, for many inputs at once (issue 21): every report carries its
// input, tool, version and parameters; a failing input gets an error row and exit 1 while the
// others are reported; the formats (JSON, JSON Lines, CSV, markdown, text, plain) agree.
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/corpus.h"
#include "support/run_tool.h"

namespace pc::test {
namespace {

const std::string kSamples = std::string(PC_SAMPLE_CLOUDS_DIR) + "/";

/// Three points labelled 1, 2, 0 (noise): two clusters.
std::string labelled() {
    return pcd_header("x y z label", "4 4 4 4", "F F F U", "1 1 1 1", "3", "3", "ascii") +
           "0 0 0 1\n1 0 0 2\n2 0 0 0\n";
}

std::vector<nlohmann::json> json_lines(const std::string& text) {
    std::vector<nlohmann::json> rows;
    std::stringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        rows.push_back(nlohmann::json::parse(line));
    }
    return rows;
}

TEST(Reports, CountCarriesInputToolVersionAndEveryParameter) {
    const RunResult r = run_shell("@pc_count --min-cluster-size 1 --gt 4", labelled());
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::ordered_json::parse(r.out);
    EXPECT_EQ(j["input"], "<stdin>");
    EXPECT_EQ(j["tool"], "pc_count");
    EXPECT_EQ(j["version"], run_shell("@pc_count --version").out.substr(9, 5));
    EXPECT_EQ(j["parameters"]["min-cluster-size"], 1);
    EXPECT_EQ(j["parameters"]["gt"], 4);
    EXPECT_FALSE(j["parameters"].contains("csv"));  // the format flags change no number
    EXPECT_EQ(j["count_error"], -2.0);
    EXPECT_EQ(j.items().begin().key(), "input");
    EXPECT_EQ((--j.end()).key(), "warnings");
}

TEST(Reports, FruitcountReportsEpsAndRulesAsUsedPerStep) {
    const RunResult r =
        run_shell("@pc_fruitcount --preset paper-sparse --jsonl " + kSamples + "fruit_small.ply");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["parameters"]["preset"], "paper-sparse");
    // The preset's fixed eps, not the default's text, and each step's points in and out.
    EXPECT_EQ(j["parameters"]["eps"], 0.03);
    ASSERT_TRUE(j["steps"].is_array());
    std::size_t in = j["steps"][0]["points_in"];
    EXPECT_EQ(in, 5640u);
    for (const auto& step : j["steps"]) {
        EXPECT_EQ(step["points_in"], in) << step;  // each step gets what the last passed on
        in = step["points_out"];
    }
}

TEST(Reports, ManyInputsOneRowEachAndAFailureDoesNotStopTheOthers) {
    TempDir dir;
    spit(dir.file("a.pcd"), labelled());
    spit(dir.file("bad.pcd"), "VERSION .7\nFIELDS x\n");
    const std::string inputs =
        dir.file("a.pcd") + " " + dir.file("bad.pcd") + " " + dir.file("a.pcd");
    const RunResult r = run_shell("@pc_count -q --jsonl " + inputs);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("pc_count: error: " + dir.file("bad.pcd") + ": ", 0), 0u) << r.err;
    const auto rows = json_lines(r.out);
    ASSERT_EQ(rows.size(), 3u) << r.out;
    EXPECT_EQ(rows[0]["count"], 2);
    EXPECT_EQ(rows[1]["input"], dir.file("bad.pcd"));
    EXPECT_TRUE(rows[1]["error"].is_string());
    EXPECT_EQ(rows[2]["count"], 2);

    // JSON: an array of the same rows; plain: one count a line, empty for the failure.
    const auto all = nlohmann::json::parse(run_shell("@pc_count " + inputs).out);
    ASSERT_TRUE(all.is_array());
    EXPECT_EQ(all.size(), 3u);
    EXPECT_EQ(run_shell("@pc_count --plain " + inputs).out, "2\n\n2\n");

    // CSV: a header and a row each; the failed row's error lands in its own column.
    const RunResult csv = run_shell("@pc_count --csv " + inputs);
    ASSERT_EQ(line_count(csv.out), 4) << csv.out;
    EXPECT_EQ(csv.out.rfind("input,tool,version,parameters.preset,", 0), 0u) << csv.out;
    EXPECT_NE(csv.out.find(",error"), std::string::npos);

    // Every input bad: only the error lines, no report.
    const RunResult none =
        run_shell("@pc_count -q " + dir.file("bad.pcd") + " " + dir.file("x.pcd"));
    EXPECT_EQ(none.code, 1);
    EXPECT_EQ(none.out, "");
    EXPECT_EQ(line_count(none.err), 2);
}

TEST(Reports, MarkdownAndTextLeaveNothingOut) {
    TempDir dir;
    spit(dir.file("a.pcd"), labelled());
    const RunResult md = run_shell("@pc_count --markdown " + dir.file("a.pcd"));
    ASSERT_EQ(md.code, 0) << md.err;
    EXPECT_EQ(line_count(md.out), 3);
    EXPECT_EQ(md.out.rfind("| input | count | noise_points |", 0), 0u) << md.out;
    const RunResult text = run_shell("@pc_count --text " + dir.file("a.pcd"));
    EXPECT_NE(text.out.find("\ncount 2\n"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("\nparameters.min-cluster-size 1\n"), std::string::npos);
    EXPECT_EQ(run_shell("@pc_count --csv --markdown " + dir.file("a.pcd")).code, 2);
}

TEST(Reports, FruitcountWritesOneLabelledCloudAnInputByStem) {
    TempDir dir;
    const std::string one = kSamples + "fruit_small.ply";
    const std::string two = kSamples + "plum_bunches_explicit.pcd";
    const RunResult r = run_shell("@pc_fruitcount --plain " + one + " " + two + " --cloud " +
                                  dir.path + "/{stem}_labelled.pcd");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(line_count(r.out), 2);
    for (const char* stem : {"fruit_small", "plum_bunches_explicit"}) {
        const RunResult count =
            run_shell("@pc_count --plain " + dir.path + "/" + stem + "_labelled.pcd");
        EXPECT_EQ(count.code, 0) << count.err;
        EXPECT_NE(r.out.find(count.out), std::string::npos) << stem;
    }
    // Several inputs into one --cloud file would overwrite it: refused before any work.
    const RunResult clash =
        run_shell("@pc_fruitcount " + one + " " + two + " --cloud " + dir.file("x.pcd"));
    EXPECT_EQ(clash.code, 2);
    EXPECT_NE(clash.err.find("{stem}"), std::string::npos);
}

TEST(Reports, TheParallelRecipeGivesTheRowsOfOneProcess) {
    // README's recipe for many trees on all cores (GNU parallel, installed by scripts/setup.sh):
    // JSON Lines concatenate, --keep-order keeps the inputs' order.
    const std::string clouds = kSamples + "fruit_small.ply " + kSamples +
                               "plum_bunches_explicit.pcd " + kSamples + "apple_small_degraded.pcd";
    const RunResult together = run_shell("@pc_fruitcount -q --jsonl " + clouds);
    ASSERT_EQ(together.code, 0) << together.err;
    const RunResult parallel =
        run_shell("parallel -j2 --keep-order @pc_fruitcount -q --jsonl {} ::: " + clouds);
    ASSERT_EQ(parallel.code, 0) << parallel.err;
    const auto a = json_lines(together.out), b = json_lines(parallel.out);
    ASSERT_EQ(a.size(), 3u);
    ASSERT_EQ(b.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(a[k]["input"], b[k]["input"]);
        EXPECT_EQ(a[k]["count"], b[k]["count"]);
        EXPECT_EQ(a[k]["steps"], b[k]["steps"]);
    }
}

TEST(Reports, PlotsAndTheirNumbersBesideThem) {
    TempDir dir;
    const std::string sample = kSamples + "plum_bunches_explicit.pcd";
    const RunResult r =
        run_shell("@pc_fruitcount -q -i " + sample + " --plot " + dir.file("c.png"));
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(slurp(dir.file("c.png")).substr(1, 3), "PNG");
    // The CSV's cluster sizes are the report's clusters' points, in order.
    std::stringstream csv(slurp(dir.file("c.csv")));
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line, "panel,kind,xlabel,name,value");
    for (const auto& c : j["clusters"]) {
        ASSERT_TRUE(std::getline(csv, line));
        EXPECT_EQ(line, "cluster sizes,histogram,points a cluster,," +
                            std::to_string(c["points"].get<int>()));
    }
    const RunResult extent = run_shell("@pc_extent " + sample + " " + kSamples +
                                       "fruit_small.ply --plot " + dir.file("e.png"));
    ASSERT_EQ(extent.code, 0) << extent.err;
    EXPECT_NE(slurp(dir.file("e.csv")).find("points,bars,,fruit_small,5640\n"), std::string::npos);
    // Several inputs need {stem}; a plot is a PNG.
    EXPECT_EQ(run_shell("@pc_count " + sample + " " + sample + " --plot " + dir.file("x.png")).code,
              2);
    EXPECT_EQ(run_shell("@pc_count -i " + sample + " --plot " + dir.file("x.jpg")).code, 2);
    EXPECT_EQ(run_shell("@pc_maskeval " + kSamples + "views/masks " + kSamples +
                        "views/masks --plot " + dir.file("m.png"))
                  .code,
              0);
    EXPECT_NE(slurp(dir.file("m.csv")).find("iou,box,,masks,1\n"), std::string::npos);
    // pc_plot draws the CSV again, after an edit or not: the same picture.
    const RunResult again = run_shell("@pc_plot " + dir.file("c.csv") + " -o " + dir.file("d.png"));
    ASSERT_EQ(again.code, 0) << again.err;
    EXPECT_TRUE(slurp(dir.file("d.png")) == slurp(dir.file("c.png")));
}

TEST(Reports, InstalledToolsRunFromTheirPrefixAndFindPcPlot) {
    // README: `cmake --install build --prefix ~/.local` puts the tools on PATH.
    TempDir dir;
    const std::string build = std::filesystem::path(PC_TOOLS_DIR).parent_path().string();
    const RunResult install =
        run_shell("cmake --install '" + build + "' --prefix '" + dir.path + "' >/dev/null");
    ASSERT_EQ(install.code, 0) << install.err;
    const RunResult r = run_shell("PATH='" + dir.path + "/bin':/usr/bin:/bin; cd '" + dir.path +
                                  "' && pc_fruitcount -q --plain -i " + kSamples +
                                  "fruit_small.ply --plot count.png && pc_info --version");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("pc_info 0."), std::string::npos) << r.out;
    EXPECT_EQ(slurp(dir.file("count.png")).substr(1, 3), "PNG");  // pc_plot beside it drew it
}

TEST(Reports, ExtentGoesOnPastAFailingInput) {
    TempDir dir;
    const RunResult r = run_shell("@pc_extent " + kSamples + "fruit_small.ply " +
                                  dir.file("missing.pcd") + " --markdown");
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(line_count(r.out), 4) << r.out;
    EXPECT_NE(r.out.find("| missing | error: see stderr |"), std::string::npos) << r.out;
    const auto j = nlohmann::json::parse(
        run_shell("@pc_extent " + kSamples + "fruit_small.ply " + dir.file("missing.pcd")).out);
    EXPECT_EQ(j["tool"], "pc_extent");
    EXPECT_TRUE(j["clouds"][1].contains("error"));
    EXPECT_TRUE(j["clouds"][0]["warnings"].empty());
    const auto lines = json_lines(
        run_shell("@pc_extent --jsonl " + kSamples + "fruit_small.ply " + dir.file("missing.pcd"))
            .out);
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[0]["tool"], "pc_extent");
    EXPECT_EQ(lines[0]["points"], 5640);
    EXPECT_TRUE(lines[1].contains("error"));
}

TEST(Reports, CompareWarnsAboutCloudsInDifferentFramesAndEmptySides) {
    const std::string sample = kSamples + "fruit_small.ply";
    const RunResult moved = run_shell("@pc_transform --translate 5,0,0 -i " + sample +
                                      " | @pc_compare " + sample + " -");
    ASSERT_EQ(moved.code, 0) << moved.err;
    EXPECT_NE(moved.err.find("warning: the clouds barely overlap"), std::string::npos) << moved.err;
    const auto j = nlohmann::json::parse(moved.out);
    EXPECT_EQ(j["warnings"].size(), 1u);
    EXPECT_EQ(j["box_overlap"], 0.0);
    // An empty A: B's points are still counted; its distances are undefined, not 0.
    const RunResult empty = run_shell("@pc_compare - " + sample, xyz_header("0", "binary"));
    ASSERT_EQ(empty.code, 0) << empty.err;
    const auto e = nlohmann::json::parse(empty.out);
    EXPECT_EQ(e["b_to_a"]["points"], 5640);
    EXPECT_TRUE(e["b_to_a"]["mean"].is_null());
    EXPECT_NE(empty.err.find("A has no finite point"), std::string::npos);
}

TEST(Reports, ProgressOnAskingAndNeverWithQuiet) {
    const std::string sample = kSamples + "fruit_small.ply";
    const RunResult r = run_shell("@pc_compare --progress " + sample + " " + sample);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("pc_compare: A to B: 5640 distances ["), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("pc_compare: coverage: "), std::string::npos) << r.err;
    EXPECT_EQ(run_shell("@pc_compare " + sample + " " + sample).err, "");  // not a terminal
    EXPECT_EQ(run_shell("@pc_compare -q --progress " + sample + " " + sample).err, "");
}

TEST(Reports, EvalTruthWithAWrongKeySaysWhatWasExpected) {
    TempDir dir;
    spit(dir.file("truth.json"), R"({"fruit": []})");
    const RunResult r =
        run_shell("@pc_eval --truth " + dir.file("truth.json") + " --match centroid", labelled());
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(line_count(r.err), 1);
    EXPECT_EQ(r.err.find("json.exception"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("key 'fruits' not found (expected {\"fruits\": [{\"id\""),
              std::string::npos)
        << r.err;
}

}  // namespace
}  // namespace pc::test
