#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <pc/io/pcd.h>
#include <pc/io/read.h>

#include "support/corpus.h"
#include "support/run_tool.h"
#include "support/synthetic.h"

namespace pc::test {
namespace {

const std::string kSample = std::string(PC_SAMPLE_CLOUDS_DIR) + "/fruit_small.ply";

TEST(PcConvert, WritesBinaryPcdByDefault) {
    const RunResult r = run_shell("@pc_convert -i " + kSample);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("\nDATA binary\n"), std::string::npos);
    EXPECT_EQ(io::parse_cloud(r.out).blob.size(), 5640u);
}

TEST(PcConvert, EveryEncodingThroughPipesGivesTheSameCloud) {
    const RunResult direct = run_shell("@pc_convert -i " + kSample);
    const RunResult chain = run_shell("@pc_convert -i " + kSample +
                                      " --format ascii | @pc_convert --format compressed | "
                                      "@pc_convert --to ply | @pc_convert --to ply --format ascii "
                                      "| @pc_convert");
    ASSERT_EQ(chain.code, 0) << chain.err;
    EXPECT_EQ(chain.out, direct.out);
}

TEST(PcConvert, OutputExtensionPlyWritesPly) {
    TempDir dir;
    const RunResult r = run_shell("@pc_convert -i " + kSample + " -o " + dir.file("a.PLY"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(slurp(dir.file("a.PLY")).rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
}

TEST(PcConvert, CompressedPlyIsAUsageError) {
    const RunResult r = run_shell("@pc_convert -i " + kSample + " --to ply --format compressed");
    EXPECT_EQ(r.code, 2);
    EXPECT_TRUE(r.out.empty());
}

TEST(PcConvert, ClosedPipeIsQuiet) {
    TempDir dir;
    io::StringSink sink;
    io::write_pcd(random_xyz(400000), io::PcdEncoding::kBinary, sink);
    spit(dir.file("big.pcd"), sink.out);
    const RunResult r = run_shell("@pc_convert -i " + dir.file("big.pcd") + " | head -c 10");
    EXPECT_EQ(r.out.size(), 10u);
    EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(PcConvert, HugeClaimFailsAtOnceWithinAMemoryCap) {
    TempDir dir;
    const std::string f = dir.file("liar.pcd");
    spit(f, xyz_header("4000000000", "binary") + floats({1, 2, 3}));
    ASSERT_LT(slurp(f).size(), 250u);
    const RunResult r = run_shell("timeout 5 sh -c '" + memory_cap(300000) + "@pc_convert -i " + f + "'");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("header declares 4000000000 points x 12 B = 48000000000 B, 12 B present"),
              std::string::npos)
        << r.err;
}

TEST(PcConvert, ExistingOutputSurvivesAFailedRun) {
    TempDir dir;
    spit(dir.file("out.pcd"), "precious");
    const RunResult r = run_shell("@pc_convert -o " + dir.file("out.pcd"), "garbage\n");
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(slurp(dir.file("out.pcd")), "precious");
}

TEST(PcConvert, VerboseNotesGoToStderrOnly) {
    const RunResult r = run_shell("@pc_convert -v -i " + kSample + " | @pc_info --text");
    EXPECT_EQ(r.code, 0);
    EXPECT_NE(r.err.find("pc_convert: " + kSample + ": 5640 points, ply binary_little_endian"),
              std::string::npos) << r.err;
    EXPECT_EQ(r.out.rfind("format pcd binary\npoints 5640\n", 0), 0u) << r.out;
}

}  // namespace
}  // namespace pc::test
