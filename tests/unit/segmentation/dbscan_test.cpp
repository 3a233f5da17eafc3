#include <algorithm>
#include <cstring>
#include <map>
#include <memory>
#include <numeric>
#include <stdexcept>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/segmentation/dbscan.h>

#include "support/clouds.h"

namespace pc::segmentation {
namespace {

/// O(n²) DBSCAN with the documented semantics: d² <= eps², min_points counts the point itself,
/// border points join their nearest core point (ties: smallest index). Labels are arbitrary ids.
std::vector<std::int64_t> brute_dbscan(const Cloud& c, double eps, std::size_t min_points) {
    const std::size_t n = c.size();
    std::vector<std::vector<std::size_t>> nb(n);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = 0; j < n && is_finite(c[i]); ++j) {
            if (is_finite(c[j]) && test::dist2(c[i], c[j]) <= eps * eps) {
                nb[i].push_back(j);
            }
        }
    }
    std::vector<bool> core(n);
    for (std::size_t i = 0; i < n; ++i) {
        core[i] = nb[i].size() >= min_points;
    }
    std::vector<std::int64_t> label(n, -1);
    std::int64_t next = 0;
    for (std::size_t s = 0; s < n; ++s) {
        if (!core[s] || label[s] >= 0) {
            continue;
        }
        std::vector<std::size_t> stack = {s};
        label[s] = next;
        while (!stack.empty()) {
            const std::size_t i = stack.back();
            stack.pop_back();
            for (std::size_t j : nb[i]) {
                if (core[j] && label[j] < 0) {
                    label[j] = next;
                    stack.push_back(j);
                }
            }
        }
        ++next;
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (core[i]) {
            continue;
        }
        double best = INFINITY;
        for (std::size_t j : nb[i]) {
            if (core[j] && test::dist2(c[i], c[j]) < best) {
                best = test::dist2(c[i], c[j]);
                label[i] = label[j];
            }
        }
    }
    return label;
}

/// Same partition up to renaming, noise (0 / -1) identical.
void expect_same_partition(const DbscanResult& r, const std::vector<std::int64_t>& ref) {
    std::map<std::uint32_t, std::int64_t> fwd;
    std::map<std::int64_t, std::uint32_t> back;
    for (std::size_t i = 0; i < ref.size(); ++i) {
        ASSERT_EQ(r.labels[i] == kNoise, ref[i] < 0) << "point " << i;
        if (ref[i] < 0) {
            continue;
        }
        const auto [f, fresh_f] = fwd.try_emplace(r.labels[i], ref[i]);
        const auto [b, fresh_b] = back.try_emplace(ref[i], r.labels[i]);
        ASSERT_EQ(f->second, ref[i]) << "point " << i;
        ASSERT_EQ(b->second, r.labels[i]) << "point " << i;
    }
    EXPECT_EQ(r.cluster_count, fwd.size());
}

TEST(Dbscan, MatchesBruteForceOnRandomClouds) {
    const Cloud c = test::uniform(1500, 1.0f, 21);
    for (const auto& [eps, min_points] :
         {std::pair{0.05, 3u}, {0.08, 10u}, {0.03, 1u}, {0.2, 40u}}) {
        const DbscanResult r = dbscan(c, {.eps = eps, .min_points = min_points});
        expect_same_partition(r, brute_dbscan(c, eps, min_points));
    }
}

TEST(Dbscan, MatchesBruteForceOnDenseBlobsNearEachOther) {
    // Many points per cell (cell-local components, cell pairs joined once) and blobs that
    // touch, nearly touch or are bridged by a thin chain.
    Cloud c = test::concat(test::ball({0, 0, 0}, 0.05f, 900, 31),
                           test::ball({0.11f, 0, 0}, 0.05f, 900, 32));
    c = test::concat(c, test::ball({0.3f, 0, 0}, 0.03f, 600, 33));
    for (int i = 0; i < 12; ++i) {
        c.push_back({0.16f + 0.01f * static_cast<float>(i), 0.002f, 0.0f});
    }
    c = test::concat(c, test::uniform(300, 0.5f, 34));
    for (const auto& [eps, min_points] :
         {std::pair{0.01, 5u}, {0.02, 12u}, {0.006, 3u}, {0.05, 60u}}) {
        const DbscanResult r = dbscan(c, {.eps = eps, .min_points = min_points});
        expect_same_partition(r, brute_dbscan(c, eps, min_points));
    }
}

TEST(Dbscan, ThinAndRichRecordsGiveTheSameResultAndAreLeftInPlace) {
    // 12-byte records are sorted in place, 20-byte ones copied (search::grid_over): the same
    // clusters either way, with NaN points, and the records come back byte for byte.
    const DbscanParams p{.eps = 0.05, .min_points = 4};
    Cloud c =
        test::concat(test::uniform(800, 1.0f, 41), test::ball({0.5f, 0.5f, 0.5f}, 0.1f, 400, 42));
    c.push_back(test::nan_point());
    const DbscanResult want = dbscan(c, p);
    expect_same_partition(want, brute_dbscan(c, p.eps, p.min_points));
    for (const std::size_t stride : {12u, 20u}) {
        std::vector<std::uint8_t> bytes = test::records_of(c, stride);
        const std::vector<std::uint8_t> original = bytes;
        XyzRecords records{bytes.data(), stride, c.size(), 0};
        const DbscanResult got = dbscan(records, p);
        EXPECT_EQ(bytes, original) << "stride " << stride;
        EXPECT_EQ(got.labels, want.labels) << "stride " << stride;
        EXPECT_EQ(got.core, want.core) << "stride " << stride;
        EXPECT_EQ(got.cluster_count, want.cluster_count) << "stride " << stride;
    }
}

TEST(Dbscan, PointsAtExactlyEpsAreNeighbours) {
    // Lattice spacing 0.25 (exact in binary): with eps = 0.25 each inner point has 7 neighbours
    // (itself + 6 at exactly eps); corners 4. sklearn's `<=` makes every point core at 4.
    const Cloud c = test::grid({0, 0, 0}, 4, 0.25f);
    const DbscanResult r = dbscan(c, {.eps = 0.25, .min_points = 4});
    EXPECT_EQ(r.cluster_count, 1u);
    EXPECT_EQ(std::count(r.core.begin(), r.core.end(), 1), 64);
    expect_same_partition(r, brute_dbscan(c, 0.25, 4));
    // min_points 5: corners (4 neighbours) become border points, still clustered.
    const DbscanResult r5 = dbscan(c, {.eps = 0.25, .min_points = 5});
    EXPECT_EQ(std::count(r5.core.begin(), r5.core.end(), 1), 56);
    EXPECT_EQ(std::count(r5.labels.begin(), r5.labels.end(), kNoise), 0);
}

TEST(Dbscan, TwoDistantLatticesAreTwoClustersNumberedBySize) {
    const Cloud c = test::concat(test::grid({10, 0, 0}, 3, 0.1f), test::grid({0, 0, 0}, 5, 0.1f));
    const DbscanResult r = dbscan(c, {.eps = 0.15, .min_points = 4});
    EXPECT_EQ(r.cluster_count, 2u);
    EXPECT_EQ(r.labels.front(), 2u);  // the 27-point lattice comes first but is smaller
    EXPECT_EQ(r.labels.back(), 1u);
}

TEST(Dbscan, BorderPointJoinsTheNearestCore) {
    // Two dense clumps; one point between them, within eps of a core point of each, nearer B.
    Cloud c = test::concat(test::grid({0, 0, 0}, 3, 0.01f), test::grid({1, 0, 0}, 3, 0.01f));
    c.push_back({0.52f, 0.01f, 0.01f});
    const DbscanResult r = dbscan(c, {.eps = 0.5, .min_points = 27});
    ASSERT_EQ(r.core.back(), 0);
    expect_same_partition(r, brute_dbscan(c, 0.5, 27));
    EXPECT_EQ(r.labels.back(), r.labels[27]);  // the clump at x = 1
}

TEST(Dbscan, NonFinitePointsAreNoiseAndIsolatedPointsToo) {
    Cloud c = test::grid({0, 0, 0}, 3, 0.1f);
    c.push_back(test::nan_point());
    c.push_back({5, 5, 5});
    const DbscanResult r = dbscan(c, {.eps = 0.15, .min_points = 3});
    EXPECT_EQ(r.labels[27], kNoise);
    EXPECT_EQ(r.labels[28], kNoise);
    EXPECT_EQ(r.cluster_count, 1u);
}

TEST(Dbscan, LabelsAreInvariantUnderTranslation) {
    const Cloud c = test::uniform(500, 1.0f, 22);
    Cloud moved = c;
    for (auto& p : moved.points) {
        p.x += 100;  // exact for these magnitudes? not always: compare partitions, not bits
    }
    const auto a = dbscan(c, {.eps = 0.1, .min_points = 4});
    const auto b = dbscan(moved, {.eps = 0.1, .min_points = 4});
    EXPECT_EQ(a.cluster_count, b.cluster_count);
}

TEST(Dbscan, EstimatedEpsSeparatesTwoBalls) {
    const Cloud c =
        test::concat(test::ball({0, 0, 0}, 1, 3000, 1), test::ball({3, 0, 0}, 1, 3000, 2));
    const double eps = estimate_eps(c, 5);
    EXPECT_GT(eps, 0.0);
    EXPECT_LT(eps, 1.0);
    EXPECT_EQ(dbscan(c, {.eps = eps, .min_points = 5}).cluster_count, 2u);
}

TEST(Dbscan, RejectsNonPositiveEps) {
    EXPECT_THROW((void)dbscan(test::grid({0, 0, 0}, 2, 1.0f), {.eps = 0.0}), InvalidArgument);
    EXPECT_THROW((void)dbscan(test::grid({0, 0, 0}, 2, 1.0f), {.eps = -0.5}), InvalidArgument);
}

}  // namespace
}  // namespace pc::segmentation
