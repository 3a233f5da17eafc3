#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/io/points.h>
#include <pc/pipeline/steps.h>

#include "support/synthetic.h"

namespace pc::pipeline {
namespace {

using F = pcl::PCLPointField;

/// x y z, an unknown field `quality` F 8 and packed rgb: points 0..n-1 along x, colour by parity.
io::Blob line_cloud(std::size_t n) {
    io::Blob b = test::make_blob({{"x", F::FLOAT32}, {"y", F::FLOAT32}, {"z", F::FLOAT32},
                                  {"quality", F::FLOAT64}, {"rgb", F::UINT32}},
                                 n, 1, [](std::size_t i, std::size_t k, std::uint32_t) {
                                     return k == 0 ? i * 0.01 : k == 3 ? i * 1.5 : k == 4 ? 0.0 : 0.0;
                                 });
    for (std::size_t i = 0; i < n; ++i) {
        test::set_bits(b, i, 4, i % 2 ? 0xFFFFFFu : 0x101010u);
    }
    return b;
}

TEST(Steps, FiltersKeepUnknownFieldsBitForBit) {
    const io::Blob in = line_cloud(10);
    const Step s = apply_color_filter(in, {.min_mean = 0.5});
    ASSERT_EQ(s.blob.size(), 5u);
    EXPECT_EQ(s.blob.cloud.fields.size(), in.cloud.fields.size());
    for (std::size_t j = 0; j < 5; ++j) {  // kept points are 1, 3, 5, 7, 9
        EXPECT_EQ(0, std::memcmp(&s.blob.cloud.data[j * in.cloud.point_step],
                                 &in.cloud.data[(2 * j + 1) * in.cloud.point_step], in.cloud.point_step));
    }
}

TEST(Steps, ColourFilterOnACloudWithoutColourIsAnError) {
    EXPECT_THROW((void)apply_color_filter(test::random_xyz(3), {.min_mean = 0.5}), IoError);
}

TEST(Steps, DbscanAddsALabelFieldAndKnnCanMark) {
    const io::Blob in = line_cloud(20);
    const Step d = apply_dbscan(in, {.eps = 0.015, .min_points = 2});
    const auto labels = io::labels(d.blob);
    EXPECT_EQ(labels, std::vector<std::uint32_t>(20, 1));
    const Step m = apply_knn_outlier(in, {.k = 2}, {.mark_field = "outlier"});
    EXPECT_EQ(m.blob.size(), 20u);
    EXPECT_NE(io::find_field(m.blob, "outlier"), nullptr);
}

TEST(Steps, EmptyCloudFlowsThroughTheWholeChain) {
    const ChainResult r = run_chain(line_cloud(0), preset("paper-dense"));
    EXPECT_EQ(r.labelled.size(), 0u);
    EXPECT_NE(io::find_field(r.labelled, "label"), nullptr);
}

}  // namespace
}  // namespace pc::pipeline
