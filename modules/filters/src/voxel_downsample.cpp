#include <pc/filters/voxel_downsample.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include <pc/core/error.h>
#include <pc/io/points.h>

namespace pc::filters {

void VoxelParams::validate() const {
    if (!(leaf > 0) || !std::isfinite(leaf)) {
        throw InvalidArgument("voxel_downsample: leaf must be > 0, got " + format_number(leaf));
    }
}

VoxelResult voxel_downsample(const Cloud& cloud, const VoxelParams& params) {
    params.validate();
    const std::size_t n = cloud.size();
    VoxelResult r;
    r.voxel.assign(n, io::kNoGroup);
    double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                    std::numeric_limits<double>::infinity()};
    for (const auto& p : cloud.points) {
        if (is_finite(p)) {
            lo[0] = std::min(lo[0], double{p.x});
            lo[1] = std::min(lo[1], double{p.y});
            lo[2] = std::min(lo[2], double{p.z});
        }
    }
    using Key = std::tuple<std::int64_t, std::int64_t, std::int64_t>;
    std::vector<std::pair<Key, std::uint32_t>> keyed;
    keyed.reserve(n);
    for (std::uint32_t i = 0; i < n; ++i) {
        const auto& p = cloud[i];
        if (!is_finite(p)) {
            continue;
        }
        const auto cell = [&](double v, int a) {
            return static_cast<std::int64_t>(std::floor((v - (lo[a] - params.leaf / 2)) / params.leaf));
        };
        keyed.push_back({{cell(p.x, 0), cell(p.y, 1), cell(p.z, 2)}, i});
    }
    std::sort(keyed.begin(), keyed.end());  // by voxel, then by point index
    // Voxel ids in order of each voxel's first point.
    std::vector<std::pair<std::uint32_t, std::size_t>> firsts;  // (first point, run start)
    for (std::size_t s = 0; s < keyed.size(); ++s) {
        if (s == 0 || keyed[s].first != keyed[s - 1].first) {
            firsts.push_back({keyed[s].second, s});
        }
    }
    std::sort(firsts.begin(), firsts.end());
    for (std::uint32_t v = 0; v < firsts.size(); ++v) {
        std::size_t s = firsts[v].second;
        const Key key = keyed[s].first;
        for (; s < keyed.size() && keyed[s].first == key; ++s) {
            r.voxel[keyed[s].second] = v;
        }
    }
    r.count = static_cast<std::uint32_t>(firsts.size());
    return r;
}

}  // namespace pc::filters
