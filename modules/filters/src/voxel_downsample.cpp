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

/// Voxel ids in order of each voxel's first point, from m (voxel key, point index) entries sorted
/// by key then index: key_at(s) and index_at(s) read entry s.
template <class KeyAt, class IndexAt>
std::uint32_t number_voxels(std::size_t m, KeyAt key_at, IndexAt index_at, std::vector<std::uint32_t>& voxel) {
    std::size_t runs = 0;
    for (std::size_t s = 0; s < m; ++s) {
        runs += s == 0 || key_at(s) != key_at(s - 1);
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> firsts;  // (first point, run start)
    firsts.reserve(runs);
    for (std::size_t s = 0; s < m; ++s) {
        if (s == 0 || key_at(s) != key_at(s - 1)) {
            firsts.push_back({index_at(s), static_cast<std::uint32_t>(s)});
        }
    }
    std::sort(firsts.begin(), firsts.end());
    for (std::uint32_t v = 0; v < firsts.size(); ++v) {
        std::size_t s = firsts[v].second;
        const auto key = key_at(s);
        for (; s < m && key_at(s) == key; ++s) {
            voxel[index_at(s)] = v;
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
    const auto packed_key = [&](const pcl::PointXYZ& p) {
        return (static_cast<std::uint64_t>(cell(p.x, 0)) << (bits[1] + bits[2])) |
               (static_cast<std::uint64_t>(cell(p.y, 1)) << bits[2]) | static_cast<std::uint64_t>(cell(p.z, 2));
    };
    const int key_bits = bits[0] + bits[1] + bits[2];
    const int index_bits = static_cast<int>(std::bit_width(std::max<std::size_t>(n, 2) - 1));
    if (key_bits + index_bits <= 64) {
        // The usual case: key and point index in one word, 8 bytes a point (pairs of them took
        // 16 with padding, the step's largest block).
        std::vector<std::uint64_t> keyed;
        keyed.reserve(finite);
        for (std::uint32_t i = 0; i < n; ++i) {
            const pcl::PointXYZ p = cloud[i];
            if (is_finite(p)) {
                keyed.push_back((packed_key(p) << index_bits) | i);
            }
        }
        std::sort(keyed.begin(), keyed.end());  // by voxel, then by point index
        const std::uint64_t index_mask = (std::uint64_t{1} << index_bits) - 1;
        r.count = number_voxels(
            keyed.size(), [&](std::size_t s) { return keyed[s] >> index_bits; },
            [&](std::size_t s) { return static_cast<std::uint32_t>(keyed[s] & index_mask); }, r.voxel);
        return r;
    }
    const auto by_pairs = [&](auto key_of) {
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
        return number_voxels(
            keyed.size(), [&](std::size_t s) { return keyed[s].first; }, [&](std::size_t s) { return keyed[s].second; },
            r.voxel);
    };
    if (key_bits <= 64) {
        // Voxel indices are >= 0 and fit: one packed word per key, the same order as (x, y, z).
        r.count = by_pairs(packed_key);
    } else {  // more than 2^64 voxels in the bounding box
        r.count = by_pairs([&](const pcl::PointXYZ& p) {
            return std::tuple<std::int64_t, std::int64_t, std::int64_t>{cell(p.x, 0), cell(p.y, 1), cell(p.z, 2)};
        });
    }
    return r;
}

}  // namespace pc::filters
