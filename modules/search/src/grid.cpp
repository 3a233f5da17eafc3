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
#include <pc/core/radix_sort.h>
#include <pc/search/grid.h>

namespace pc::search {

namespace {

constexpr std::int64_t kAxisCells = std::int64_t{1} << 21;  // 21 bits per axis in a 63-bit key

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
            key = (key << 21) | static_cast<std::uint64_t>(
                                    std::min<double>(std::floor(v[a] / cell), kAxisCells - 1));
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
    for (std::size_t stride = std::max<std::size_t>(1, b.n / 50000);;
         stride = std::max<std::size_t>(1, stride / 4)) {
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
                block_key = (block_key << 21) | static_cast<std::uint64_t>(
                                                    std::min<double>(v[a] / block, kAxisCells - 1));
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
void build_table(std::size_t count,
                 KeyOf key_of,
                 std::vector<std::uint32_t>& table,
                 std::uint64_t& mask,
                 int& shift) {
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
            cells_.push_back({static_cast<std::uint32_t>(key),
                              static_cast<std::uint32_t>(key >> 32),
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
    build_table(
        row_begin_.size() - 1, [&](std::size_t r) { return row_key_[r]; }, row_table_, row_mask_,
        row_shift_);
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
        const auto [sorted, idx] = radix_sort_pairs(keys, order_.data(), k2, i2, n);
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

Grid::Grid(XyzRecords& records, double cell)
    : sorted_(records), in_place_(true), has_points_(false) {
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
            keys[i] =
                is_finite(p) ? static_cast<Key>(cell_key(p)) : static_cast<Key>(Key{1} << key_bits);
            order_[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(i);
        }
        flag_sort(records.base, records.stride, keys.data(), order_.data(), n);
        try {
            index_sorted(keys.data(), finite_);
        } catch (...) {  // no destructor runs for a constructor that throws: put them back here
            permute_records(sorted_, order_);
            throw;
        }
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
        // Back to the original order: record s goes to place order_[s]. (The sort's scratch is
        // a few hundred KiB a thread; failing to get it here would end the program.)
        permute_records(sorted_, order_);
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
    std::uint32_t row_at[3] = {};           // per dx: first row not below (x + dx, y - 1)
    std::uint32_t at[9] = {}, end[9] = {};  // per (dx, dy): cells of that row not yet passed

    /// The existing cells among c's 3x3x3 neighbourhood (c included), in neighbour_cells()'s
    /// order. Calls for one cursor must come in ascending c: rows are then found by moving
    /// forward, not by hashing.
    void neighbours(std::uint32_t c,
                    std::vector<std::uint32_t>& out,
                    Neighbours which = Neighbours::kAll) {
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
            while (at[j] < end[j] &&
                   static_cast<std::int64_t>(g.cells_[at[j]].key() & zmask) < xyz[2] - 1) {
                ++at[j];
            }
            std::uint32_t t = at[j];
            if (after && j == 4) {
                t = c + 1;  // the own row's cells are consecutive: c + 1 is the next, if any
            }
            for (; t < end[j] && static_cast<std::int64_t>(g.cells_[t].key() & zmask) <= xyz[2] + 1;
                 ++t) {
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
                const std::uint64_t from =
                    g.pack(nx, std::max<std::int64_t>(y - 1, 0), 0) >> g.bits_[2];
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
        throw std::logic_error(
            "Grid::order_cells_by_index: needs a grid that sorted records in place");
    }
    // Small cells (the usual ones) by insertion, records moved through a buffer; others by
    // the radix sort of the build (its set-up costs more than a few dozen moves).
    constexpr std::uint32_t kInsertion = 32;
    constexpr std::size_t kBuffer = 256;
    const std::size_t stride = sorted_.stride;
    const auto cells = static_cast<std::int64_t>(cell_count());
#pragma omp parallel for schedule(dynamic, 1024)
    for (std::int64_t c = 0; c < cells; ++c) {
        const std::uint32_t b = cell_begin(static_cast<std::size_t>(c)),
                            e = cell_end(static_cast<std::size_t>(c));
        if (e - b < 2 || std::is_sorted(order_.begin() + b, order_.begin() + e)) {
            continue;
        }
        std::uint8_t* rec = sorted_.base;
        if (e - b > kInsertion || stride > kBuffer) {
            flag_sort<std::uint32_t>(rec + std::size_t{b} * stride, stride, order_.data() + b,
                                     nullptr, e - b);
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
            std::memmove(rec + (std::size_t{j} + 1) * stride, rec + std::size_t{j} * stride,
                         std::size_t{i - j} * stride);
            std::memcpy(rec + std::size_t{j} * stride, held.data(), stride);
            order_[j] = key;
        }
    }
}

std::unique_ptr<Grid> grid_over(XyzRecords& records, double cell) {
    constexpr std::size_t kThin = 16;  // bytes a record, x y z's 12 included
    if (records.stride <= kThin && records.aligned()) {
        return std::make_unique<Grid>(records, cell);
    }
    return std::make_unique<Grid>(records.view(), cell);
}

std::pair<const Grid::Cell*, const Grid::Cell*> Grid::row_span(std::int64_t x,
                                                               std::int64_t y,
                                                               std::int64_t z_lo,
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

void Grid::neighbour_cells(std::size_t c, std::vector<std::uint32_t>& out) const {
    RowCursor cursor{*this};
    cursor.neighbours(static_cast<std::uint32_t>(c), out);
}

void Grid::sweep_cells(
    const std::function<void(std::uint32_t, const std::vector<std::uint32_t>&)>& f,
    const std::function<bool(std::uint32_t)>& needs_neighbours,
    Neighbours which) const {
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

}  // namespace pc::search
