#include <filesystem>

#include <sys/stat.h>
#include <unistd.h>

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

TEST(PcConvert, TextOutByExtensionAndOtherFormatsRefusedBeforeAnyWork) {
    TempDir dir;
    const RunResult r = run_shell("@pc_convert -i " + kSample + " -o " + dir.file("a.xyz"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(slurp(dir.file("a.xyz")).rfind("//X Y Z R G B\n", 0), 0u);
    // A float cloud read back: the same cloud, bit for bit (the sample PLY's doubles would come
    // back as floats: text has no types).
    const std::string floats = std::string(PC_SAMPLE_CLOUDS_DIR) + "/plum_bunches_explicit.pcd";
    ASSERT_EQ(run_shell("@pc_convert -i " + floats + " -o " + dir.file("b.xyz")).code, 0);
    EXPECT_TRUE(run_shell("@pc_convert -i " + dir.file("b.xyz")).out ==
                run_shell("@pc_convert -i " + floats).out);
    // PCD bytes under a .las name would be a file that every LAS reader refuses: say so instead.
    const RunResult las = run_shell("@pc_convert -i " + kSample + " -o " + dir.file("a.las"));
    EXPECT_EQ(las.code, 2);
    EXPECT_NE(las.err.find("not .las"), std::string::npos) << las.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("a.las")));
    EXPECT_EQ(run_shell("@pc_convert -i " + kSample + " --to pcd -o " + dir.file("a.las")).code, 0);
    EXPECT_EQ(slurp(dir.file("a.las")).rfind("# .PCD", 0), 0u);
    // --cloud follows the same rule, checked before the chain runs.
    EXPECT_EQ(run_shell("@pc_fruitcount -i " + kSample + " --cloud " + dir.file("c.laz")).code, 2);
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
    const RunResult r =
        run_shell("timeout 5 sh -c '" + memory_cap(300000) + "@pc_convert -i " + f + "'");
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

TEST(PcConvert, OutputToAFifoIsWrittenThroughNotReplaced) {
    // -o /dev/null once renamed a temporary file over the device (as root). A FIFO stands for
    // any existing non-regular file: it must stay a FIFO and its reader must get the cloud.
    TempDir dir;
    const std::string fifo = dir.file("pipe");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const RunResult r = run_shell("timeout 20 cat " + fifo + " > " + dir.file("got") +
                                  " & @pc_convert -i " + kSample + " -o " + fifo + "; wait");
    EXPECT_EQ(r.code, 0) << r.err;
    struct stat st {};
    ASSERT_EQ(::stat(fifo.c_str(), &st), 0);
    EXPECT_TRUE(S_ISFIFO(st.st_mode));
    EXPECT_NE(run_shell("@pc_info --text -i " + dir.file("got"))
                  .out.find("\nformat pcd binary\npoints 5640\n"),
              std::string::npos);
}

TEST(PcConvert, OutputThroughASymlinkReplacesItsTargetAndKeepsPermissions) {
    TempDir dir;
    spit(dir.file("target.pcd"), "old");
    ASSERT_EQ(::chmod(dir.file("target.pcd").c_str(), 0640), 0);
    ASSERT_EQ(::symlink(dir.file("target.pcd").c_str(), dir.file("link.pcd").c_str()), 0);
    const RunResult r = run_shell("@pc_convert -i " + kSample + " -o " + dir.file("link.pcd"));
    EXPECT_EQ(r.code, 0) << r.err;
    struct stat st {};
    ASSERT_EQ(::lstat(dir.file("link.pcd").c_str(), &st), 0);
    EXPECT_TRUE(S_ISLNK(st.st_mode));  // the link stays a link
    ASSERT_EQ(::stat(dir.file("target.pcd").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, 0640u);  // the file keeps its permissions
    EXPECT_NE(run_shell("@pc_info --text -i " + dir.file("target.pcd"))
                  .out.find("\nformat pcd binary\npoints 5640\n"),
              std::string::npos);
    EXPECT_NE(run_shell("@pc_convert -i " + kSample + " -o " + dir.path).code,
              0);  // a directory is refused
}

TEST(PcConvert, VerboseNotesGoToStderrOnly) {
    const RunResult r = run_shell("@pc_convert -v -i " + kSample + " | @pc_info --text");
    EXPECT_EQ(r.code, 0);
    EXPECT_NE(r.err.find("pc_convert: " + kSample + ": 5640 points, ply binary_little_endian"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.out.find("\nformat pcd binary\npoints 5640\n"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace pc::test
