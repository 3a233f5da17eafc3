#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <tuple>
#include <type_traits>
#include <vector>

#include <pc/core/error.h>
#include <pc/filters/voxel_downsample.h>
#include <pc/io/points.h>

namespace pc::filters {

void VoxelParams::validate() const {
    if (!(leaf > 0) || !std::isfinite(leaf)) {
        throw InvalidArgument("voxel_downsample: leaf must be > 0, got " + format_number(leaf));
    }
}

namespace {

/// Voxel ids in order of each voxel's first point, from the (voxel key, point index) entries of
/// `keyed` sorted by key then index: key_at(s) and index_at(s) read entry s. Each point first
/// gets its run's number (runs in key order); `keyed` is then freed, and one pass over the
/// points in index order renumbers the runs as first met (4 bytes a run; a table of (first
/// point, run) pairs sorted by point, 8 bytes a run, was the step's peak beside the entries).
template <class Entries, class KeyAt, class IndexAt>
std::uint32_t number_voxels(Entries&& keyed,
                            KeyAt key_at,
                            IndexAt index_at,
                            std::vector<std::uint32_t>& voxel) {
    const std::size_t m = keyed.size();
    std::uint32_t runs = 0;
    for (std::size_t s = 0; s < m; ++s) {
        runs += s > 0 && key_at(s) != key_at(s - 1);
        voxel[index_at(s)] = runs;
    }
    runs += m > 0;
    std::remove_reference_t<Entries>().swap(keyed);
    std::vector<std::uint32_t> id(runs, io::kNoGroup);
    std::uint32_t next = 0;
    for (auto& v : voxel) {
        if (v != io::kNoGroup) {
            if (id[v] == io::kNoGroup) {
                id[v] = next++;
            }
            v = id[v];
        }
    }
    return next;
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
        bits[a] = static_cast<int>(
            std::bit_width(static_cast<std::uint64_t>(cell(hi[a], a))));  // cell(hi) >= 0
    }
    const auto packed_key = [&](const pcl::PointXYZ& p) {
        return (static_cast<std::uint64_t>(cell(p.x, 0)) << (bits[1] + bits[2])) |
               (static_cast<std::uint64_t>(cell(p.y, 1)) << bits[2]) |
               static_cast<std::uint64_t>(cell(p.z, 2));
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
            keyed, [&](std::size_t s) { return keyed[s] >> index_bits; },
            [&](std::size_t s) { return static_cast<std::uint32_t>(keyed[s] & index_mask); },
            r.voxel);
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
            keyed, [&](std::size_t s) { return keyed[s].first; },
            [&](std::size_t s) { return keyed[s].second; }, r.voxel);
    };
    if (key_bits <= 64) {
        // Voxel indices are >= 0 and fit: one packed word per key, the same order as (x, y, z).
        r.count = by_pairs(packed_key);
    } else {  // more than 2^64 voxels in the bounding box
        r.count = by_pairs([&](const pcl::PointXYZ& p) {
            return std::tuple<std::int64_t, std::int64_t, std::int64_t>{cell(p.x, 0), cell(p.y, 1),
                                                                        cell(p.z, 2)};
        });
    }
    return r;
}

}  // namespace pc::filters
