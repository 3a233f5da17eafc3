// core_split: touching solid balls cut at their necks, hollow shells cut into spheres, fragments
// joined; the same partition after scaling and rotating.
#include <cmath>
#include <cstring>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/segmentation/core_split.h>

#include "support/clouds.h"
#include "support/partition.h"

namespace pc::segmentation {
namespace {

using test::few_misassigned;

/// Lattice points (spacing 1) inside a ball: what an explicit voxel reconstruction exports.
void add_solid(Cloud& c,
               std::vector<std::uint32_t>& truth,
               std::vector<std::uint32_t>& label,
               const Eigen::Vector3d& centre,
               double r,
               std::uint32_t id,
               std::uint32_t cluster) {
    for (int i = -8; i <= 8; ++i) {
        for (int j = -8; j <= 8; ++j) {
            for (int k = -8; k <= 8; ++k) {
                const Eigen::Vector3d p(std::floor(centre.x()) + i + 0.5,
                                        std::floor(centre.y()) + j + 0.5,
                                        std::floor(centre.z()) + k + 0.5);
                if ((p - centre).norm() <= r) {
                    c.push_back({static_cast<float>(p.x()), static_cast<float>(p.y()),
                                 static_cast<float>(p.z())});
                    truth.push_back(id);
                    label.push_back(cluster);
                }
            }
        }
    }
}

/// True when `got` and `want` put points together in exactly the same way (labels may differ).
bool same_partition(const std::vector<std::uint32_t>& got, const std::vector<std::uint32_t>& want) {
    std::map<std::uint32_t, std::uint32_t> fwd, back;
    for (std::size_t k = 0; k < got.size(); ++k) {
        if (fwd.emplace(got[k], want[k]).first->second != want[k] ||
            back.emplace(want[k], got[k]).first->second != got[k]) {
            return false;
        }
    }
    return true;
}

struct Scene {
    Cloud cloud;
    std::vector<std::uint32_t> truth, label;
};

/// Three lone balls and a bunch of four touching balls (radius 4.5 voxels; DBSCAN would give one
/// cluster for the bunch).
Scene bunch() {
    Scene s;
    const double r = 4.5;
    add_solid(s.cloud, s.truth, s.label, {0, 0, 0}, r, 1, 1);
    add_solid(s.cloud, s.truth, s.label, {30, 0, 0}, r, 2, 2);
    add_solid(s.cloud, s.truth, s.label, {0, 30, 0}, r, 3, 3);
    const std::array<Eigen::Vector3d, 4> at = {
        Eigen::Vector3d{30, 30, 0}, {39.1, 30, 0}, {34.6, 37.9, 0}, {34.6, 33, 7.6}};
    for (std::uint32_t f = 0; f < 4; ++f) {
        add_solid(s.cloud, s.truth, s.label, at[f], r, 4 + f, 4);
    }
    return s;
}

TEST(CoreSplit, TouchingSolidBallsAreCutAtTheirNecks) {
    const Scene s = bunch();
    const CoreSplitResult r = core_split(s.cloud, s.label, {});
    EXPECT_EQ(r.cluster_count, 7u);
    EXPECT_EQ(r.splits, 1u);
    EXPECT_NEAR(r.spacing, 1.0, 1e-6);
    EXPECT_TRUE(few_misassigned(r.labels, s.truth, 100));  // a few points at the necks
}

TEST(CoreSplit, SparseLabelValuesGiveTheResultOfDenseOnes) {
    // Sparse label values and noise between clusters: the clusters are compacted first, so the
    // partition is that of the same labels numbered densely.
    Scene s = bunch();
    std::vector<std::uint32_t> label = s.label, dense = s.label;
    for (std::size_t i = 0; i < label.size(); ++i) {
        label[i] = i % 13 == 0 ? 0 : 7 * label[i] + 3;
        dense[i] = i % 13 == 0 ? 0 : dense[i];
    }
    const CoreSplitResult viewed = core_split(s.cloud, label, {});
    const CoreSplitResult compact = core_split(s.cloud, dense, {});
    EXPECT_EQ(compact.labels, viewed.labels);
    EXPECT_EQ(compact.depth, viewed.depth);
    EXPECT_EQ(compact.cluster_count, viewed.cluster_count);
    EXPECT_EQ(compact.splits, viewed.splits);
    EXPECT_GE(viewed.splits, 1u);
    // The same points seen through a subset view (all of them, in order).
    std::vector<std::uint32_t> all(s.cloud.size());
    std::iota(all.begin(), all.end(), 0u);
    const CoreSplitResult through = core_split(XyzView(s.cloud).subset(all), label, {});
    EXPECT_EQ(through.labels, viewed.labels);
}

TEST(CoreSplit, ASubsetViewGivesWhatACopyOfItsPointsGives) {
    // core_split works on the clustered points in cell order and returns its arrays to point
    // order: through a view of a subset (its indices composed, then reordered beside the
    // compaction's) the result must be the copy's, point for point.
    const Scene s = bunch();
    std::vector<std::uint32_t> pick;
    for (std::uint32_t i = 0; i < s.cloud.size(); ++i) {
        if (i % 5 != 3) {
            pick.push_back(i);
        }
    }
    Cloud copy;
    std::vector<std::uint32_t> label;
    for (const auto i : pick) {
        copy.push_back(s.cloud[i]);
        label.push_back(s.label[i]);
    }
    const CoreSplitResult copied = core_split(copy, label, {});
    const CoreSplitResult viewed = core_split(XyzView(s.cloud).subset(pick), label, {});
    EXPECT_EQ(viewed.labels, copied.labels);
    EXPECT_EQ(viewed.depth, copied.depth);
    EXPECT_EQ(viewed.spacing, copied.spacing);
    EXPECT_EQ(copied.cluster_count, 7u);
    EXPECT_GE(copied.splits, 1u);
}

TEST(CoreSplit, SamePartitionWhenScaledOrRotated) {
    const Scene s = bunch();
    const CoreSplitResult base = core_split(s.cloud, s.label, {});
    const Eigen::Matrix3d rot =
        Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    for (const auto& [name, m] : std::vector<std::pair<std::string, Eigen::Matrix3d>>{
             {"x0.25", 0.25 * Eigen::Matrix3d::Identity()},
             {"x4", 4.0 * Eigen::Matrix3d::Identity()},
             {"rotated", rot}}) {
        Cloud t;
        for (const auto& p : s.cloud) {
            const Eigen::Vector3d q = m * Eigen::Vector3d(p.x, p.y, p.z);
            t.push_back(
                {static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z())});
        }
        const CoreSplitResult r = core_split(t, s.label, {});
        EXPECT_EQ(r.cluster_count, base.cluster_count) << name;
        EXPECT_TRUE(few_misassigned(r.labels, s.truth, 100)) << name;
    }
}

TEST(CoreSplit, HollowShellsAreCutIntoSpheres) {
    // Surface points only (a NeRF-like export): three lone shells and a touching pair in one
    // cluster.
    Cloud c;
    std::vector<std::uint32_t> truth, label;
    const auto shell = [&](float x, float y, std::uint32_t id, std::uint32_t cluster,
                           unsigned seed) {
        for (const auto& p : test::sphere_shell(1.0f, 600, seed)) {
            c.push_back({p.x + x, p.y + y, p.z});
            truth.push_back(id);
            label.push_back(cluster);
        }
    };
    shell(0, 0, 1, 1, 1);
    shell(10, 0, 2, 2, 2);
    shell(0, 10, 3, 3, 3);
    shell(10, 10, 4, 4, 4);
    shell(12.05f, 10, 5, 4, 5);
    const CoreSplitResult r = core_split(c, label, {});
    EXPECT_EQ(r.cluster_count, 5u);
    EXPECT_EQ(r.hollow_splits, 1u);
    EXPECT_NEAR(r.hollow_radius, 1.0, 0.05);
    EXPECT_TRUE(few_misassigned(r.labels, truth, 50));  // points near the contact may go either way
}

TEST(CoreSplit, FragmentsOfOneFruitAreJoined) {
    // Two caps cut from one ball (labelled apart, as DBSCAN leaves them) next to whole balls.
    Scene s;
    add_solid(s.cloud, s.truth, s.label, {0, 0, 0}, 4.5, 1, 1);
    add_solid(s.cloud, s.truth, s.label, {30, 0, 0}, 4.5, 2, 2);
    add_solid(s.cloud, s.truth, s.label, {0, 30, 0}, 4.5, 3, 3);
    Scene whole;
    add_solid(whole.cloud, whole.truth, whole.label, {30, 30, 0}, 4.5, 4, 4);
    for (std::size_t k = 0; k < whole.cloud.size(); ++k) {
        const float x = whole.cloud[k].x - 30;
        if (std::abs(x) > 1.2f) {  // drop a slab through the middle: two caps 3 voxels apart
            s.cloud.push_back(whole.cloud[k]);
            s.truth.push_back(4);
            s.label.push_back(x < 0 ? 4 : 5);
        }
    }
    const CoreSplitResult r = core_split(s.cloud, s.label, {});
    EXPECT_EQ(r.merged_fragments, 1u);
    EXPECT_EQ(r.cluster_count, 4u);
    EXPECT_TRUE(same_partition(r.labels, s.truth));
    CoreSplitParams off;
    off.merge_fragments = false;
    EXPECT_EQ(core_split(s.cloud, s.label, off).cluster_count, 5u);
}

TEST(CoreSplit, NoiseStaysNoiseAndBadParametersAreRefused) {
    Scene s = bunch();
    s.cloud.push_back({100, 100, 100});
    s.label.push_back(0);
    s.truth.push_back(0);
    const CoreSplitResult r = core_split(s.cloud, s.label, {});
    EXPECT_EQ(r.labels.back(), 0u);
    CoreSplitParams bad;
    bad.core_fraction = 1.5;
    EXPECT_THROW((void)core_split(s.cloud, s.label, bad), InvalidArgument);
    EXPECT_THROW((void)core_split(s.cloud, std::vector<std::uint32_t>(3, 1), {}), InvalidArgument);
    EXPECT_EQ(core_split(Cloud{}, std::vector<std::uint32_t>{}, {}).cluster_count, 0u);
}

}  // namespace
}  // namespace pc::segmentation
