#include <cmath>

#include <limits>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/io/blob.h>

#include "support/synthetic.h"

namespace pc::io {
namespace {

using F = pcl::PCLPointField;

TEST(Blob, SelectKeepsEveryFieldInIndexOrder) {
    const Blob b = test::make_blob({{"x", F::FLOAT32}, {"id", F::UINT16}}, 5, 1,
                                   [](std::size_t i, std::size_t k, std::uint32_t) {
                                       return k == 0 ? i * 0.5 : i + 100.0;
                                   });
    const std::vector<std::uint32_t> idx = {4, 0, 2};
    const Blob s = select(b, idx);
    ASSERT_EQ(s.size(), 3u);
    EXPECT_EQ(s.cloud.fields.size(), 2u);
    for (std::size_t j = 0; j < idx.size(); ++j) {
        EXPECT_EQ(0, std::memcmp(&s.cloud.data[j * s.cloud.point_step],
                                 &b.cloud.data[idx[j] * b.cloud.point_step], b.cloud.point_step));
    }
}

TEST(Blob, SelectRejectsOutOfRangeIndex) {
    const Blob b = test::random_xyz(3);
    const std::vector<std::uint32_t> idx = {3};
    EXPECT_THROW((void)select(b, idx), Error);
}

TEST(Blob, WithFieldAppendsThenOverwritesInPlace) {
    const Blob b = test::random_xyz(4);
    const std::vector<std::uint32_t> a = {1, 2, 3, 4}, c = {9, 8, 7, 6};
    const Blob once = with_field(b, "label", a);
    ASSERT_NE(find_field(once, "label"), nullptr);
    EXPECT_EQ(once.cloud.point_step, b.cloud.point_step + 4);
    const Blob twice = with_field(once, "label", c);
    EXPECT_EQ(twice.cloud.fields.size(), once.cloud.fields.size());
    const auto* f = find_field(twice, "label");
    EXPECT_EQ(f->datatype, F::UINT32);
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(value_as_double(&twice.cloud.data[i * twice.cloud.point_step + f->offset],
                                  f->datatype),
                  c[i]);
    }
}

TEST(Blob, WithFieldReplacesFieldOfAnotherType) {
    const Blob b = test::make_blob({{"x", F::FLOAT32}, {"label", F::INT16}, {"y", F::FLOAT32}}, 2,
                                   1, [](auto...) { return 1.0; });
    const std::vector<std::uint32_t> v = {5, 6};
    const Blob out = with_field(b, "label", v);
    EXPECT_EQ(out.cloud.fields.size(), 3u);
    EXPECT_EQ(find_field(out, "label")->datatype, F::UINT32);
    EXPECT_NE(find_field(out, "y"), nullptr);
}

TEST(Blob, IsDenseFollowsEveryFloatField) {
    Blob b = test::make_blob({{"x", F::FLOAT32}, {"i", F::FLOAT64}}, 3, 1, [](auto...) { return 1.0; });
    update_is_dense(b);
    EXPECT_TRUE(b.cloud.is_dense);
    const double nan = std::nan("");
    std::memcpy(&b.cloud.data[2 * b.cloud.point_step + 4], &nan, 8);
    update_is_dense(b);
    EXPECT_FALSE(b.cloud.is_dense);
}

TEST(Blob, IsDenseSeesAnInfinityFarIntoTheCloud) {
    // Past the first block of points the check works on; -Inf in a float32 element.
    Blob b = test::make_blob({{"x", F::FLOAT32}, {"y", F::FLOAT32}}, 9000, 1, [](auto...) { return 0.5; });
    update_is_dense(b);
    EXPECT_TRUE(b.cloud.is_dense);
    const float inf = -std::numeric_limits<float>::infinity();
    std::memcpy(&b.cloud.data[8999 * b.cloud.point_step + 4], &inf, 4);
    update_is_dense(b);
    EXPECT_FALSE(b.cloud.is_dense);
}

}  // namespace
}  // namespace pc::io
