#include <pc/search/grid.h>

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <numeric>
#include <span>
#include <stdexcept>
#include <tuple>
#include <type_traits>

#include <omp.h>

#include <pc/core/error.h>
#include <pc/core/stats.h>

namespace pc::search {

namespace {

constexpr std::int64_t kAxisCells = std::int64_t{1} << 21;  // 21 bits per axis in a 63-bit key

/// LSD radix sort of n (key, index) pairs, 12 bits per pass, skipping passes where all digits
/// agree. Keys are 32-bit when the cell key fits (nearly always): half the bytes to move and hold.
/// `k2` and `i2` are scratch of n entries each; the sorted pairs end in either array of each
/// pair, which is returned. Each pass runs on two threads (each counts and moves its half of the
/// input; its elements go after the first half's within every digit): stable, so the result is
/// the serial sort's.
template <class Key>
std::pair<Key*, std::uint32_t*> radix_sort(Key* keys, std::uint32_t* idx, Key* k2, std::uint32_t* i2, std::size_t n) {
    Key all_or = 0, all_and = static_cast<Key>(~Key{0});
    for (std::size_t i = 0; i < n; ++i) {
        all_or |= keys[i];
        all_and &= keys[i];
    }
    const Key varying = all_or ^ all_and;
    constexpr std::size_t kDigits = 4096;
    const int threads = n >= (std::size_t{1} << 16) ? 2 : 1;  // small inputs: not worth a thread
    std::vector<std::size_t> count(kDigits * static_cast<std::size_t>(threads));
    for (int shift = 0; shift < static_cast<int>(8 * sizeof(Key)); shift += 12) {
        if (((varying >> shift) & 0xfff) == 0) {
            continue;
        }
        std::fill(count.begin(), count.end(), 0);
#pragma omp parallel num_threads(threads)
        {
            // The team may be smaller than asked (nested in another parallel region, a limit).
            const auto parts = static_cast<std::size_t>(omp_get_num_threads());
            const auto part = static_cast<std::size_t>(omp_get_thread_num());
            const std::size_t from = n * part / parts;
            const std::size_t to = n * (part + 1) / parts;
            std::size_t* mine = &count[kDigits * part];
            for (std::size_t i = from; i < to; ++i) {
                ++mine[(keys[i] >> shift) & 0xfff];
            }
#pragma omp barrier
#pragma omp single
            {
                // Digit-major, part-minor starting offsets.
                std::size_t at = 0;
                for (std::size_t d = 0; d < kDigits; ++d) {
                    for (std::size_t p = 0; p < parts; ++p) {
                        const std::size_t c = count[kDigits * p + d];
                        count[kDigits * p + d] = at;
                        at += c;
                    }
                }
            }
            for (std::size_t i = from; i < to; ++i) {
                const std::size_t at = mine[(keys[i] >> shift) & 0xfff]++;
                k2[at] = keys[i];
                i2[at] = idx[i];
            }
        }
        std::swap(keys, k2);
        std::swap(idx, i2);
    }
    return {keys, idx};
}

/// A 32-bit word that may alias a float: the sort's keys and scratch live in the coordinates'
/// storage until the coordinates are written there.
using Word = std::uint32_t __attribute__((may_alias));

/// Sorts n records of `step` bytes (a multiple of 4) at `rec` in place by keys[i], carrying keys
/// and, when kTagged, tags along. Untagged, the keys must be distinct (the records' original
/// indices: putting them back). Not stable. American flag sort (in-place MSD radix, 8 bits a
/// level) until a bucket fits in the cache; a bucket's (key, position) pairs are then sorted
/// aside and the records moved once each by walking the permutation's cycles. Every move thus
/// lands at one of 256 advancing places or inside a cached bucket: applying the whole
/// permutation by its cycles instead took 0.4 s for 4M points here (20 ms for 1M, which fit in
/// the cache). Buckets of the first level are sorted on two threads.
template <class Key, std::size_t kWords, bool kTagged>
void flag_sort_impl(std::uint8_t* rec, std::size_t step, Key* keys, std::uint32_t* tags, std::size_t n) {
    const std::size_t words = kWords != 0 ? kWords : step / sizeof(Word);
    const auto swap_words = [&](Word* a, Word* b) {
        for (std::size_t w = 0; w < words; ++w) {
            const std::uint32_t t = a[w];
            a[w] = b[w];
            b[w] = t;
        }
    };
    const auto swap = [&](std::size_t i, std::size_t j) {
        swap_words(reinterpret_cast<Word*>(rec + i * step), reinterpret_cast<Word*>(rec + j * step));
        std::swap(keys[i], keys[j]);
        if constexpr (kTagged) {
            std::swap(tags[i], tags[j]);
        }
    };
    // A bucket of at most kLeaf records (about 200 KiB for x y z only, and 200 KiB of positions)
    // is sorted aside, then permuted.
    constexpr std::size_t kLeaf = 16384;
    const auto leaf = [&](std::size_t lo, std::size_t hi) {
        // dest[i]: where the record at lo + i goes. Distinct keys spanning m values (untagged:
        // original indices) are placed directly; other keys (repeated cell keys may span m
        // values too) by an LSD radix sort of their positions over the key bits that vary.
        thread_local std::vector<std::uint32_t> dest, pos, pos2;
        const std::size_t m = hi - lo;
        if (m < 2) {
            return;  // nothing to move (and keys[lo] may be past the end)
        }
        dest.resize(m);
        Key kmin = keys[lo], kmax = keys[lo], varying = 0;
        for (std::size_t i = lo; i < hi; ++i) {
            kmin = std::min(kmin, keys[i]);
            kmax = std::max(kmax, keys[i]);
            varying |= keys[i] ^ keys[lo];
        }
        if (!kTagged && kmax - kmin == m - 1) {
            for (std::size_t i = 0; i < m; ++i) {
                dest[i] = static_cast<std::uint32_t>(keys[lo + i] - kmin);
            }
        } else {
            pos.resize(m);
            pos2.resize(m);
            for (std::size_t i = 0; i < m; ++i) {
                pos[i] = static_cast<std::uint32_t>(i);
            }
            for (int shift = 0; shift < static_cast<int>(std::bit_width(varying)); shift += 8) {
                std::array<std::uint32_t, 257> count{};
                for (std::size_t i = 0; i < m; ++i) {
                    ++count[((keys[lo + i] >> shift) & 0xff) + 1];
                }
                for (std::size_t d = 1; d < 257; ++d) {
                    count[d] += count[d - 1];
                }
                for (std::size_t i = 0; i < m; ++i) {
                    const std::uint32_t p = pos[i];
                    pos2[count[(keys[lo + p] >> shift) & 0xff]++] = p;
                }
                pos.swap(pos2);
            }
            for (std::size_t i = 0; i < m; ++i) {
                dest[pos[i]] = static_cast<std::uint32_t>(i);
            }
        }
        // Each cycle of the permutation walked once: the record in hand goes to its place and
        // the one there is taken up; dest[j] = j marks a place done.
        std::array<std::uint32_t, 64> held{};  // step is at most 256 here
        for (std::size_t i = 0; i < m; ++i) {
            if (dest[i] == i) {
                continue;
            }
            const Word* from = reinterpret_cast<const Word*>(rec + (lo + i) * step);
            std::copy(from, from + words, held.begin());
            Key held_key = keys[lo + i];
            std::uint32_t held_tag = kTagged ? tags[lo + i] : 0;
            std::size_t j = dest[i];
            dest[i] = static_cast<std::uint32_t>(i);
            while (true) {
                swap_words(reinterpret_cast<Word*>(rec + (lo + j) * step), held.data());
                std::swap(held_key, keys[lo + j]);
                if constexpr (kTagged) {
                    std::swap(held_tag, tags[lo + j]);
                }
                if (j == i) {
                    break;
                }
                const std::size_t k = dest[j];
                dest[j] = static_cast<std::uint32_t>(j);
                j = k;
            }
        }
    };
    // The digit of key k at `shift`: bits shift .. shift + 7 (a negative shift: the lowest bits,
    // moved up).
    const auto digit = [](Key k, int shift) {
        return static_cast<unsigned>((shift >= 0 ? k >> shift : k << -shift) & 0xff);
    };
    const auto sort = [&](auto& self, std::size_t lo, std::size_t hi, int shift, bool parallel) -> void {
        if (hi - lo <= kLeaf && step <= 256) {
            leaf(lo, hi);
            return;
        }
        std::array<std::size_t, 256> head{}, end{};
        for (std::size_t i = lo; i < hi; ++i) {
            ++end[digit(keys[i], shift)];
        }
        std::size_t at = lo;
        for (unsigned d = 0; d < 256; ++d) {
            head[d] = at;
            at += end[d];
            end[d] = at;
        }
        const std::array<std::size_t, 256> begin = head;
        for (unsigned d = 0; d < 256; ++d) {
            // Four records at a time, their digits read first: the four moves are independent,
            // so their cache misses overlap (one at a time, each waited for the last: 1.5x
            // slower). Positions below head[d] hold bucket d's records; a record swapped in is
            // looked at in a later round. Each target head[e] lies outside [head[d], end[d])
            // unless e == d, and then at or below the record moved: the later digits stay valid.
            while (end[d] - head[d] >= 4) {
                const std::size_t i = head[d];
                const unsigned e0 = digit(keys[i], shift), e1 = digit(keys[i + 1], shift);
                const unsigned e2 = digit(keys[i + 2], shift), e3 = digit(keys[i + 3], shift);
                swap(i, head[e0]++);
                swap(i + 1, head[e1]++);
                swap(i + 2, head[e2]++);
                swap(i + 3, head[e3]++);
            }
            while (head[d] < end[d]) {
                const std::size_t i = head[d];
                for (unsigned e = digit(keys[i], shift); e != d; e = digit(keys[i], shift)) {
                    swap(i, head[e]++);
                }
                ++head[d];
            }
        }
        if (shift <= 0) {
            return;  // the last digit: each bucket holds one key
        }
        // Buckets wider than a leaf recurse (a few hundred calls at most for 4M points): the
        // one-thread team that `if` makes below the first level costs nothing that shows.
#pragma omp parallel for schedule(dynamic, 1) num_threads(2) if (parallel)
        for (int d = 0; d < 256; ++d) {
            if (end[d] - begin[d] > 1) {
                self(self, begin[d], end[d], shift - 8, false);
            }
        }
    };
    Key all = 0;
    for (std::size_t i = 0; i < n; ++i) {
        all |= keys[i];
    }
    const int bits = static_cast<int>(std::bit_width(all));
    if (bits > 0) {
        sort(sort, 0, n, bits - 8, n >= (std::size_t{1} << 16));
    }
}

/// flag_sort_impl with the record size fixed for the common layouts (x y z, + 1, 2 or 5 fields);
/// tags null: the keys are distinct.
template <class Key>
void flag_sort(std::uint8_t* rec, std::size_t step, Key* keys, std::uint32_t* tags, std::size_t n) {
    const auto run = [&]<std::size_t kWords>() {
        if (tags != nullptr) {
            flag_sort_impl<Key, kWords, true>(rec, step, keys, tags, n);
        } else {
            flag_sort_impl<Key, kWords, false>(rec, step, keys, tags, n);
        }
    };
    switch (step) {
        case 12: run.template operator()<3>(); break;
        case 16: run.template operator()<4>(); break;
        case 20: run.template operator()<5>(); break;
        case 32: run.template operator()<8>(); break;
        default: run.template operator()<0>(); break;
    }
}

struct Bounds {
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    std::size_t n = 0;
};

Bounds empty_bounds() {
    Bounds b;
    for (int a = 0; a < 3; ++a) {
        b.lo[a] = std::numeric_limits<double>::infinity();
        b.hi[a] = -b.lo[a];
    }
    return b;
}

Bounds finite_bounds(const XyzView& cloud) {
    Bounds b = empty_bounds();
    const auto n = static_cast<std::int64_t>(cloud.size);
#pragma omp parallel
    {
        Bounds t = empty_bounds();  // not a copy of b, which another thread may be updating
#pragma omp for schedule(static) nowait
        for (std::int64_t i = 0; i < n; ++i) {
            const pcl::PointXYZ p = cloud[static_cast<std::size_t>(i)];
            if (!is_finite(p)) {
                continue;
            }
            ++t.n;
            const double v[3] = {p.x, p.y, p.z};
            for (int a = 0; a < 3; ++a) {
                t.lo[a] = std::min(t.lo[a], v[a]);
                t.hi[a] = std::max(t.hi[a], v[a]);
            }
        }
#pragma omp critical
        {
            b.n += t.n;
            for (int a = 0; a < 3; ++a) {
                b.lo[a] = std::min(b.lo[a], t.lo[a]);
                b.hi[a] = std::max(b.hi[a], t.hi[a]);
            }
        }
    }
    return b;
}

/// Mean over the points of the number of points in their cell of side `cell` (what a query
/// pays for; points relative to the lower corner).
double occupancy(const std::vector<std::array<double, 3>>& points, double cell) {
    std::vector<std::uint64_t> keys;
    keys.reserve(points.size());
    for (const auto& v : points) {
        std::uint64_t key = 0;
        for (int a = 0; a < 3; ++a) {
            key = (key << 21) | static_cast<std::uint64_t>(std::min<double>(std::floor(v[a] / cell), kAxisCells - 1));
        }
        keys.push_back(key);
    }
    std::sort(keys.begin(), keys.end());
    double sum_sq = 0;
    for (std::size_t i = 0; i < keys.size();) {
        std::size_t j = i;
        while (j < keys.size() && keys[j] == keys[i]) {
            ++j;
        }
        sum_sq += static_cast<double>(j - i) * static_cast<double>(j - i);
        i = j;
    }
    return keys.empty() ? 1.0 : sum_sq / static_cast<double>(keys.size());
}

/// Inserts (dd, i) into the ascending (d², index) list of at most k entries.
inline void insert_candidate(std::uint32_t i, double dd, std::size_t k,
                             std::vector<std::uint32_t>& idx, std::vector<double>& d2) {
    if (idx.size() == k && (dd > d2.back() || (dd == d2.back() && i > idx.back()))) {
        return;
    }
    std::size_t at = idx.size() == k ? k - 1 : idx.size();
    if (idx.size() < k) {
        idx.push_back(0);
        d2.push_back(0);
    }
    while (at > 0 && (d2[at - 1] > dd || (d2[at - 1] == dd && idx[at - 1] > i))) {
        idx[at] = idx[at - 1];
        d2[at] = d2[at - 1];
        --at;
    }
    idx[at] = i;
    d2[at] = dd;
}

constexpr std::int64_t kMaxRing = 2;       // rings searched before falling back to the tree
constexpr std::uint32_t kLeafCells = 16;  // cells per k-d tree leaf (4: 4 % more CPU and 3 MB more at 1M, kNN; 16 vs 8: as fast, 0.9 MB less)

}  // namespace

double Grid::suggest_cell(const XyzView& cloud, double target) {
    const Bounds b = finite_bounds(cloud);
    if (b.n < 2) {
        return 1.0;
    }
    double extent = 0;
    for (int a = 0; a < 3; ++a) {
        extent = std::max(extent, b.hi[a] - b.lo[a]);
    }
    if (!(extent > 0)) {
        return 1.0;  // all points coincide
    }
    const double floor_cell = extent / static_cast<double>(kAxisCells - 2);
    // First guess: the cell of a uniform 3-D cloud; surfaces and lines need smaller ones.
    double cell = std::max(floor_cell, extent / std::cbrt(static_cast<double>(b.n)));
    // Measured on the points of a subset of blocks (side 8 first guesses, one in `stride` chosen
    // by hash): whole blocks keep the local density, where every stride-th point would thin
    // every cell and bias the measure. Blocks are taken more often until the sample holds
    // enough points (every point when the cloud is small).
    const std::size_t wanted = std::min<std::size_t>(b.n, 20000);
    const double block = 8 * cell;
    std::vector<std::array<double, 3>> sample;
    for (std::size_t stride = std::max<std::size_t>(1, b.n / 50000);; stride = std::max<std::size_t>(1, stride / 4)) {
        const std::uint64_t keep_below = ~std::uint64_t{0} / stride;
        sample.clear();
        for (std::size_t i = 0; i < cloud.size; ++i) {
            const pcl::PointXYZ p = cloud[i];
            if (!is_finite(p)) {
                continue;
            }
            const std::array<double, 3> v = {p.x - b.lo[0], p.y - b.lo[1], p.z - b.lo[2]};
            std::uint64_t block_key = 0;
            for (int a = 0; a < 3; ++a) {
                block_key = (block_key << 21) | static_cast<std::uint64_t>(std::min<double>(v[a] / block, kAxisCells - 1));
            }
            if (stride == 1 || (block_key + 1) * 0x9E3779B97F4A7C15ull < keep_below) {
                sample.push_back(v);
            }
        }
        if (sample.size() >= wanted || stride == 1) {
            break;
        }
    }
    // Measure how occupancy grows with the cell side (2^d for a d-dimensional point set) and
    // solve for the target occupancy.
    for (int iter = 0; iter < 3; ++iter) {
        const double a1 = occupancy(sample, cell);
        const double a2 = occupancy(sample, 2 * cell);
        const double d = std::clamp(std::log2(std::max(a2 / a1, 1.0)), 1.0, 3.0);
        const double next = cell * std::pow(target / a1, 1.0 / d);
        cell = std::max(next, floor_cell);
        if (a1 > target / 2 && a1 < target * 2) {
            break;
        }
    }
    return cell;
}

namespace {

/// Open-addressing table of `count` keys (key_of(i) for i < count): slot holds i + 1, 0 = empty.
template <class KeyOf>
void build_table(std::size_t count, KeyOf key_of, std::vector<std::uint32_t>& table,
                 std::uint64_t& mask, int& shift) {
    std::size_t cap = 16;
    int bits = 4;
    while (cap < 2 * count) {
        cap *= 2;
        ++bits;
    }
    table.assign(cap, 0);
    mask = cap - 1;
    shift = 64 - bits;
    for (std::size_t i = 0; i < count; ++i) {
        std::uint64_t h = (key_of(i) * 0x9E3779B97F4A7C15ull) >> shift;
        while (table[h & mask] != 0) {
            ++h;
        }
        table[h & mask] = static_cast<std::uint32_t>(i + 1);
    }
}

}  // namespace

std::size_t Grid::set_frame(const XyzView& points, double cell) {
    if (!(cell > 0) || !std::isfinite(cell)) {
        throw InvalidArgument("grid: cell must be > 0, got " + format_number(cell));
    }
    cell_ = cell;
    const Bounds b = finite_bounds(points);
    for (int a = 0; a < 3; ++a) {
        origin_[a] = b.n ? b.lo[a] : 0.0;
        // Keep every axis within 21 bits of cells: a larger cell is still exact, only slower.
        if (b.n) {
            cell_ = std::max(cell_, (b.hi[a] - b.lo[a]) / static_cast<double>(kAxisCells - 4));
        }
    }
    for (int a = 0; a < 3 && b.n; ++a) {
        dims_[a] = coord(static_cast<float>(b.hi[a]), a) + 1;
        bits_[a] = static_cast<int>(std::bit_width(static_cast<std::uint64_t>(dims_[a] - 1)));
    }
    finite_ = b.n;
    return b.n;
}

template <class Key>
void Grid::index_sorted(const Key* sorted, std::size_t n) {
    // Cells (runs of equal keys) and rows (runs of equal x, y), reserved exactly.
    std::size_t cells = 0, rows = 0;
    for (std::size_t s = 0; s < n; ++s) {
        if (s == 0 || sorted[s] != sorted[s - 1]) {
            ++cells;
            rows += s == 0 || (sorted[s] >> bits_[2]) != (sorted[s - 1] >> bits_[2]);
        }
    }
    cells_.reserve(cells + 1);
    row_begin_.reserve(rows + 1);
    for (std::size_t s = 0; s < n; ++s) {
        if (s == 0 || sorted[s] != sorted[s - 1]) {
            const auto key = static_cast<std::uint64_t>(sorted[s]);
            cells_.push_back({static_cast<std::uint32_t>(key), static_cast<std::uint32_t>(key >> 32),
                              static_cast<std::uint32_t>(s)});
            if (s == 0 || (sorted[s] >> bits_[2]) != (sorted[s - 1] >> bits_[2])) {
                row_begin_.push_back(static_cast<std::uint32_t>(cells_.size() - 1));
            }
        }
    }
    row_begin_.push_back(static_cast<std::uint32_t>(cells_.size()));
    cells_.push_back({0, 0, static_cast<std::uint32_t>(n)});  // the sentinel: the last cell's end
    row_key_.resize(row_begin_.size() - 1);
    for (std::size_t r = 0; r + 1 < row_begin_.size(); ++r) {
        row_key_[r] = cells_[row_begin_[r]].key() >> bits_[2];
    }
    build_table(row_begin_.size() - 1,
                [&](std::size_t r) { return row_key_[r]; }, row_table_,
                row_mask_, row_shift_);
}

Grid::Grid(const XyzView& cloud, double cell) : points_(cloud) {
    const std::size_t n = set_frame(cloud, cell);
    order_.resize(n);
    // 1. Cell keys, sorted with the points' order. 32-bit keys: keys and sort scratch (3 x 4
    //    bytes per point) live in xyz_'s storage (3 floats per point), allocated once here: the
    //    grid's build needs no block beside its own arrays. 64-bit keys: their own scratch.
    const auto sort_points = [&](auto* keys, auto* k2, std::uint32_t* i2) {
        using Key = std::remove_reference_t<decltype(*keys)>;
        const auto key_of = [&](const pcl::PointXYZ& p) { return static_cast<Key>(cell_key(p)); };
        if (n == cloud.size) {  // all finite (the usual case): in parallel
            const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
            for (std::int64_t i = 0; i < count; ++i) {
                keys[i] = key_of(cloud[static_cast<std::size_t>(i)]);
                order_[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(i);
            }
        } else {
            std::size_t at = 0;
            for (std::uint32_t i = 0; i < cloud.size; ++i) {
                const pcl::PointXYZ p = cloud[i];
                if (is_finite(p)) {
                    keys[at] = key_of(p);
                    order_[at++] = i;
                }
            }
        }
        const auto [sorted, idx] = radix_sort(keys, order_.data(), k2, i2, n);
        if (idx != order_.data()) {
            std::copy(idx, idx + n, order_.begin());
        }
        // 2. Cells and rows.
        index_sorted(sorted, n);
    };
    if (bits_[0] + bits_[1] + bits_[2] <= 32) {
        xyz_.resize(3 * n);
        Word* words = reinterpret_cast<Word*>(xyz_.data());
        sort_points(words, words + n, words + 2 * n);
    } else {
        std::vector<std::uint64_t> keys(2 * n);
        std::vector<std::uint32_t> i2(n);
        sort_points(keys.data(), keys.data() + n, i2.data());
        std::vector<std::uint64_t>().swap(keys);
        std::vector<std::uint32_t>().swap(i2);
        xyz_.resize(3 * n);
    }
    // 3. The coordinates in sorted order, over the keys (no longer read).
    const auto m = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
    for (std::int64_t s = 0; s < m; ++s) {
        const pcl::PointXYZ p = cloud[order_[static_cast<std::size_t>(s)]];
        xyz_[3 * s] = p.x;
        xyz_[3 * s + 1] = p.y;
        xyz_[3 * s + 2] = p.z;
    }
    xyz_at_ = xyz_.data();
}

Grid::Grid(XyzRecords& records, double cell) : sorted_(records), in_place_(true), has_points_(false) {
    if (!records.aligned()) {
        throw std::logic_error("grid: records sorted in place need 4-aligned x y z floats");
    }
    if (records.size > std::numeric_limits<std::uint32_t>::max()) {
        throw InvalidArgument("grid: at most 2^32 - 1 points, got " + std::to_string(records.size));
    }
    const XyzView view = records.view();
    set_frame(view, cell);
    const std::size_t n = records.size;
    order_.resize(n);
    // Keys with one bit above the cell key's: set for non-finite points, which sort last.
    const int key_bits = bits_[0] + bits_[1] + bits_[2];
    const auto sort_records = [&](auto key_type) {
        using Key = decltype(key_type);
        std::vector<Key> keys(n);
        const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < count; ++i) {
            const pcl::PointXYZ p = view[static_cast<std::size_t>(i)];
            keys[i] = is_finite(p) ? static_cast<Key>(cell_key(p)) : static_cast<Key>(Key{1} << key_bits);
            order_[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(i);
        }
        flag_sort(records.base, records.stride, keys.data(), order_.data(), n);
        index_sorted(keys.data(), finite_);
    };
    if (key_bits < 32) {
        sort_records(std::uint32_t{});
    } else {
        sort_records(std::uint64_t{});
    }
    xyz_at_ = reinterpret_cast<const float*>(records.base + records.offset);
    stride_ = records.stride / sizeof(float);
}

Grid::~Grid() {
    if (in_place_ && !identity_) {
        // Back to the original order: each record's original index is its sort key.
        flag_sort<std::uint32_t>(sorted_.base, sorted_.stride, order_.data(), nullptr, order_.size());
    }
}

std::int64_t Grid::coord(float v, int axis) const {
    // Clamped so that far query points (not in the grid) cannot overflow the conversion.
    const double c = std::floor((double{v} - origin_[axis]) / cell_);
    return static_cast<std::int64_t>(std::clamp(c, -1e12, 1e12));
}

void Grid::unpack(std::uint64_t key, std::int64_t out[3]) const {
    out[2] = static_cast<std::int64_t>(key & ((std::uint64_t{1} << bits_[2]) - 1));
    key >>= bits_[2];
    out[1] = static_cast<std::int64_t>(key & ((std::uint64_t{1} << bits_[1]) - 1));
    out[0] = static_cast<std::int64_t>(key >> bits_[1]);
}

std::pair<std::uint32_t, std::uint32_t> Grid::row(std::int64_t x, std::int64_t y) const {
    if (!inside(x, y, 0)) {
        return {0, 0};
    }
    const std::uint64_t key = pack(x, y, 0) >> bits_[2];
    for (std::uint64_t h = (key * 0x9E3779B97F4A7C15ull) >> row_shift_;; ++h) {
        const std::uint32_t at = row_table_[h & row_mask_];
        if (at == 0) {
            return {0, 0};
        }
        if (row_key_[at - 1] == key) {
            return {row_begin_[at - 1], row_begin_[at]};
        }
    }
}

struct Grid::RowCursor {
    const Grid& g;
    std::uint64_t row_key = ~std::uint64_t{0};
    bool started = false;
    std::uint32_t row_at[3] = {};          // per dx: first row not below (x + dx, y - 1)
    std::uint32_t at[9] = {}, end[9] = {};  // per (dx, dy): cells of that row not yet passed

    /// The existing cells among c's 3x3x3 neighbourhood (c included), in neighbour_cells()'s
    /// order. Calls for one cursor must come in ascending c: rows are then found by moving
    /// forward, not by hashing.
    void neighbours(std::uint32_t c, std::vector<std::uint32_t>& out, Neighbours which = Neighbours::kAll) {
        out.clear();
        const std::uint64_t key = g.cells_[c].key();
        std::int64_t xyz[3];
        g.unpack(key, xyz);
        if ((key >> g.bits_[2]) != row_key) {
            row_key = key >> g.bits_[2];
            next_row(xyz[0], xyz[1]);
        }
        const std::uint64_t zmask = (std::uint64_t{1} << g.bits_[2]) - 1;
        // The own row first, then the rows sharing a face with it, then the diagonal ones: the
        // nearest cells come first, for sweeps that stop once they have found enough.
        // Cells after c (kAfter): the own row above z and the rows after it, (x, y + 1) and x + 1.
        static constexpr int kRows[9] = {4, 1, 3, 5, 7, 0, 2, 6, 8};
        static constexpr int kAfterRows[5] = {4, 5, 6, 7, 8};
        const bool after = which == Neighbours::kAfter;
        for (const int j : after ? std::span<const int>(kAfterRows) : std::span<const int>(kRows)) {
            while (at[j] < end[j] && static_cast<std::int64_t>(g.cells_[at[j]].key() & zmask) < xyz[2] - 1) {
                ++at[j];
            }
            std::uint32_t t = at[j];
            if (after && j == 4) {
                t = c + 1;  // the own row's cells are consecutive: c + 1 is the next, if any
            }
            for (; t < end[j] && static_cast<std::int64_t>(g.cells_[t].key() & zmask) <= xyz[2] + 1; ++t) {
                out.push_back(t);
            }
        }
    }

private:
    [[nodiscard]] std::uint64_t key_of_row(std::uint32_t r) const { return g.row_key_[r]; }
    void next_row(std::int64_t x, std::int64_t y) {
        const auto rows = static_cast<std::uint32_t>(g.row_begin_.size() - 1);
        for (int dx = -1; dx <= 1; ++dx) {
            const std::int64_t nx = x + dx;
            const bool valid_x = nx >= 0 && nx < g.dims_[0];
            std::uint32_t& r = row_at[dx + 1];
            if (valid_x) {
                const std::uint64_t from = g.pack(nx, std::max<std::int64_t>(y - 1, 0), 0) >> g.bits_[2];
                if (!started) {  // first row of the run: binary search
                    std::uint32_t lo = 0, hi = rows;
                    while (lo < hi) {
                        const std::uint32_t mid = lo + (hi - lo) / 2;
                        if (key_of_row(mid) < from) {
                            lo = mid + 1;
                        } else {
                            hi = mid;
                        }
                    }
                    r = lo;
                }
                while (r < rows && key_of_row(r) < from) {
                    ++r;
                }
            }
            for (int dy = -1; dy <= 1; ++dy) {
                const int j = 3 * (dx + 1) + (dy + 1);
                at[j] = end[j] = 0;
                const std::int64_t ny = y + dy;
                if (!valid_x || ny < 0 || ny >= g.dims_[1]) {
                    continue;
                }
                const std::uint64_t want = g.pack(nx, ny, 0) >> g.bits_[2];
                for (std::uint32_t q = r; q < rows && q < r + 3 && key_of_row(q) <= want; ++q) {
                    if (key_of_row(q) == want) {
                        at[j] = g.row_begin_[q];
                        end[j] = g.row_begin_[q + 1];
                    }
                }
            }
        }
        started = true;
    }
};

void Grid::knn(std::uint32_t self,
               std::size_t k,
               std::vector<std::uint32_t>& idx,
               std::vector<double>& d2) const {
    if (!has_points_) {
        throw std::logic_error("grid: knn(i) needs a grid that copied the points and was not renumbered");
    }
    search(points_[self], self, k, idx, d2);
}

void Grid::knn_point(const pcl::PointXYZ& q, std::size_t k, std::vector<std::uint32_t>& idx,
                     std::vector<double>& d2) const {
    search(q, std::numeric_limits<std::uint32_t>::max(), k, idx, d2);
}

void Grid::search(const pcl::PointXYZ& q,
                  std::uint32_t self,
                  std::size_t k,
                  std::vector<std::uint32_t>& idx,
                  std::vector<double>& d2) const {
    idx.clear();
    d2.clear();
    if (k == 0 || finite_ == 0 || !is_finite(q)) {
        return;  // a non-finite query has no neighbours
    }
    const std::int64_t c[3] = {coord(q.x, 0), coord(q.y, 1), coord(q.z, 2)};
    // A query outside the grid's range (pc_compare's other cloud) goes to the tree at once.
    bool outside = false;
    for (int a = 0; a < 3; ++a) {
        outside = outside || c[a] < -1 || c[a] > dims_[a];
    }
    // Distance from q to the nearest face of its own cell: points in ring r+1 are at least
    // r * cell + margin away.
    double margin = std::numeric_limits<double>::infinity();
    const double v[3] = {q.x, q.y, q.z};
    for (int a = 0; a < 3; ++a) {
        const double lo = origin_[a] + static_cast<double>(c[a]) * cell_;
        margin = std::min({margin, v[a] - lo, lo + cell_ - v[a]});
    }
    margin = std::max(margin, 0.0);
    const auto consider = [&](const Cell& cell) {
        for (std::uint32_t s = cell.begin; s < cell.end(); ++s) {
            const std::uint32_t i = index_of(s);
            if (i == self) {
                continue;
            }
            const float* p = point(s);
            const double ex = double{p[0]} - q.x;
            const double ey = double{p[1]} - q.y;
            const double ez = double{p[2]} - q.z;
            insert_candidate(i, ex * ex + ey * ey + ez * ez, k, idx, d2);
        }
    };
    const bool indexed = has_points_ && self < points_.size && is_finite(points_[self]);
    const std::size_t others = finite_ - (indexed ? 1 : 0);
    for (std::int64_t r = 0;; ++r) {
        // Ring r by rows: rows on the square's edge give all of z - r .. z + r, inner rows only
        // their two ends.
        for (std::int64_t dx = -r; dx <= r; ++dx) {
            for (std::int64_t dy = -r; dy <= r; ++dy) {
                const bool edge = std::abs(dx) == r || std::abs(dy) == r;
                for (const std::int64_t z_lo : {c[2] - r, c[2] + r}) {
                    const std::int64_t z_hi = edge ? c[2] + r : z_lo;
                    const auto [first, last] = row_span(c[0] + dx, c[1] + dy, z_lo, z_hi);
                    for (const Cell* cell = first; cell < last; ++cell) {
                        consider(*cell);
                    }
                    if (edge || r == 0) {
                        break;
                    }
                }
            }
        }
        // Unvisited points are at least `reach` away; strict so that index tie-breaks are exact.
        const double reach = static_cast<double>(r) * cell_ + margin;
        if (idx.size() == k && d2.back() < reach * reach) {
            return;
        }
        if (idx.size() == others) {
            return;  // fewer than k other points, all seen
        }
        if (r == kMaxRing || outside) {
            tree_knn(q, self, k, idx, d2);  // an isolated point: let the tree bound the work
            return;
        }
    }
}

void Grid::build_tree() const {
    std::call_once(tree_once_, [this] {
        // A k-d tree over the occupied cells (a few points each), split on cell coordinates:
        // cheaper to build than one over the points, and a cell's points are contiguous.
        const auto n = static_cast<std::uint32_t>(cell_count());
        tree_perm_.resize(n);
        for (std::uint32_t c = 0; c < n; ++c) {
            tree_perm_[c] = c;
        }
        const auto at_axis = [&](std::uint32_t c, int axis) {
            std::int64_t v[3];
            unpack(cells_[c].key(), v);
            return static_cast<std::int32_t>(v[axis]);
        };
        // Median splits leave at least kLeafCells / 2 cells in a leaf, so about n / 2 nodes; skewed
        // splits (many cells on one plane) may grow the vector past that, which is rare. (2 n, the
        // bound, held 48 bytes a cell: 6.9 MB at 1M points, part of it resident in huge pages.)
        nodes_.reserve(2 * (std::size_t{n} / (kLeafCells / 2) + 1));
        nodes_.push_back({0, n});
        std::vector<std::uint32_t> mid;  // per node of a level: where its range splits (end = a leaf)
        // Level by level: the nodes of one level own disjoint ranges of tree_perm_, so they are
        // split in parallel; children are appended afterwards, in order.
        for (std::size_t level_begin = 0; level_begin < nodes_.size();) {
            const std::size_t level_end = nodes_.size();
            mid.assign(level_end - level_begin, 0);
#pragma omp parallel for schedule(dynamic, 1)
            for (std::int64_t at = static_cast<std::int64_t>(level_begin);
                 at < static_cast<std::int64_t>(level_end); ++at) {
                Node& node = nodes_[static_cast<std::size_t>(at)];
                const std::uint32_t b = node.begin, e = node.end;
                std::uint32_t& split_at = mid[static_cast<std::size_t>(at) - level_begin];
                split_at = e;  // a leaf unless split below
                if (e - b <= kLeafCells) {
                    continue;
                }
                std::int32_t lo[3] = {INT32_MAX, INT32_MAX, INT32_MAX}, hi[3] = {INT32_MIN, INT32_MIN, INT32_MIN};
                for (std::uint32_t p = b; p < e; ++p) {
                    for (int a = 0; a < 3; ++a) {
                        lo[a] = std::min(lo[a], at_axis(tree_perm_[p], a));
                        hi[a] = std::max(hi[a], at_axis(tree_perm_[p], a));
                    }
                }
                int axis = 0;
                for (int a = 1; a < 3; ++a) {
                    if (hi[a] - lo[a] > hi[axis] - lo[axis]) {
                        axis = a;
                    }
                }
                // Distinct cells differ on some axis, so the widest one has lo < hi.
                auto* first = tree_perm_.data() + b;
                auto* last = tree_perm_.data() + e;
                std::nth_element(first, first + (e - b) / 2, last, [&](std::uint32_t u, std::uint32_t v) {
                    return at_axis(u, axis) < at_axis(v, axis);
                });
                std::int32_t boundary = at_axis(first[(e - b) / 2], axis);  // left: coordinate < boundary
                if (boundary == lo[axis]) {
                    ++boundary;
                }
                auto* split = std::partition(first, last, [&](std::uint32_t u) { return at_axis(u, axis) < boundary; });
                split_at = static_cast<std::uint32_t>(split - tree_perm_.data());
                node.axis = static_cast<std::uint8_t>(axis);
                node.plane = origin_[axis] + static_cast<double>(boundary) * cell_;
            }
            for (std::size_t at = level_begin; at < level_end; ++at) {
                const Node node = nodes_[at];
                const std::uint32_t m = mid[at - level_begin];
                if (m == node.end) {
                    continue;
                }
                nodes_[at].left = static_cast<std::int32_t>(nodes_.size());  // right: left + 1
                nodes_.push_back({node.begin, m});
                nodes_.push_back({m, node.end});
            }
            level_begin = level_end;
        }
    });
}

void Grid::tree_knn(const pcl::PointXYZ& q, std::uint32_t self, std::size_t k,
                    std::vector<std::uint32_t>& idx, std::vector<double>& d2) const {
    build_tree();
    idx.clear();
    d2.clear();
    const double v[3] = {q.x, q.y, q.z};
    // A point's cell coordinate is computed with rounding, so it may sit a hair across its
    // cell's plane: planes are widened by `slack` to keep the bounds below the true distances.
    const double slack = 1e-6 * cell_;
    // Depth-first, near side first; a far side is skipped only when its half-space is strictly
    // farther than the current k-th distance (so index tie-breaks stay exact).
    thread_local std::vector<std::pair<std::int32_t, double>> stack;
    stack.assign(1, {0, 0.0});
    while (!stack.empty()) {
        const auto [at, bound] = stack.back();
        stack.pop_back();
        if (idx.size() == k && bound > d2.back()) {
            continue;
        }
        const Node& node = nodes_[static_cast<std::size_t>(at)];
        if (node.left < 0) {
            for (std::uint32_t p = node.begin; p < node.end; ++p) {
                const Cell& cell = cells_[tree_perm_[p]];
                for (std::uint32_t s = cell.begin; s < cell.end(); ++s) {
                    const std::uint32_t i = index_of(s);
                    if (i == self) {
                        continue;
                    }
                    const float* at_s = point(s);
                    const double ex = double{at_s[0]} - v[0];
                    const double ey = double{at_s[1]} - v[1];
                    const double ez = double{at_s[2]} - v[2];
                    insert_candidate(i, ex * ex + ey * ey + ez * ez, k, idx, d2);
                }
            }
            continue;
        }
        const double diff = v[node.axis] - node.plane;
        const std::int32_t near = diff < 0 ? node.left : node.left + 1;
        const std::int32_t far = diff < 0 ? node.left + 1 : node.left;
        const double gap = std::max(0.0, std::abs(diff) - slack);
        stack.push_back({far, std::max(bound, gap * gap)});
        stack.push_back({near, bound});
    }
}

void Grid::renumber_by_position() {
    if (finite_ != (in_place_ ? sorted_.size : points_.size)) {
        throw std::logic_error("Grid::renumber_by_position: needs a grid over finite points only");
    }
    std::vector<std::uint32_t>().swap(order_);
    identity_ = true;
    has_points_ = false;
}

void Grid::order_cells_by_index() {
    if (!in_place_ || identity_) {
        throw std::logic_error("Grid::order_cells_by_index: needs a grid that sorted records in place");
    }
    // Small cells (the usual ones) by insertion, records moved through a buffer; others by
    // the radix sort of the build (its set-up costs more than a few dozen moves).
    constexpr std::uint32_t kInsertion = 32;
    constexpr std::size_t kBuffer = 256;
    const std::size_t stride = sorted_.stride;
    const auto cells = static_cast<std::int64_t>(cell_count());
#pragma omp parallel for schedule(dynamic, 1024)
    for (std::int64_t c = 0; c < cells; ++c) {
        const std::uint32_t b = cell_begin(static_cast<std::size_t>(c)), e = cell_end(static_cast<std::size_t>(c));
        if (e - b < 2 || std::is_sorted(order_.begin() + b, order_.begin() + e)) {
            continue;
        }
        std::uint8_t* rec = sorted_.base;
        if (e - b > kInsertion || stride > kBuffer) {
            flag_sort<std::uint32_t>(rec + std::size_t{b} * stride, stride, order_.data() + b, nullptr, e - b);
            continue;
        }
        std::array<std::uint8_t, kBuffer> held{};
        for (std::uint32_t i = b + 1; i < e; ++i) {
            const std::uint32_t key = order_[i];
            std::uint32_t j = i;
            if (order_[j - 1] <= key) {
                continue;
            }
            std::memcpy(held.data(), rec + std::size_t{i} * stride, stride);
            for (; j > b && order_[j - 1] > key; --j) {
                order_[j] = order_[j - 1];
            }
            std::memmove(rec + (std::size_t{j} + 1) * stride, rec + std::size_t{j} * stride, std::size_t{i - j} * stride);
            std::memcpy(rec + std::size_t{j} * stride, held.data(), stride);
            order_[j] = key;
        }
    }
}

void permute_records(XyzRecords& records, std::span<std::uint32_t> to) {
    if (to.size() != records.size) {
        throw std::logic_error("permute_records: one place per record");
    }
    permute_records(records.base, records.stride, to);
}

void permute_records(void* base, std::size_t stride, std::span<std::uint32_t> to) {
    if (stride == 0 || stride % sizeof(std::uint32_t) != 0) {
        throw std::logic_error("permute_records: records of whole 4-byte words");
    }
    flag_sort<std::uint32_t>(static_cast<std::uint8_t*>(base), stride, to.data(), nullptr, to.size());
}

std::unique_ptr<Grid> grid_over(XyzRecords& records, double cell) {
    constexpr std::size_t kThin = 16;  // bytes a record, x y z's 12 included
    if (records.stride <= kThin && records.aligned()) {
        return std::make_unique<Grid>(records, cell);
    }
    return std::make_unique<Grid>(records.view(), cell);
}

void Grid::neighbour_cells(std::size_t c, std::vector<std::uint32_t>& out) const {
    RowCursor cursor{*this};
    cursor.neighbours(static_cast<std::uint32_t>(c), out);
}

void Grid::sweep_cells(
    const std::function<void(std::uint32_t, const std::vector<std::uint32_t>&)>& f,
    const std::function<bool(std::uint32_t)>& needs_neighbours, Neighbours which) const {
    // Runs of consecutive cells per task, so that the row cursors mostly move forward.
    constexpr std::int64_t kRun = 256;
    const auto cells = static_cast<std::int64_t>(cell_count());
    const std::int64_t runs = (cells + kRun - 1) / kRun;
#pragma omp parallel
    {
        std::vector<std::uint32_t> nb;
#pragma omp for schedule(dynamic, 1)
        for (std::int64_t run = 0; run < runs; ++run) {
            RowCursor cursor{*this};
            for (std::int64_t c = run * kRun; c < std::min(cells, (run + 1) * kRun); ++c) {
                const auto cell = static_cast<std::uint32_t>(c);
                if (!needs_neighbours || needs_neighbours(cell)) {
                    cursor.neighbours(cell, nb, which);
                } else {
                    nb.clear();
                }
                f(cell, nb);
            }
        }
    }
}

namespace {

/// A cell near a query's cell: its index, its offset (-2..2 per axis), |offset|_1.
struct Segment {
    std::uint32_t cell;
    std::int8_t d[3];
    std::uint8_t rank;
};

/// Per-thread scratch of all_knn (one thread_local look-up per cell, not per access).
struct KnnScratch {
    std::vector<std::uint32_t> idx, far;
    std::vector<double> d2;
    std::vector<Segment> block, ring2;  // the 3x3x3 block; the cells at Chebyshev distance 2
};

}  // namespace

std::pair<const Grid::Cell*, const Grid::Cell*> Grid::row_span(std::int64_t x, std::int64_t y, std::int64_t z_lo,
                                                               std::int64_t z_hi) const {
    const auto [rb, re] = row(x, y);
    const std::uint64_t zmask = (std::uint64_t{1} << bits_[2]) - 1;
    const auto z_of = [&](const Cell& c) { return static_cast<std::int64_t>(c.key() & zmask); };
    const Cell* first = std::partition_point(cells_.data() + rb, cells_.data() + re,
                                             [&](const Cell& c) { return z_of(c) < z_lo; });
    const Cell* last = std::partition_point(first, cells_.data() + re,
                                            [&](const Cell& c) { return z_of(c) <= z_hi; });
    return {first, last};
}

void Grid::all_knn(std::size_t k,
                   const std::function<void(std::uint32_t, const std::vector<std::uint32_t>&,
                                            const std::vector<double>&)>& f) const {
    const std::size_t others = finite_ == 0 ? 0 : finite_ - 1;
    // A point's cell is found with rounding, so a point may sit a hair across its cell's face:
    // face distances are reduced by `slack`, keeping every bound below the true distance.
    const double slack = 1e-6 * cell_;
    std::vector<std::uint32_t> far_points;  // left for the k-d tree
    std::mutex far_mutex;
    const auto segment = [](std::uint32_t cell, const std::int64_t at[3], const std::int64_t centre[3]) {
        Segment seg{cell, {static_cast<std::int8_t>(at[0] - centre[0]), static_cast<std::int8_t>(at[1] - centre[1]),
                           static_cast<std::int8_t>(at[2] - centre[2])}, 0};
        seg.rank = static_cast<std::uint8_t>(std::abs(seg.d[0]) + std::abs(seg.d[1]) + std::abs(seg.d[2]));
        return seg;
    };
    sweep_cells([&](std::uint32_t c, const std::vector<std::uint32_t>& nb) {
        thread_local KnnScratch scratch;
        KnnScratch& w = scratch;
        w.far.clear();
        std::int64_t xyz[3];
        unpack(cells_[c].key(), xyz);
        const double lo[3] = {origin_[0] + static_cast<double>(xyz[0]) * cell_,
                              origin_[1] + static_cast<double>(xyz[1]) * cell_,
                              origin_[2] + static_cast<double>(xyz[2]) * cell_};
        // The 3x3x3 block's cells, nearest first (own cell, faces, edges, corners), so that a
        // point can skip cells farther than its current k-th distance.
        w.block.clear();
        for (std::uint32_t nc : nb) {
            std::int64_t at[3];
            unpack(cells_[nc].key(), at);
            w.block.push_back(segment(nc, at, xyz));
        }
        std::stable_sort(w.block.begin(), w.block.end(),
                         [](const Segment& a, const Segment& b) { return a.rank < b.rank; });
        bool ring2_ready = false;
        for (std::uint32_t s = cells_[c].begin; s < cells_[c].end(); ++s) {
            w.idx.clear();
            w.d2.clear();
            // gap[a][d + 2]: squared distance from the point to the cells at offset d along axis a.
            double gap[3][5];
            double margin = cell_;  // to the nearest face of its own cell
            for (int a = 0; a < 3; ++a) {
                const double below = std::max(0.0, double{point(s)[a]} - lo[a] - slack);
                const double above = std::max(0.0, lo[a] + cell_ - point(s)[a] - slack);
                gap[a][0] = (below + cell_) * (below + cell_);
                gap[a][1] = below * below;
                gap[a][2] = 0;
                gap[a][3] = above * above;
                gap[a][4] = (above + cell_) * (above + cell_);
                margin = std::min({margin, below, above});
            }
            const double px = point(s)[0], py = point(s)[1], pz = point(s)[2];
            const auto scan = [&](const std::vector<Segment>& cells) {
                double worst = w.idx.size() == k ? w.d2.back() : std::numeric_limits<double>::infinity();
                for (const Segment& seg : cells) {
                    if (gap[0][seg.d[0] + 2] + gap[1][seg.d[1] + 2] + gap[2][seg.d[2] + 2] > worst) {
                        continue;  // every point of that cell is farther than the k-th
                    }
                    const float* q = point(cells_[seg.cell].begin);
                    for (std::uint32_t t = cells_[seg.cell].begin; t < cells_[seg.cell].end(); ++t, q += stride_) {
                        const double ex = px - q[0], ey = py - q[1], ez = pz - q[2];
                        const double dd = ex * ex + ey * ey + ez * ez;
                        if (dd <= worst && t != s) {
                            insert_candidate(index_of(t), dd, k, w.idx, w.d2);
                            if (w.idx.size() == k) {
                                worst = w.d2.back();
                            }
                        }
                    }
                }
            };
            // The 3x3x3 block covers every point closer than one cell plus the distance to the
            // nearest face of the point's own cell; the 5x5x5 block one cell more.
            const auto done = [&](double reach) {
                return (w.idx.size() == k && w.d2.back() < reach * reach) ||
                       (w.idx.size() == others && others < k);
            };
            scan(w.block);
            if (!done(cell_ + margin)) {
                if (!ring2_ready) {  // gathered once per cell, for its points that need it
                    w.ring2.clear();
                    for (std::int64_t dx = -2; dx <= 2; ++dx) {
                        for (std::int64_t dy = -2; dy <= 2; ++dy) {
                            const bool inner_row = std::abs(dx) <= 1 && std::abs(dy) <= 1;
                            const auto [first, last] = row_span(xyz[0] + dx, xyz[1] + dy, xyz[2] - 2, xyz[2] + 2);
                            for (const Cell* cell = first; cell < last; ++cell) {
                                std::int64_t at[3];
                                unpack(cell->key(), at);
                                if (!inner_row || std::abs(at[2] - xyz[2]) == 2) {  // not in the block
                                    w.ring2.push_back(segment(static_cast<std::uint32_t>(cell - cells_.data()), at, xyz));
                                }
                            }
                        }
                    }
                    ring2_ready = true;
                }
                scan(w.ring2);
                if (!done(2 * cell_ + margin)) {
                    w.far.push_back(s);  // sparse: the tree bounds the work
                    continue;
                }
            }
            f(index_of(s), w.idx, w.d2);
        }
        if (!w.far.empty()) {
            const std::lock_guard<std::mutex> lock(far_mutex);
            far_points.insert(far_points.end(), w.far.begin(), w.far.end());
        }
    });
    if (far_points.empty()) {
        return;
    }
    build_tree();  // here, outside the sweep, so that its build is parallel too
#pragma omp parallel
    {
        std::vector<std::uint32_t> idx;
        std::vector<double> d2;
#pragma omp for schedule(dynamic, 256)
        for (std::int64_t at = 0; at < static_cast<std::int64_t>(far_points.size()); ++at) {
            const std::uint32_t s = far_points[static_cast<std::size_t>(at)];
            const float* p = point(s);
            tree_knn(pcl::PointXYZ(p[0], p[1], p[2]), index_of(s), k, idx, d2);
            f(index_of(s), idx, d2);
        }
    }
}

namespace {

/// Points per occupied cell of the grid median_spacing() samples by position.
constexpr double kSpacingOccupancy = 16;

}  // namespace

double median_spacing(const XyzView& cloud, std::size_t samples) {
    return median_spacing(Grid(cloud, Grid::suggest_cell(cloud, kSpacingOccupancy)), samples);
}

double median_spacing(const Grid& grid, std::size_t samples) {
    if (grid.finite_count() < 2) {
        return 0;
    }
    const std::size_t stride = std::max<std::size_t>(1, grid.finite_count() / std::max<std::size_t>(1, samples));
    std::vector<double> d;
    std::vector<std::uint32_t> idx;
    std::vector<double> d2;
    for (std::size_t s = 0; s < grid.finite_count(); s += stride) {
        // The two nearest to the point's own coordinates: itself (0) first, then its nearest
        // other point, unless another coincides with it (then both are 0 and it is skipped).
        const float* p = grid.point(static_cast<std::uint32_t>(s));
        grid.knn_point(pcl::PointXYZ(p[0], p[1], p[2]), 2, idx, d2);
        if (d2.size() == 2 && d2[1] > 0) {
            d.push_back(std::sqrt(d2[1]));
        }
    }
    return d.empty() ? 0 : median(d);
}

}  // namespace pc::search
