// Steady-state timing of dbscan() on one cloud, in one process (no start-up, reading or
// first-touch page faults): the way to see a 5 % change, which whole-tool runs on this VM cannot
// (see docs/performance.md).
//   build-bench/bin/dbscan_loop CLOUD [EPS [MIN_POINTS [RUNS]]]
// prints the minimum and median of RUNS (default 21) of dbscan() over the cloud's records, grid
// build (sorting thin records in place or copying rich ones, as pc_dbscan does) and restoring
// included, and the cluster count.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include <pc/cli/tool.h>
#include <pc/io/points.h>
#include <pc/io/read.h>
#include <pc/segmentation/dbscan.h>

namespace {

double seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: dbscan_loop CLOUD [EPS [MIN_POINTS [RUNS]]]\n");
        return 2;
    }
    pc::cli::tune_allocator();  // as the tools run
    const double eps = argc > 2 ? std::atof(argv[2]) : 0.015;
    const auto min_points = static_cast<std::uint32_t>(argc > 3 ? std::atoi(argv[3]) : 10);
    const int runs = std::max(1, argc > 4 ? std::atoi(argv[4]) : 21);
    try {
        pc::io::Blob blob = pc::io::read_cloud(argv[1], std::uint64_t{1} << 40).blob;
        pc::io::XyzSortable points(blob);
        std::vector<double> t;
        std::uint32_t clusters = 0;
        for (int r = 0; r < runs; ++r) {
            const double t0 = seconds();
            const auto result =
                pc::segmentation::dbscan(points.records(), {.eps = eps, .min_points = min_points});
            t.push_back(seconds() - t0);
            clusters = result.cluster_count;
        }
        std::sort(t.begin(), t.end());
        std::printf("dbscan min %.1f ms median %.1f ms | %u clusters, %zu points, %d runs\n",
                    t.front() * 1e3, t[t.size() / 2] * 1e3, clusters, blob.size(), runs);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "dbscan_loop: %s\n", e.what());
        return 1;
    }
    return 0;
}
