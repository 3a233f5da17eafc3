#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <random>
#include <stdexcept>
#include <tuple>

#include <gtest/gtest.h>

#include <pc/search/grid.h>
#include <pc/search/spacing.h>

#include "support/clouds.h"

namespace pc::search {
namespace {

/// Brute-force k nearest others of point i, ordered by (d², index).
std::vector<std::pair<double, std::uint32_t>> brute_knn(const Cloud& c,
                                                        std::uint32_t i,
                                                        std::size_t k) {
    std::vector<std::pair<double, std::uint32_t>> all;
    for (std::uint32_t j = 0; j < c.size(); ++j) {
        if (j != i && is_finite(c[j])) {
            all.push_back({test::dist2(c[i], c[j]), j});
        }
    }
    std::sort(all.begin(), all.end());
    all.resize(std::min(k, all.size()));
    return all;
}

/// grid.knn(i) for every `stride`-th point equals the brute force over `c` (the grid's points,
/// in its numbering).
void expect_grid_knn_is_brute_force(const Grid& grid,
                                    const Cloud& c,
                                    std::size_t k,
                                    std::uint32_t stride = 1) {
    std::vector<std::uint32_t> idx;
    std::vector<double> d2;
    for (std::uint32_t i = 0; i < c.size(); i += stride) {
        grid.knn(i, k, idx, d2);
        if (!is_finite(c[i])) {
            EXPECT_TRUE(idx.empty());
            continue;
        }
        const auto ref = brute_knn(c, i, k);
        ASSERT_EQ(idx.size(), ref.size()) << "point " << i;
        for (std::size_t m = 0; m < ref.size(); ++m) {
            EXPECT_EQ(d2[m], ref[m].first) << "point " << i << " rank " << m;
            EXPECT_EQ(idx[m], ref[m].second) << "point " << i << " rank " << m;
        }
    }
}

void expect_knn_matches_brute_force(const Cloud& c, std::size_t k, double cell) {
    expect_grid_knn_is_brute_force(Grid(c, cell), c, k);
}

TEST(Grid, KnnMatchesBruteForceOnRandomClouds) {
    const Cloud c = test::uniform(1500, 1.0f, 3);
    for (double cell : {0.01, 0.05, 0.3, 2.0, Grid::suggest_cell(c)}) {
        expect_knn_matches_brute_force(c, 6, cell);
    }
}

TEST(Grid, WorksOnAStridedViewWithFieldsInAnyOrder) {
    // Records of 20 bytes holding z, 4 other bytes, x, y: a PCD blob's layout, read in place.
    const Cloud c = test::uniform(800, 1.0f, 5);
    std::vector<std::uint8_t> bytes(c.size() * 20, 0xAB);
    for (std::size_t i = 0; i < c.size(); ++i) {
        std::memcpy(&bytes[20 * i], &c[i].z, 4);
        std::memcpy(&bytes[20 * i + 8], &c[i].x, 4);
        std::memcpy(&bytes[20 * i + 12], &c[i].y, 4);
    }
    XyzView view;
    view.base = bytes.data();
    view.stride = 20;
    view.size = c.size();
    view.offset[0] = 8;
    view.offset[1] = 12;
    view.offset[2] = 0;
    EXPECT_EQ(Grid::suggest_cell(view), Grid::suggest_cell(c));
    expect_grid_knn_is_brute_force(Grid(view, 0.1), c, 5);
}

TEST(Grid, KnnMatchesBruteForceWhateverTheKeyWidthAndSortPasses) {
    // Unit cube: 500 cells per axis = 27-bit keys sorted in 3 passes (odd: the order comes back
    // from the scratch); 5000 = 39 bits (64-bit keys, 4 passes); 200000 = 54 bits (5 passes).
    const Cloud c = test::uniform(400, 1.0f, 8);
    for (double cell : {0.002, 2e-4, 5e-6}) {
        expect_knn_matches_brute_force(c, 4, cell);
    }
}

TEST(Grid, LargeCloudsAreSortedOnTwoThreadsWithTheSameNeighbours) {
    // Above 65536 points each sort pass splits the input between two threads. A tube along the
    // diagonal of a 1000-cell cube: 30-bit keys (3 passes, the order coming back from the
    // scratch), ~5 points per occupied cell (answered by the ring search, which needs the cells
    // sorted), and duplicates (the sort must be stable).
    std::mt19937 rng(12);
    std::uniform_real_distribution<float> along(0.0f, 1000.0f), across(-1.0f, 1.0f);
    Cloud c;
    for (int i = 0; i < 70000; ++i) {
        const float t = along(rng);
        c.push_back({t + across(rng), t + across(rng), t + across(rng)});
    }
    for (std::size_t i = 0; i < 2000; ++i) {
        c.push_back(c[7 * i]);
    }
    expect_grid_knn_is_brute_force(Grid(c, 1.0), c, 3, 1201);
}

TEST(Grid, WorksOnASubsetOfAView) {
    // Every third point, in reverse: the grid numbers them by their place in the subset.
    const Cloud c = test::uniform(900, 1.0f, 9);
    std::vector<std::uint32_t> pick;
    for (std::uint32_t i = 900; i >= 3; i -= 3) {
        pick.push_back(i - 1);
    }
    Cloud copy;
    for (auto i : pick) {
        copy.push_back(c[i]);
    }
    const XyzView view = XyzView(c).subset(pick);
    ASSERT_EQ(view.size, pick.size());
    EXPECT_EQ(median_spacing(view), median_spacing(copy));
    for (std::uint32_t i = 0; i < copy.size(); ++i) {
        EXPECT_EQ(view[i].x, copy[i].x);
        EXPECT_EQ(view.record(i), reinterpret_cast<const std::uint8_t*>(&c.points[pick[i]]));
    }
    expect_grid_knn_is_brute_force(Grid(view, 0.1), copy, 5);
    EXPECT_THROW((void)view.subset(pick), std::logic_error);  // no subset of a subset
}

TEST(Grid, NeighbourCellsAreTheBlockAroundACellNearestRowsFirst) {
    const Cloud c = test::uniform(3000, 1.0f, 10);
    const double cell = 0.1;
    double origin[3] = {1e9, 1e9, 1e9};
    for (const auto& p : c) {
        origin[0] = std::min(origin[0], double{p.x});
        origin[1] = std::min(origin[1], double{p.y});
        origin[2] = std::min(origin[2], double{p.z});
    }
    const Grid grid(c, cell);
    const auto at = [&](std::size_t cc) {
        const float* p = grid.point(grid.cell_begin(cc));
        std::array<long, 3> v{};
        for (int a = 0; a < 3; ++a) {
            v[a] = static_cast<long>(std::floor((double{p[a]} - origin[a]) / cell));
        }
        return v;
    };
    std::vector<std::uint32_t> nb;
    for (std::size_t cc = 0; cc < grid.cell_count(); ++cc) {
        grid.neighbour_cells(cc, nb);
        const auto here = at(cc);
        std::vector<std::uint32_t> expected;
        for (std::size_t o = 0; o < grid.cell_count(); ++o) {
            const auto there = at(o);
            if (std::abs(there[0] - here[0]) <= 1 && std::abs(there[1] - here[1]) <= 1 &&
                std::abs(there[2] - here[2]) <= 1) {
                expected.push_back(static_cast<std::uint32_t>(o));
            }
        }
        std::vector<std::uint32_t> got = nb;
        std::sort(got.begin(), got.end());
        ASSERT_EQ(got, expected) << "cell " << cc;
        int last = 0;  // 0: own row, 1: a row sharing a face, 2: a diagonal row
        for (auto o : nb) {
            const auto there = at(o);
            const int kind =
                static_cast<int>(std::abs(there[0] - here[0]) + std::abs(there[1] - here[1]));
            EXPECT_GE(kind, last) << "cell " << cc;
            last = kind;
        }
    }
    // A sweep handing over the cells after c: exactly those of the block above c.
    std::mutex mutex;
    std::size_t seen = 0;
    grid.sweep_cells(
        [&](std::uint32_t cc, const std::vector<std::uint32_t>& after) {
            std::vector<std::uint32_t> all;
            grid.neighbour_cells(cc, all);
            std::vector<std::uint32_t> expected;
            for (auto o : all) {
                if (o > cc) {
                    expected.push_back(o);
                }
            }
            std::vector<std::uint32_t> got = after;
            std::sort(got.begin(), got.end());
            std::sort(expected.begin(), expected.end());
            const std::lock_guard<std::mutex> lock(mutex);
            EXPECT_EQ(got, expected) << "cell " << cc;
            ++seen;
        },
        {}, Grid::Neighbours::kAfter);
    EXPECT_EQ(seen, grid.cell_count());
}

TEST(Grid, KnnBreaksTiesByIndexOnALattice) {
    // Every inner lattice point has 6 neighbours at exactly the same distance.
    expect_knn_matches_brute_force(test::grid({0, 0, 0}, 6, 0.1f), 4, 0.1);
    expect_knn_matches_brute_force(test::grid({0, 0, 0}, 6, 0.1f), 7, 0.25);
}

TEST(Grid, KnnHandlesDuplicatesNanAndTinyClouds) {
    Cloud c = test::uniform(50, 1.0f, 4);
    c.push_back(c[3]);
    c.push_back(c[3]);
    c.push_back(test::nan_point());
    expect_knn_matches_brute_force(c, 5, 0.2);
    Cloud two;
    two.push_back({0, 0, 0});
    two.push_back({1, 0, 0});
    expect_knn_matches_brute_force(two, 5, 0.1);  // fewer than k others
}

TEST(Grid, RadiusQueryMatchesBruteForceIncludingExactDistances) {
    const Cloud c = test::concat(test::grid({0, 0, 0}, 5, 0.25f), test::uniform(300, 1.0f, 5));
    for (double r : {0.25, 0.1, 0.4}) {
        const Grid grid(c, r);
        for (std::uint32_t i = 0; i < c.size(); ++i) {
            std::vector<std::uint32_t> got;
            grid.for_each_within(c[i], r, [&](std::uint32_t j, double) { got.push_back(j); });
            std::sort(got.begin(), got.end());
            // The filtered form: the points the predicate accepts, each asked about once.
            std::vector<std::uint32_t> odd, asked;
            grid.for_each_within_if(
                c[i], r,
                [&](std::uint32_t j) {
                    asked.push_back(j);
                    return j % 2 == 1;
                },
                [&](std::uint32_t j, double d2) {
                    EXPECT_EQ(d2, test::dist2(c[i], c[j]));
                    odd.push_back(j);
                });
            std::sort(odd.begin(), odd.end());
            std::sort(asked.begin(), asked.end());
            EXPECT_TRUE(std::adjacent_find(asked.begin(), asked.end()) == asked.end());
            std::vector<std::uint32_t> want, want_odd;
            for (std::uint32_t j = 0; j < c.size(); ++j) {
                if (test::dist2(c[i], c[j]) <= r * r) {
                    want.push_back(j);
                    if (j % 2 == 1) {
                        want_odd.push_back(j);
                    }
                }
            }
            ASSERT_EQ(got, want) << "point " << i << " r " << r;
            ASSERT_EQ(odd, want_odd) << "point " << i << " r " << r;
            ASSERT_TRUE(std::includes(asked.begin(), asked.end(), want.begin(), want.end()));
        }
    }
}

/// Dense blobs, a lattice, a sparse scatter and far floaters: every path of all_knn (the 3x3x3
/// block, the next ring, the k-d tree for isolated points) is taken.
Cloud mixed_density_cloud() {
    Cloud c =
        test::concat(test::ball({0, 0, 0}, 0.05f, 1500, 7), test::grid({0.2f, 0, 0}, 6, 0.02f));
    c = test::concat(c, test::uniform(200, 1.0f, 8));
    c.push_back({5, 5, 5});
    c.push_back({-3, 2, 0});
    c.push_back(test::nan_point());
    return c;
}

TEST(Grid, AllKnnMatchesBruteForceAcrossDensities) {
    const Cloud c = mixed_density_cloud();
    for (std::size_t k : {1u, 5u, 12u}) {
        for (double cell : {0.005, 0.02, Grid::suggest_cell(c)}) {
            const Grid grid(c, cell);
            std::vector<int> seen(c.size(), 0);
            std::mutex m;
            grid.all_knn(k, [&](std::uint32_t i, const std::vector<std::uint32_t>& idx,
                                const std::vector<double>& d2) {
                const auto ref = brute_knn(c, i, k);
                const std::lock_guard<std::mutex> lock(m);
                ++seen[i];
                ASSERT_EQ(idx.size(), ref.size()) << "point " << i;
                for (std::size_t r = 0; r < ref.size(); ++r) {
                    EXPECT_EQ(d2[r], ref[r].first) << "point " << i << " rank " << r;
                    EXPECT_EQ(idx[r], ref[r].second) << "point " << i << " rank " << r;
                }
            });
            for (std::uint32_t i = 0; i < c.size(); ++i) {
                EXPECT_EQ(seen[i], is_finite(c[i]) ? 1 : 0) << "point " << i;
            }
        }
    }
}

/// Checks an in-place grid over `c` (as records of `stride` bytes, x at `offset`) against the
/// copying grid: the records are whole and in cell order, the answers are the same, and
/// the destructor gives back the original bytes.
void expect_in_place_grid_equals_copy(const Cloud& c,
                                      double cell,
                                      std::size_t stride,
                                      std::uint32_t offset) {
    SCOPED_TRACE("stride " + std::to_string(stride) + ", cell " + std::to_string(cell));
    std::vector<std::uint8_t> bytes = test::records_of(c, stride, offset);
    const std::vector<std::uint8_t> original = bytes;
    XyzRecords records{bytes.data(), stride, c.size(), offset};
    const Grid copy(c, cell);
    auto grid_ptr = std::make_unique<Grid>(records, cell);
    Grid& grid = *grid_ptr;
    ASSERT_EQ(grid.finite_count(), copy.finite_count());
    ASSERT_EQ(grid.cell_count(), copy.cell_count());
    EXPECT_EQ(grid.point_stride(), stride / 4);
    for (std::uint32_t s = 0; s < grid.finite_count(); ++s) {
        // Each sorted record is a whole original one, its coordinates where point() says.
        const std::uint32_t i = grid.index_of(s);
        ASSERT_EQ(0, std::memcmp(&bytes[s * stride], &original[i * stride], stride))
            << "position " << s;
        EXPECT_EQ(grid.point(s), reinterpret_cast<const float*>(&bytes[s * stride + offset]));
    }
    for (std::size_t k = 0; k < grid.cell_count(); ++k) {
        // The same cells, holding the same points (the order within a cell may differ).
        std::vector<std::uint32_t> a, b;
        for (std::uint32_t s = grid.cell_begin(k); s < grid.cell_end(k); ++s) {
            a.push_back(grid.index_of(s));
        }
        for (std::uint32_t s = copy.cell_begin(k); s < copy.cell_end(k); ++s) {
            b.push_back(copy.index_of(s));
        }
        std::sort(a.begin(), a.end());
        std::sort(b.begin(), b.end());
        ASSERT_EQ(a, b) << "cell " << k;
    }
    std::vector<std::uint32_t> idx_a, idx_b;
    std::vector<double> d2_a, d2_b;
    for (std::size_t i = 0; i < c.size(); i += 97) {
        grid.knn_point(c[i], 6, idx_a, d2_a);
        copy.knn_point(c[i], 6, idx_b, d2_b);
        EXPECT_EQ(idx_a, idx_b) << "query " << i;
        EXPECT_EQ(d2_a, d2_b) << "query " << i;
    }
    std::vector<std::vector<std::uint32_t>> all_a(c.size()), all_b(c.size());
    grid.all_knn(4, [&](std::uint32_t i, const std::vector<std::uint32_t>& idx,
                        const std::vector<double>&) { all_a[i] = idx; });
    copy.all_knn(4, [&](std::uint32_t i, const std::vector<std::uint32_t>& idx,
                        const std::vector<double>&) { all_b[i] = idx; });
    EXPECT_EQ(all_a, all_b);
    EXPECT_THROW(grid.knn(0, 3, idx_a, d2_a), std::logic_error);  // the records have moved
    grid_ptr.reset();
    EXPECT_EQ(bytes, original);
    {
        // With each cell put in index order, the in-place grid's positions are the copying grid's.
        Grid ordered(records, cell);
        ordered.order_cells_by_index();
        for (std::uint32_t s = 0; s < ordered.finite_count(); ++s) {
            ASSERT_EQ(ordered.index_of(s), copy.index_of(s)) << "position " << s;
            ASSERT_EQ(0,
                      std::memcmp(&bytes[s * stride], &original[copy.index_of(s) * stride], stride))
                << "position " << s;
        }
        EXPECT_EQ(median_spacing(ordered), median_spacing(copy));
    }
    EXPECT_EQ(bytes, original);
}

TEST(Grid, InPlaceSortsWholeRecordsAnswersAsTheCopyAndPutsThemBack) {
    // Records of x y z only, + 2 fields (the sort's fixed sizes), and of odd sizes with x not
    // first (the general path; 264 bytes: too large to be moved through a buffer when a cell
    // is put in index order); NaN points go after the finite ones.
    Cloud c = mixed_density_cloud();
    c.push_back(test::nan_point());
    c.push_back(c[3]);  // a duplicate
    for (const auto& [stride, offset] :
         {std::pair<std::size_t, std::uint32_t>{12, 0}, {20, 8}, {44, 16}, {264, 100}}) {
        for (double cell : {0.005, 0.02}) {
            expect_in_place_grid_equals_copy(c, cell, stride, offset);
        }
    }
}

TEST(Grid, InPlaceCellsInIndexOrderHoldManyEqualPoints) {
    // Cells of hundreds of points, many of them equal (the order within such a cell is all the
    // in-place sort leaves to chance).
    Cloud c = test::uniform(20000, 1.0f, 31);
    for (std::size_t i = 0; i < c.size(); i += 3) {
        c[i] = c[i / 100];
    }
    expect_in_place_grid_equals_copy(c, 0.2, 16, 0);
    Grid copy(c, 0.1);
    EXPECT_THROW(copy.order_cells_by_index(), std::logic_error);
}

TEST(Grid, MedianSpacingIsTheMedianNearestOtherDistanceOfStridedSamples) {
    // Brute force over the samples a copying grid of the suggested cell takes (every stride-th
    // position); points with a coincident other point are skipped.
    Cloud c = test::uniform(5000, 1.0f, 33);
    for (std::size_t i = 0; i < 400; ++i) {
        c[i + 1000] = c[i];
    }
    const Grid grid(c, Grid::suggest_cell(c, 16));
    const std::size_t samples = 700, stride = c.size() / samples;
    std::vector<double> d;
    for (std::size_t s = 0; s < c.size(); s += stride) {
        const auto& p = c[grid.index_of(static_cast<std::uint32_t>(s))];
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t j = 0; j < c.size(); ++j) {
            if (j != grid.index_of(static_cast<std::uint32_t>(s))) {
                const double ex = double{c[j].x} - p.x, ey = double{c[j].y} - p.y,
                             ez = double{c[j].z} - p.z;
                best = std::min(best, ex * ex + ey * ey + ez * ez);
            }
        }
        if (best > 0) {
            d.push_back(std::sqrt(best));
        }
    }
    std::sort(d.begin(), d.end());
    const std::size_t mid = (d.size() - 1) / 2;  // numpy's median, as pc::median computes it
    const double want = d.size() % 2 ? d[mid] : d[mid] + 0.5 * (d[mid + 1] - d[mid]);
    EXPECT_EQ(median_spacing(c, samples), want);
    EXPECT_EQ(median_spacing(grid, samples), want);
}

TEST(Grid, InPlaceSortsFewRecordsWithRepeatedKeys) {
    // Cells z = 0, 2, 0: three keys spanning exactly 3 values, not distinct (only putting
    // records back, by their distinct original indices, may place them by key directly).
    Cloud c;
    c.push_back({0, 0, 0.1f});
    c.push_back({0, 0, 2.5f});
    c.push_back({0, 0, 0.2f});
    expect_in_place_grid_equals_copy(c, 1.0, 12, 0);
}

TEST(Grid, InPlaceSortsLargeCloudsAndWideKeys) {
    // 70000 points: more than a cache-sized bucket, so the in-place radix levels (and their two
    // threads) run before the buckets are sorted aside; 2e-4 cells in a unit cube: 39-bit keys.
    const Cloud c = test::uniform(70000, 1.0f, 13);
    expect_in_place_grid_equals_copy(c, 0.01, 16, 0);
    expect_in_place_grid_equals_copy(test::uniform(3000, 1.0f, 14), 2e-4, 12, 0);
}

TEST(Grid, InPlaceHandlesNonFinitePointsAndWideKeys) {
    // Non-finite points sort after the finite ones and come back to their places (32- and
    // 39-bit keys, records of 12 and 16 bytes).
    Cloud c = mixed_density_cloud();
    c.push_back(test::nan_point());
    for (double cell : {0.02, 2e-6}) {
        expect_in_place_grid_equals_copy(c, cell, 12, 0);
        expect_in_place_grid_equals_copy(c, cell, 16, 0);
    }
}

TEST(Grid, InPlaceChecksItsRecords) {
    const Cloud c = test::uniform(50, 1.0f, 3);
    std::vector<std::uint8_t> bytes = test::records_of(c, 16, 0);
    XyzRecords odd_stride{bytes.data(), 14, 50, 0};
    XyzRecords odd_offset{bytes.data(), 16, 50, 6};
    EXPECT_THROW(Grid(odd_stride, 0.1), std::logic_error);
    EXPECT_THROW(Grid(odd_offset, 0.1), std::logic_error);
}

TEST(Grid, InPlacePutsTheRecordsBackWhenUnwinding) {
    // The guard: an exception thrown while the records are in cell order leaves them in their
    // original order.
    const Cloud c = test::uniform(5000, 1.0f, 8);
    std::vector<std::uint8_t> bytes = test::records_of(c, 16, 0);
    const std::vector<std::uint8_t> original = bytes;
    XyzRecords records{bytes.data(), 16, c.size(), 0};
    try {
        const Grid grid(records, 0.05);
        ASSERT_NE(bytes, original);  // sorted into cell order
        throw std::runtime_error("mid-search");
    } catch (const std::runtime_error&) {
    }
    EXPECT_EQ(bytes, original);
}

TEST(Grid, OverThinRecordsSortsInPlaceOverRichOnesCopies) {
    const Cloud c = test::uniform(2000, 1.0f, 9);
    for (const std::size_t stride : {12u, 16u, 20u}) {
        std::vector<std::uint8_t> bytes = test::records_of(c, stride, 0);
        const std::vector<std::uint8_t> original = bytes;
        XyzRecords records{bytes.data(), stride, c.size(), 0};
        {
            const auto grid = grid_over(records, 0.05);
            const bool in_place = grid->point(0) == reinterpret_cast<const float*>(bytes.data());
            EXPECT_EQ(in_place, stride <= 16) << "stride " << stride;
            EXPECT_EQ(grid->finite_count(), c.size());
        }
        EXPECT_EQ(bytes, original) << "stride " << stride;
    }
}

TEST(Grid, RenumberedByPositionItAnswersForTheCloudInCellOrder) {
    // The caller moves point index_of(s) to place s; the renumbered grid then answers for that
    // reordered cloud exactly what a grid built over it answers, and radius queries name the
    // same points as before, by their new numbers.
    const Cloud c = test::uniform(3000, 1.0f, 21);
    const double cell = 0.08;
    Grid grid(c, cell);
    Cloud sorted;
    std::vector<std::uint32_t> old(c.size());
    for (std::uint32_t s = 0; s < c.size(); ++s) {
        old[s] = grid.index_of(s);
        sorted.push_back(c[old[s]]);
    }
    const Grid before(c, cell);
    grid.renumber_by_position();
    const Grid rebuilt(sorted, cell);
    std::vector<std::uint32_t> idx, ref_idx;
    std::vector<double> d2, ref_d2;
    for (std::uint32_t s = 0; s < sorted.size(); s += 7) {
        EXPECT_EQ(grid.index_of(s), s);
        EXPECT_EQ(rebuilt.index_of(s), s);  // the sort is stable: cell order is kept
        std::vector<std::pair<std::uint32_t, double>> got, want;
        grid.for_each_within(sorted[s], cell,
                             [&](std::uint32_t j, double d) { got.emplace_back(old[j], d); });
        before.for_each_within(sorted[s], cell,
                               [&](std::uint32_t j, double d) { want.emplace_back(j, d); });
        EXPECT_EQ(got, want) << "position " << s;
        grid.knn_point(sorted[s], 4, idx, d2);
        rebuilt.knn_point(sorted[s], 4, ref_idx, ref_d2);
        EXPECT_EQ(idx, ref_idx);
        EXPECT_EQ(d2, ref_d2);
    }
    EXPECT_THROW(grid.knn(0, 3, idx, d2), std::logic_error);  // the old view is forgotten
    Cloud with_nan = c;
    with_nan[5].x = std::numeric_limits<float>::quiet_NaN();
    Grid partial(with_nan, cell);
    EXPECT_THROW(partial.renumber_by_position(), std::logic_error);
    // Built in place, the records stay in cell order, also after the grid is gone.
    std::vector<std::uint8_t> bytes = test::records_of(c, 16, 0);
    XyzRecords records{bytes.data(), 16, c.size(), 0};
    auto in_place_ptr = std::make_unique<Grid>(records, cell);
    Grid& in_place = *in_place_ptr;
    in_place.order_cells_by_index();
    in_place.renumber_by_position();
    for (std::uint32_t s = 0; s < sorted.size(); s += 7) {
        EXPECT_EQ(in_place.index_of(s), s);
        EXPECT_EQ(records.view()[s].x, sorted[s].x);
        std::vector<std::uint32_t> got, want;
        in_place.for_each_within(sorted[s], cell,
                                 [&](std::uint32_t j, double) { got.push_back(j); });
        rebuilt.for_each_within(sorted[s], cell,
                                [&](std::uint32_t j, double) { want.push_back(j); });
        EXPECT_EQ(got, want) << "position " << s;
    }
    in_place_ptr.reset();
    for (std::uint32_t s = 0; s < sorted.size(); s += 7) {
        EXPECT_EQ(records.view()[s].x, sorted[s].x);
    }
    std::vector<std::uint8_t> nan_bytes = test::records_of(with_nan, 16, 0);
    XyzRecords nan_records{nan_bytes.data(), 16, c.size(), 0};
    Grid in_place_nan(nan_records, cell);
    EXPECT_THROW(in_place_nan.renumber_by_position(), std::logic_error);
}

TEST(Grid, RebuiltOverACloudInItsCellOrderItKeepsEveryPointInPlace) {
    // A copying grid's sort is stable, also on two threads (clouds of 2^16 points and more) and
    // with 64-bit keys: rebuilt over points already in its cell order, it keeps them in place.
    for (const auto& [points, cell] : std::vector<std::pair<std::uint32_t, double>>{
             {3000, 0.08}, {120000, 0.02}, {120000, 2e-6}}) {
        const Cloud c = test::uniform(points, 1.0f, 23);
        const Grid first(c, cell);
        Cloud sorted;
        for (std::uint32_t s = 0; s < c.size(); ++s) {
            sorted.push_back(c[first.index_of(s)]);
        }
        const Grid rebuilt(sorted, cell);
        std::uint32_t moved = 0;
        for (std::uint32_t s = 0; s < sorted.size(); ++s) {
            moved += rebuilt.index_of(s) != s || rebuilt.point(s)[0] != sorted[s].x;
        }
        EXPECT_EQ(moved, 0u) << points << " points, cell " << cell;
    }
}

/// Mean over the points of how many points share their cell.
double point_occupancy(const Cloud& c, double cell) {
    std::map<std::tuple<long, long, long>, int> count;
    for (const auto& p : c) {
        ++count[{std::lround(std::floor(p.x / cell)), std::lround(std::floor(p.y / cell)),
                 std::lround(std::floor(p.z / cell))}];
    }
    double sum = 0;
    for (const auto& [key, n] : count) {
        sum += static_cast<double>(n) * n;
    }
    return sum / static_cast<double>(c.size());
}

TEST(Grid, SuggestedCellGivesTheTargetOccupancyOnVolumesAndSurfaces) {
    Cloud plane;
    for (int i = 0; i < 300; ++i) {
        for (int j = 0; j < 300; ++j) {
            plane.push_back({0.01f * static_cast<float>(i), 0.01f * static_cast<float>(j), 0.0f});
        }
    }
    for (const Cloud& c : {test::uniform(90000, 1.0f, 9), plane}) {
        for (double target : {4.0, 8.0}) {
            const double occ = point_occupancy(c, Grid::suggest_cell(c, target));
            EXPECT_GT(occ, target / 2);
            EXPECT_LT(occ, target * 2);
        }
    }
}

TEST(Grid, HugeExtentEnlargesCellsInsteadOfFailing) {
    Cloud c = test::uniform(100, 1.0f, 6);
    c.push_back({1e7f, 0, 0});
    const Grid grid(c, 1e-4);
    EXPECT_GT(grid.cell(), 1e-4);
    expect_knn_matches_brute_force(c, 3, 1e-4);
}

}  // namespace
}  // namespace pc::search
