// The memory target (issue 18): pc_dbscan, pc_knn_outlier and pc_fruitcount on 1M points peak at
// no more than 3x the cloud's bytes + 8 MB (the program itself is about 5 MB). The peak is the
// resident set's high-water mark from wait4(), as /usr/bin/time reports it. Two clouds: the bench
// canopy (x y z rgb gt_instance, 20 bytes a point) and the same points as x y z only (12 bytes),
// where any per-point array is a large share of the budget. Skipped in sanitizer builds (shadow
// memory). bench/run.sh has the same rows beside the peers' figures.
// Known miss, not tested here: the default `cores` split on x y z-only input (pc_fruitcount
// --no-color, pc_recursive_split --rule cores on x y z label) peaks at 4-5x; that splitter is
// being replaced by the counting work (issue 19), whose splitter must meet this budget too.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <pc/io/points.h>
#include <pc/io/read.h>

#include "support/run_tool.h"

namespace pc::test {
namespace {

/// Peak resident memory of `tool args... -i input -o /dev/null`, in bytes; -1 when it failed.
long long peak_rss(const std::string& tool,
                   std::vector<std::string> args,
                   const std::string& input) {
    args.insert(args.begin(), tool_path(tool));
    args.insert(args.end(), {"-i", input, "-o", "/dev/null", "-q"});
    std::vector<char*> argv;
    for (auto& a : args) {
        argv.push_back(a.data());
    }
    argv.push_back(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    int status = 0;
    rusage usage{};
    if (pid < 0 || ::wait4(pid, &status, 0, &usage) != pid || !WIFEXITED(status) ||
        WEXITSTATUS(status) != 0) {
        return -1;
    }
    return static_cast<long long>(usage.ru_maxrss) * 1024;  // KiB on Linux
}

/// The bench's 1M canopy (bench/run.sh, canopy_cloud 1000000 0.0066) and its x y z only copy,
/// made once for the tests below.
class Memory : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = new TempDir;
#ifdef PC_SANITIZE
        return;  // nothing is measured (below)
#endif
        const RunResult r = run_shell(
            "@pc_synth --species apple --voxel 0.0066 --fruit-count 1266 --canopy "
            "1.9772,1.9772,1.6477 -o '" +
            canopy() + "'");
        ASSERT_EQ(r.code, 0) << r.err;
        // x y z only: the same points, written by hand as a binary PCD of three F 4 fields.
        const Cloud points = io::xyz(io::read_cloud(canopy()).blob);
        std::ofstream out(xyz(), std::ios::binary);
        out << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH "
            << points.size() << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << points.size()
            << "\nDATA binary\n";
        for (const auto& p : points) {
            out.write(reinterpret_cast<const char*>(&p.x), 12);
        }
    }
    static void TearDownTestSuite() {
        delete dir_;
        dir_ = nullptr;
    }
    static std::string canopy() { return dir_->file("canopy.pcd"); }
    static std::string xyz() { return dir_->file("xyz.pcd"); }

    static void expect_within_budget(const std::string& tool,
                                     const std::vector<std::string>& args,
                                     const std::string& input) {
#ifdef PC_SANITIZE
        GTEST_SKIP() << "peak memory is not measured under the sanitizers";
#endif
        std::ifstream f(input, std::ios::binary | std::ios::ate);
        const auto bytes = static_cast<long long>(f.tellg());
        ASSERT_GT(bytes, 10'000'000);
        const long long budget = 3 * bytes + 8'000'000;
        const long long peak = peak_rss(tool, args, input);
        ASSERT_GT(peak, 0) << tool << " failed on " << input;
        EXPECT_LE(peak, budget) << tool << " peaked at " << peak / 1e6 << " MB on a " << bytes / 1e6
                                << " MB cloud ("
                                << static_cast<double>(peak) / static_cast<double>(bytes)
                                << "x); the budget is " << budget / 1e6 << " MB";
    }

private:
    static inline TempDir* dir_ = nullptr;
};

TEST_F(Memory, DbscanOnOneMillionPointsStaysWithinThreeTimesTheCloud) {
    expect_within_budget("pc_dbscan", {"--preset", "paper-dense"}, canopy());
    expect_within_budget("pc_dbscan", {"--preset", "paper-dense"}, xyz());
}

TEST_F(Memory, KnnOutlierOnOneMillionPointsStaysWithinThreeTimesTheCloud) {
    expect_within_budget("pc_knn_outlier", {"--preset", "paper-dense"}, canopy());
    expect_within_budget("pc_knn_outlier", {"--preset", "paper-dense"}, xyz());
}

TEST_F(Memory, FruitcountOnOneMillionPointsStaysWithinThreeTimesTheCloud) {
    expect_within_budget("pc_fruitcount", {}, canopy());
    expect_within_budget("pc_fruitcount", {"--no-color"}, canopy());
    expect_within_budget("pc_fruitcount", {"--preset", "paper-dense", "--no-color"}, xyz());
}

}  // namespace
}  // namespace pc::test
