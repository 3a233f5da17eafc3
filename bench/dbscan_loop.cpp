// Steady-state timing of the grid build and dbscan() on one cloud, in one process (no start-up,
// reading or first-touch page faults): the way to see a 5 % change to either, which whole-tool
// runs on this VM cannot (see CONTRIBUTING, "Speed and memory").
//   build-bench/bin/dbscan_loop CLOUD [EPS [MIN_POINTS [RUNS [copy|inplace]]]]
// prints the minimum and median of RUNS (default 21) for each, and the cluster count. `inplace`
// (pc_dbscan's way for clouds with F 4 x y z) sorts the cloud's own records into the grid and
// also times putting them back; `copy` (the default) builds the grid from a sorted copy.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <stdexcept>
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
    const bool in_place = argc > 5 && std::string(argv[5]) == "inplace";
    try {
        pc::io::Blob blob = pc::io::read_cloud(argv[1], std::uint64_t{1} << 40).blob;
        const auto records = pc::io::xyz_records(blob);
        if (in_place && !records) {
            throw std::runtime_error("inplace needs F 4 x y z at consecutive offsets");
        }
        std::vector<double> grid_t, dbscan_t, restore_t;
        std::uint32_t clusters = 0;
        for (int r = 0; r < runs; ++r) {
            const pc::io::XyzPoints points(blob);
            const double t0 = seconds();
            std::optional<pc::search::Grid> grid;
            if (in_place) {
                grid.emplace(pc::search::Grid::kInPlace, *records, eps);
            } else {
                grid.emplace(points.view(), eps);
                grid->release_cloud();
            }
            const double t1 = seconds();
            const auto result = pc::segmentation::dbscan(*grid, blob.size(), {.eps = eps, .min_points = min_points});
            const double t2 = seconds();
            if (in_place) {
                grid->restore_order(*records);
            }
            grid_t.push_back(t1 - t0);
            dbscan_t.push_back(t2 - t1);
            restore_t.push_back(seconds() - t2);
            clusters = result.cluster_count;
        }
        report("grid", grid_t);
        report("dbscan", dbscan_t);
        if (in_place) {
            report("restore", restore_t);
        }
        std::printf("%u clusters, %zu points, %d runs\n", clusters, blob.size(), runs);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "dbscan_loop: %s\n", e.what());
        return 1;
    }
    return 0;
}
