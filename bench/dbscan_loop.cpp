// Steady-state timing of the grid build and dbscan() on one cloud, in one process (no start-up,
// reading or first-touch page faults): the way to see a 5 % change to either, which whole-tool
// runs on this VM cannot (see CONTRIBUTING, "Speed and memory").
//   build-bench/bin/dbscan_loop CLOUD [EPS [MIN_POINTS [RUNS]]]
// prints the minimum and median of RUNS (default 21) for each, and the cluster count.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <pc/cli/tool.h>
#include <pc/io/points.h>
#include <pc/io/read.h>
#include <pc/search/grid.h>
#include <pc/segmentation/dbscan.h>

namespace {

double seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void report(const char* what, std::vector<double> t) {
    std::sort(t.begin(), t.end());
    std::printf("%s min %.1f ms median %.1f ms | ", what, t.front() * 1e3, t[t.size() / 2] * 1e3);
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
        const pc::io::Blob blob = pc::io::read_cloud(argv[1], std::uint64_t{1} << 40).blob;
        std::vector<double> grid_t, dbscan_t;
        std::uint32_t clusters = 0;
        for (int r = 0; r < runs; ++r) {
            const pc::io::XyzPoints points(blob);
            const double t0 = seconds();
            pc::search::Grid grid(points.view(), eps);
            grid.release_cloud();
            const double t1 = seconds();
            const auto result = pc::segmentation::dbscan(grid, blob.size(), {.eps = eps, .min_points = min_points});
            grid_t.push_back(t1 - t0);
            dbscan_t.push_back(seconds() - t1);
            clusters = result.cluster_count;
        }
        report("grid", grid_t);
        report("dbscan", dbscan_t);
        std::printf("%u clusters, %zu points, %d runs\n", clusters, blob.size(), runs);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "dbscan_loop: %s\n", e.what());
        return 1;
    }
    return 0;
}
