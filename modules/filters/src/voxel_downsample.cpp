#include <pc/filters/voxel_downsample.h>

#include <algorithm>
#include <bit>
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

namespace {

/// Voxel ids in order of each voxel's first point, from (voxel key, point index) pairs sorted by
/// key then index.
template <class Keyed>
std::uint32_t number_voxels(const std::vector<Keyed>& keyed, std::vector<std::uint32_t>& voxel) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> firsts;  // (first point, run start)
    for (std::size_t s = 0; s < keyed.size(); ++s) {
        if (s == 0 || keyed[s].first != keyed[s - 1].first) {
            firsts.push_back({keyed[s].second, static_cast<std::uint32_t>(s)});
        }
    }
    std::sort(firsts.begin(), firsts.end());
    for (std::uint32_t v = 0; v < firsts.size(); ++v) {
        std::size_t s = firsts[v].second;
        const auto key = keyed[s].first;
        for (; s < keyed.size() && keyed[s].first == key; ++s) {
            voxel[keyed[s].second] = v;
        }
    }
    return static_cast<std::uint32_t>(firsts.size());
}

}  // namespace

VoxelResult voxel_downsample(const XyzView& cloud, const VoxelParams& params) {
    params.validate();
    const std::size_t n = cloud.size;
    VoxelResult r;
    r.voxel.assign(n, io::kNoGroup);
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        lo[a] = std::numeric_limits<double>::infinity();
        hi[a] = -lo[a];
    }
    std::size_t finite = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const pcl::PointXYZ p = cloud[i];
        if (is_finite(p)) {
            ++finite;
            const double v[3] = {p.x, p.y, p.z};
            for (int a = 0; a < 3; ++a) {
                lo[a] = std::min(lo[a], v[a]);
                hi[a] = std::max(hi[a], v[a]);
            }
        }
    }
    const auto cell = [&](double v, int a) {
        return static_cast<std::int64_t>(std::floor((v - (lo[a] - params.leaf / 2)) / params.leaf));
    };
    int bits[3] = {0, 0, 0};
    for (int a = 0; a < 3 && finite > 0; ++a) {
        bits[a] = static_cast<int>(std::bit_width(static_cast<std::uint64_t>(cell(hi[a], a))));  // cell(hi) >= 0
    }
    const auto sorted = [&](auto key_of) {
        using Key = decltype(key_of(pcl::PointXYZ{}));
        std::vector<std::pair<Key, std::uint32_t>> keyed;
        keyed.reserve(finite);
        for (std::uint32_t i = 0; i < n; ++i) {
            const pcl::PointXYZ p = cloud[i];
            if (is_finite(p)) {
                keyed.push_back({key_of(p), i});
            }
        }
        std::sort(keyed.begin(), keyed.end());  // by voxel, then by point index
        return keyed;
    };
    if (bits[0] + bits[1] + bits[2] <= 64) {
        // Voxel indices are >= 0 and fit: one packed word per key, the same order as (x, y, z).
        r.count = number_voxels(sorted([&](const pcl::PointXYZ& p) {
                                    return (static_cast<std::uint64_t>(cell(p.x, 0)) << (bits[1] + bits[2])) |
                                           (static_cast<std::uint64_t>(cell(p.y, 1)) << bits[2]) |
                                           static_cast<std::uint64_t>(cell(p.z, 2));
                                }),
                                r.voxel);
    } else {  // more than 2^64 voxels in the bounding box
        r.count = number_voxels(sorted([&](const pcl::PointXYZ& p) {
                                    return std::tuple<std::int64_t, std::int64_t, std::int64_t>{
                                        cell(p.x, 0), cell(p.y, 1), cell(p.z, 2)};
                                }),
                                r.voxel);
    }
    return r;
}

}  // namespace pc::filters
