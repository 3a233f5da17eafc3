// The CLI contract (docs/architecture.md), checked on every tool through real processes and pipes.
#include <cctype>
#include <filesystem>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include <pc/io/pcd.h>

#include "support/corpus.h"
#include "support/run_tool.h"

namespace pc::test {
namespace {

std::vector<std::string> all_tools() {
    std::vector<std::string> out;
    std::stringstream ss(PC_TOOL_LIST);
    for (std::string t; std::getline(ss, t, ',');) {
        out.push_back(t);
    }
    return out;
}

/// A small valid cloud every tool accepts (x y z, bright rgb, label).
std::string valid_cloud() {
    return pcd_header("x y z rgb label", "4 4 4 4 4", "F F F U U", "1 1 1 1 1", "3", "3", "ascii") +
           "0 0 0 16777215 1\n0.001 0 0 16777215 1\n0 0.001 0 16777215 1\n";
}

/// What a tool needs on its command line besides the cloud it reads: pc_compare also takes the
/// reference cloud B (its A is stdin or -i); pc_eval scores `label` against itself; pc_synth makes
/// a tiny scene; pc_range a range on x; pc_groupby a folder for its files; pc_lift takes the
/// shipped view sample's cameras and masks, pc_maskeval its masks twice.
std::string extra_args(const std::string& tool) {
    if (tool == "pc_compare") {
        return " " + std::string(PC_SAMPLE_CLOUDS_DIR) + "/fruit_small.ply";
    }
    if (tool == "pc_eval") {
        return " --gt-field label";
    }
    if (tool == "pc_synth") {
        return " --fruit-count 3 --canopy 0.2,0.2,0.2";
    }
    if (tool == "pc_maskeval") {
        const std::string masks = std::string(PC_SAMPLE_CLOUDS_DIR) + "/views/masks";
        return " " + masks + " " + masks;
    }
    if (tool == "pc_plot") {  // a one-bar plot's CSV, written where the shell says
        return " \"$(f=$(mktemp); printf 'panel,kind,xlabel,name,value\\nt,bars,,a,1\\n' >\"$f\"; "
               "echo \"$f\")\"";
    }
    if (tool == "pc_groupby") {
        return " --pattern \"$(mktemp -d)/c_#.pcd\"";  // its files out of the test's folder
    }
    if (tool == "pc_range") {
        return " --limits 'x[:]'";
    }
    if (tool == "pc_lift") {
        return " --cameras " + std::string(PC_SAMPLE_CLOUDS_DIR) + "/views/transforms.json";
    }
    return "";
}

/// Tools that read no cloud: they make one (pc_synth), read folders of images (pc_maskeval) or a
/// plot's CSV (pc_plot).
bool generator(const std::string& tool) {
    return tool == "pc_synth" || tool == "pc_maskeval" || tool == "pc_plot";
}

/// Tools whose job is the format itself: every edge-case file must pass through them.
bool format_tool(const std::string& tool) { return tool == "pc_info" || tool == "pc_convert"; }

class Contract : public ::testing::TestWithParam<std::string> {};

TEST(Docs, LinksPointIntoTheRepository) {
    // A new user found links to ../shared/... files that the repository does not have.
    const std::filesystem::path root = std::filesystem::path(PC_DOCS_DIR).parent_path();
    std::vector<std::filesystem::path> pages = {root / "README.md", root / "CONTRIBUTING.md"};
    for (const auto& e : std::filesystem::recursive_directory_iterator(root / "docs")) {
        if (e.path().extension() == ".md") {
            pages.push_back(e.path());
        }
    }
    int links = 0;
    for (const auto& page : pages) {
        const std::string text = slurp(page.string());
        EXPECT_EQ(text.find("../shared"), std::string::npos) << page;
        for (std::size_t at = 0; (at = text.find("](", at)) != std::string::npos; ++at) {
            const std::size_t end = text.find(')', at);
            std::string target = text.substr(at + 2, end - at - 2);
            target = target.substr(0, target.find('#'));
            if (target.empty() || target.find("://") != std::string::npos) {
                continue;
            }
            ++links;
            EXPECT_TRUE(std::filesystem::exists(page.parent_path() / target))
                << page << " links to " << target;
        }
    }
    EXPECT_GT(links, 30);  // the README's tool table alone has more
}

TEST_P(Contract, EveryOptionOfItsOwnIsOnItsDocPage) {
    // The options every tool has are on docs/architecture.md; a tool's own options on its page.
    const std::set<std::string> common = {"help",    "version", "input",           "output",
                                          "verbose", "quiet",   "max-input-bytes", "progress",
                                          "format",  "to",      "ply-scalars"};
    const std::string page = slurp(std::string(PC_DOCS_DIR) + "/tools/" + GetParam() + ".md");
    std::stringstream help(run_shell("@" + GetParam() + " --help").out);
    for (std::string line; std::getline(help, line);) {
        const std::size_t at = line.find("--");
        // Option lines start with "  --name" or "  -i [ --name ]".
        if (at == std::string::npos || line.find_first_not_of(" -i[o]vqh", 0) < at) {
            continue;
        }
        std::size_t end = at + 2;
        while (end < line.size() &&
               (std::isalnum(static_cast<unsigned char>(line[end])) || line[end] == '-')) {
            ++end;
        }
        const std::string name = line.substr(at + 2, end - at - 2);
        if (!name.empty() && common.count(name) == 0) {
            EXPECT_NE(page.find("--" + name), std::string::npos)
                << "--" << name << " is not on docs/tools/" << GetParam() << ".md";
        }
    }
}

TEST_P(Contract, HelpGoesToStdoutAndExitsZero) {
    const RunResult r = run_shell("@" + GetParam() + " --help");
    EXPECT_EQ(r.code, 0);
    EXPECT_NE(r.out.find(GetParam()), std::string::npos);
    EXPECT_EQ(r.out.find("--input") != std::string::npos, !generator(GetParam()));
    EXPECT_NE(r.out.find("--output"), std::string::npos);
    EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST_P(Contract, GeneratorsRefuseAnInput) {
    if (!generator(GetParam())) {
        GTEST_SKIP() << "reads a cloud";
    }
    const RunResult r = run_shell("@" + GetParam() + " -i x.pcd" + extra_args(GetParam()));
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_TRUE(r.out.empty());
}

TEST_P(Contract, VersionExitsZero) {
    const RunResult r = run_shell("@" + GetParam() + " --version");
    EXPECT_EQ(r.code, 0);
    EXPECT_EQ(line_count(r.out), 1);
}

TEST_P(Contract, UnknownOptionIsAUsageErrorOnOneLine) {
    const RunResult r =
        run_shell("@" + GetParam() + " --bogus" + extra_args(GetParam()), valid_cloud());
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind(GetParam() + ": error: ", 0), 0u) << r.err;
    EXPECT_TRUE(r.out.empty());
}

TEST_P(Contract, UnparsableValueIsAUsageError) {
    const std::string option = GetParam() == "pc_synth"      ? " --seed lots"
                               : GetParam() == "pc_maskeval" ? " --kind lots"
                                                             : " --max-input-bytes lots";
    const RunResult r =
        run_shell("@" + GetParam() + option + extra_args(GetParam()), valid_cloud());
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(line_count(r.err), 1) << r.err;
}

TEST_P(Contract, TruncatedCloudOnStdinFailsWithOneLineNamingStdin) {
    if (generator(GetParam())) {
        GTEST_SKIP() << "reads no cloud";
    }
    const RunResult r = run_shell("@" + GetParam() + extra_args(GetParam()),
                                  xyz_header("100", "binary") + floats({1, 2, 3}));
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("<stdin>: truncated binary body"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty());
}

/// Whether every line of `err` is a warning of `tool` (a valid input whose result is doubtful:
/// the only thing a successful run may print without -v).
bool only_warnings(const std::string& err, const std::string& tool) {
    std::istringstream lines(err);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind(tool + ": warning: ", 0) != 0) {
            return false;
        }
    }
    return true;
}

TEST_P(Contract, ValidCloudSucceedsWithNothingButWarnings) {
    // Three points: DBSCAN's default min_points leaves them all noise, which is worth a warning.
    const RunResult r = run_shell("@" + GetParam() + extra_args(GetParam()), valid_cloud());
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(only_warnings(r.err, GetParam())) << r.err;
    EXPECT_FALSE(r.out.empty());
    const RunResult quiet =
        run_shell("@" + GetParam() + " -q" + extra_args(GetParam()), valid_cloud());
    EXPECT_TRUE(quiet.err.empty()) << quiet.err;
}

TEST_P(Contract, EveryMalformedInputFailsCleanlyByPathAndByPipe) {
    if (generator(GetParam())) {
        GTEST_SKIP() << "reads no cloud";
    }
    TempDir dir;
    for (const auto& m : malformed_corpus()) {
        const std::string in = dir.file(m.name + ".in");
        spit(in, m.bytes);
        const std::string out = dir.file("out.pcd");
        for (const bool by_path : {true, false}) {
            const std::string cmd = (by_path ? "@" + GetParam() + " -i " + in + " -o " + out
                                             : "cat " + in + " | @" + GetParam() + " -o " + out) +
                                    extra_args(GetParam());
            const RunResult r = run_shell("timeout 10 sh -c '" + memory_cap(4000000) + cmd + "'");
            EXPECT_EQ(r.code, 1) << m.name << (by_path ? " by path: " : " by pipe: ") << r.err;
            EXPECT_EQ(line_count(r.err), 1) << m.name << ": " << r.err;
            EXPECT_NE(r.err.find(by_path ? in + ": " : std::string("<stdin>: ")), std::string::npos)
                << m.name << ": " << r.err;
            EXPECT_FALSE(std::filesystem::exists(out)) << m.name;
        }
        std::filesystem::remove(in);
        EXPECT_TRUE(std::filesystem::is_empty(dir.path)) << m.name << ": a temporary file was left";
    }
}

TEST_P(Contract, EdgeCaseInputsAreAcceptedOrRefusedCleanly) {
    if (generator(GetParam())) {
        GTEST_SKIP() << "reads no cloud";
    }
    // Format tools accept every edge case; algorithm tools may refuse one that lacks what they
    // need (colour, label), with exit 1 and one line, never a crash.
    for (const auto& e : edge_corpus()) {
        const RunResult r = run_shell("@" + GetParam() + extra_args(GetParam()), e.bytes);
        if (format_tool(GetParam())) {
            EXPECT_EQ(r.code, 0) << e.name << ": " << r.err;
            EXPECT_TRUE(r.err.empty()) << e.name << ": " << r.err;
        } else {
            EXPECT_TRUE(r.code == 0 || r.code == 1) << e.name << ": exit " << r.code;
            if (r.code == 0) {
                EXPECT_TRUE(only_warnings(r.err, GetParam())) << e.name << ": " << r.err;
            } else {
                EXPECT_EQ(line_count(r.err), 1) << e.name << ": " << r.err;
            }
        }
    }
}

TEST_P(Contract, DirectoryInputIsRejected) {
    if (generator(GetParam())) {
        GTEST_SKIP() << "reads no cloud";
    }
    const RunResult r = run_shell("@" + GetParam() + " -i /tmp" + extra_args(GetParam()));
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, GetParam() + ": error: /tmp: is a directory\n");
}

TEST_P(Contract, HasADocPage) {
    EXPECT_TRUE(std::filesystem::exists(std::string(PC_DOCS_DIR) + "/tools/" + GetParam() + ".md"));
}

INSTANTIATE_TEST_SUITE_P(Tools, Contract, ::testing::ValuesIn(all_tools()), [](const auto& p) {
    return p.param;
});

}  // namespace
}  // namespace pc::test
