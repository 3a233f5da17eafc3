// The memory target (issue 18): pc_dbscan, pc_knn_outlier and pc_fruitcount on the bench's 1M
// canopy (x y z rgb gt_instance, 20 bytes a point) peak at no more than 3x the cloud's bytes +
// 8 MB (the program itself is about 5 MB). The peak is the resident set's high-water mark from
// wait4(), as /usr/bin/time reports it, the median of three runs (heap placement and huge pages
// move one run's peak by 1-3 MB). Skipped in sanitizer builds (shadow memory). bench/run.sh has
// the same rows, and more, beside the peers' figures.
// Not tested here because they sit at the budget or above it (docs/speed-and-memory.md): on the
// same points as x y z only (12 bytes a point) pc_dbscan and pc_knn_outlier peak at 39-42 MB of
// a 43.9 MB budget, and the default `cores` split (pc_fruitcount --no-color) at 4.9x; that
// splitter is being replaced by the counting work (issue 19), whose splitter must do better.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

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

/// The bench's 1M canopy (bench/run.sh, canopy_cloud 1000000 0.0066), made once for the tests
/// below.
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
    }
    static void TearDownTestSuite() {
        delete dir_;
        dir_ = nullptr;
    }
    static std::string canopy() { return dir_->file("canopy.pcd"); }

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
        std::vector<long long> peaks;
        for (int run = 0; run < 3; ++run) {
            peaks.push_back(peak_rss(tool, args, input));
            ASSERT_GT(peaks.back(), 0) << tool << " failed on " << input;
        }
        std::sort(peaks.begin(), peaks.end());
        const long long peak = peaks[1];
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
}

TEST_F(Memory, KnnOutlierOnOneMillionPointsStaysWithinThreeTimesTheCloud) {
    expect_within_budget("pc_knn_outlier", {"--preset", "paper-dense"}, canopy());
}

TEST_F(Memory, FruitcountOnOneMillionPointsStaysWithinThreeTimesTheCloud) {
    expect_within_budget("pc_fruitcount", {}, canopy());
}

}  // namespace
}  // namespace pc::test
