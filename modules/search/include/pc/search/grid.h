#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <utility>
#include <vector>

#include <pc/core/cloud.h>

namespace pc::search {

/// A uniform grid over the finite points of a cloud, for exact radius and k-nearest-neighbour
/// queries. Points are stored sorted by cell, so a cell's points are contiguous in memory.
/// Distances are computed in double from the float coordinates: d² = Σ (a_i − b_i)².
class Grid {
public:
    Grid(const Grid&) = delete;
    Grid& operator=(const Grid&) = delete;

    /// Builds the grid with cubic cells of side `cell` (> 0), enlarged if an axis would need more
    /// than 2^21 cells (queries stay exact). Non-finite points are left out. The grid keeps its
    /// own copy of the finite points' x y z (12 bytes a point) in cell order.
    Grid(const XyzView& points, double cell);
    /// The same over a pcl cloud (which, like the points of a view, must outlive the grid: knn(i)
    /// reads it).
    Grid(const Cloud& cloud, double cell) : Grid(XyzView(cloud), cell) {}

    /// Builds the grid by sorting the cloud's own records into cell order (whole records, the
    /// non-finite points after the finite ones) and reads the coordinates there: no copy of the
    /// points, which on an x y z-only cloud would be the size of the cloud. The destructor puts
    /// the records back in their order (also when unwinding an exception), unless
    /// renumber_by_position() handed the cell order over to the caller. Until then the records
    /// must not move or be written, and knn(i) is not available. std::logic_error when x y z
    /// are not 4-aligned floats (XyzRecords::aligned()).
    Grid(XyzRecords& records, double cell);
    ~Grid();

    /// A cell side giving about `target` points per occupied cell (adapts to surfaces and lines:
    /// the occupancy is measured, not assumed).
    [[nodiscard]] static double suggest_cell(const XyzView& points, double target = 4.0);
    [[nodiscard]] static double suggest_cell(const Cloud& cloud, double target = 4.0) {
        return suggest_cell(XyzView(cloud), target);
    }

    /// Calls f(index, d²) for every point with d² <= radius² (itself included); radius <= cell().
    template <class F>
    void for_each_within(const pcl::PointXYZ& q, double radius, F&& f) const;

    /// The same for the points that `keep(index)` accepts, asked before their distance is
    /// computed: for searches that skip most of what they find (e.g. points already visited).
    template <class Keep, class F>
    void for_each_within_if(const pcl::PointXYZ& q, double radius, Keep&& keep, F&& f) const;

    /// The k nearest points to cloud point `self` other than itself: indices and d², ascending
    /// by (d², index). Fewer than k when the cloud has fewer other finite points; none when
    /// `self` is not finite.
    void knn(std::uint32_t self,
             std::size_t k,
             std::vector<std::uint32_t>& idx,
             std::vector<double>& d2) const;

    /// The k nearest indexed points to any query point q (need not be in the cloud), as knn().
    void knn_point(const pcl::PointXYZ& q,
                   std::size_t k,
                   std::vector<std::uint32_t>& idx,
                   std::vector<double>& d2) const;

    /// Calls f(i, idx, d2) for every finite point i with the same answer as knn(i, k, ...), working
    /// cell by cell in parallel (OpenMP). f is called concurrently for distinct i.
    void all_knn(std::size_t k,
                 const std::function<void(std::uint32_t,
                                          const std::vector<std::uint32_t>&,
                                          const std::vector<double>&)>& f) const;

    // Cell-level access for algorithms that sweep the grid: points are "sorted positions"
    // 0..finite_count()-1, grouped by cell.
    [[nodiscard]] std::size_t cell_count() const { return cells_.empty() ? 0 : cells_.size() - 1; }
    [[nodiscard]] std::uint32_t cell_begin(std::size_t c) const { return cells_[c].begin; }
    [[nodiscard]] std::uint32_t cell_end(std::size_t c) const { return cells_[c + 1].begin; }
    /// Which neighbour cells a sweep hands over: all of the 3x3x3 block, or only the cells after
    /// c in cell order (each pair of neighbouring cells is then seen once, from its first cell).
    enum class Neighbours { kAll, kAfter };
    /// Calls f(c, neighbours) for every cell c, in parallel over cells (OpenMP, dynamic schedule),
    /// with neighbours = neighbour_cells(c) (kAfter: those above c, in the same order).
    /// f is called concurrently for distinct cells. `needs_neighbours`, when given, says which
    /// cells need them: the others get an empty list and cost no look-ups.
    void sweep_cells(const std::function<void(std::uint32_t, const std::vector<std::uint32_t>&)>& f,
                     const std::function<bool(std::uint32_t)>& needs_neighbours = {},
                     Neighbours which = Neighbours::kAll) const;
    /// The existing cells among c's 3x3x3 neighbourhood (c included), nearest rows first: c's own
    /// row (x, y), then the four rows sharing a face with it, then the four diagonal ones; by z
    /// within a row. Sweeps that stop once they have found enough look at the near cells first.
    void neighbour_cells(std::size_t c, std::vector<std::uint32_t>& out) const;
    /// Original cloud index of sorted position s (s itself once renumbered).
    [[nodiscard]] std::uint32_t index_of(std::uint32_t s) const {
        return identity_ ? s : order_[s];
    }
    /// Coordinates (x, y, z) of sorted position s; position s + 1 is point_stride() floats on.
    [[nodiscard]] const float* point(std::uint32_t s) const { return xyz_at_ + stride_ * s; }
    /// Floats from one sorted position's coordinates to the next (3 unless built in place).
    [[nodiscard]] std::size_t point_stride() const { return stride_; }
    /// Squared distance between sorted positions s and t, in double.
    [[nodiscard]] double dist2(std::uint32_t s, std::uint32_t t) const {
        const float* a = point(s);
        const float* b = point(t);
        const double ex = double{a[0]} - b[0];
        const double ey = double{a[1]} - b[1];
        const double ez = double{a[2]} - b[2];
        return ex * ex + ey * ey + ez * ez;
    }

    [[nodiscard]] double cell() const { return cell_; }
    /// Renumbers the points by sorted position (index_of(s) == s afterwards), for a caller that
    /// keeps its per-point data in cell order, where neighbours lie near each other in memory:
    /// it moves its point index_of(s) to place s (reading index_of() before this call) and views
    /// the points in that order. The grid frees its order and forgets its cloud (knn(i) throws).
    /// Built in place, the records stay in cell order for good: the caller owns that order
    /// and puts them back itself if it must (permute_records()). Every point must be finite
    /// (std::logic_error).
    void renumber_by_position();
    /// Puts each cell's records, sorted in place, in their original order, as a grid that copies
    /// the points has them (its sort is stable; the in-place sort is not): for callers whose
    /// results depend on the order of equal cells. Only for a grid built in place
    /// (std::logic_error).
    void order_cells_by_index();
    [[nodiscard]] std::size_t finite_count() const { return finite_; }

private:
    /// 12 bytes: the key in two words (4-byte alignment) and the first sorted position; a
    /// cell ends where the next begins (cells_ closes with a sentinel holding finite_count()).
    struct Cell {
        std::uint32_t key_lo, key_hi, begin;
        [[nodiscard]] std::uint64_t key() const { return (std::uint64_t{key_hi} << 32) | key_lo; }
        [[nodiscard]] std::uint32_t end() const { return (this + 1)->begin; }
    };
    /// Checks the cell, sets the origin, dimensions and key bits; returns the finite points.
    std::size_t set_frame(const XyzView& points, double cell);
    /// Cells and rows from the n sorted keys (step 2 of a build), then the row table.
    template <class Key>
    void index_sorted(const Key* sorted, std::size_t n);
    [[nodiscard]] std::int64_t coord(float v, int axis) const;
    /// The key of the cell holding finite point p.
    [[nodiscard]] std::uint64_t cell_key(const pcl::PointXYZ& p) const {
        return pack(coord(p.x, 0), coord(p.y, 1), coord(p.z, 2));
    }
    /// Cell key: x, y, z packed with the fewest bits each axis needs (sorting by key = by x, y, z).
    [[nodiscard]] std::uint64_t pack(std::int64_t x, std::int64_t y, std::int64_t z) const {
        return (static_cast<std::uint64_t>(x) << (bits_[1] + bits_[2])) |
               (static_cast<std::uint64_t>(y) << bits_[2]) | static_cast<std::uint64_t>(z);
    }
    void unpack(std::uint64_t key, std::int64_t out[3]) const;
    [[nodiscard]] bool inside(std::int64_t x, std::int64_t y, std::int64_t z) const {
        return x >= 0 && y >= 0 && z >= 0 && x < dims_[0] && y < dims_[1] && z < dims_[2];
    }
    /// Cells [first, last) of the row (x, y, all z); empty when the row has no points.
    [[nodiscard]] std::pair<std::uint32_t, std::uint32_t> row(std::int64_t x, std::int64_t y) const;
    /// Sequential neighbour-cell enumeration for a run of cells in key order: one row look-up
    /// per neighbouring row when the row changes, then cursors that only move forward.
    struct RowCursor;
    void build_tree() const;
    /// The cells of row (x, y) with z_lo <= z <= z_hi, as [first, last).
    [[nodiscard]] std::pair<const Cell*, const Cell*> row_span(std::int64_t x,
                                                               std::int64_t y,
                                                               std::int64_t z_lo,
                                                               std::int64_t z_hi) const;
    void search(const pcl::PointXYZ& q,
                std::uint32_t self,
                std::size_t k,
                std::vector<std::uint32_t>& idx,
                std::vector<double>& d2) const;
    void tree_knn(const pcl::PointXYZ& q,
                  std::uint32_t self,
                  std::size_t k,
                  std::vector<std::uint32_t>& idx,
                  std::vector<double>& d2) const;

    // A k-d tree over the occupied cells, built on first need: the ring search bounds its work at
    // a few rings, and points far from everything else (floaters) are answered by the tree.
    struct Node {                  // 24 bytes
        std::uint32_t begin, end;  // range of tree_perm_
        std::int32_t left = -1;    // children left and left + 1; -1 = a leaf
        std::uint8_t axis = 0;
        double plane = 0;  // left: points below the plane, right: at or above (up to rounding)
    };
    mutable std::once_flag tree_once_;
    mutable std::vector<Node> nodes_;
    mutable std::vector<std::uint32_t> tree_perm_;  // cell indices

    double cell_ = 1;
    double origin_[3] = {0, 0, 0};
    std::int64_t dims_[3] = {1, 1, 1};      // cells per axis
    int bits_[3] = {0, 0, 0};               // bits per axis in a key
    std::vector<std::uint32_t> row_begin_;  // first cell of each distinct (x, y) row, + sentinel
    std::vector<std::uint64_t> row_key_;    // key >> bits_[2] of each row
    std::vector<std::uint32_t> row_table_;  // open addressing on row keys: row index + 1
    std::vector<float> xyz_;                // sorted by cell, 3 floats per point (unless in place)
    const float* xyz_at_ = nullptr;         // x of sorted position 0: xyz_, or the sorted records
    std::size_t stride_ = 3;                // floats from one sorted position to the next
    std::vector<std::uint32_t> order_;      // original index of each sorted point (in place: all
                                            // points, the non-finite ones after finite_count())
    std::size_t finite_ = 0;
    XyzRecords sorted_;  // the records sorted in place, if in_place_
    bool in_place_ = false;
    bool identity_ = false;    // renumbered: index_of(s) == s, no order kept
    std::vector<Cell> cells_;  // the occupied cells in key order, then the sentinel
    std::uint64_t row_mask_ = 0;
    int row_shift_ = 60;
    XyzView points_;          // the indexed points, for knn(i)
    bool has_points_ = true;  // false when built in place or renumbered: knn(i) throws
};

/// A grid over records with the storage that costs least memory: thin records (at most 16
/// bytes, where a 12-byte copy of x y z would be three quarters of the cloud or more) are sorted
/// in place and put back when the grid is destroyed; richer ones are copied, which is faster
/// (sorting and restoring 1M records costs about 20 ms more than copying x y z).
[[nodiscard]] std::unique_ptr<Grid> grid_over(XyzRecords& records, double cell);

template <class F>
void Grid::for_each_within(const pcl::PointXYZ& q, double radius, F&& f) const {
    for_each_within_if(
        q, radius, [](std::uint32_t) { return true; }, f);
}

template <class Keep, class F>
void Grid::for_each_within_if(const pcl::PointXYZ& q, double radius, Keep&& keep, F&& f) const {
    const double r2 = radius * radius;
    const std::int64_t cx = coord(q.x, 0), cy = coord(q.y, 1), cz = coord(q.z, 2);
    // Nine rows (one hash look-up each), then the cells z - 1 .. z + 1 of each row.
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
            const auto [first, last] = row_span(cx + dx, cy + dy, cz - 1, cz + 1);
            for (const Cell* cell = first; cell < last; ++cell) {
                for (std::uint32_t s = cell->begin; s < cell->end(); ++s) {
                    const std::uint32_t i = index_of(s);
                    if (!keep(i)) {
                        continue;
                    }
                    const float* p = point(s);
                    const double ex = double{p[0]} - q.x;
                    const double ey = double{p[1]} - q.y;
                    const double ez = double{p[2]} - q.z;
                    const double d2 = ex * ex + ey * ey + ez * ez;
                    if (d2 <= r2) {
                        f(i, d2);
                    }
                }
            }
        }
    }
}

}  // namespace pc::search
